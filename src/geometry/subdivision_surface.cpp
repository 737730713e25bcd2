// SubdivisionSurface (subdivision_surface.h): the refined limit surface as a
// triangle soup per control face for the naive tracer, and as tables of
// normals, uvs and displacement offsets that shading and Embree's
// displacement callback look up by face parameters.
//
// Looking up (face, u, v): a quad face's [0,1]² is a grid of m × m cells, m =
// 2^levels; a face of n ≠ 4 vertices has n sub-quads of m/2 × m/2 cells each,
// found from Embree's encoding (catmull_clark.h). Every cell is one refined
// quad; its corners' own parameters say which cell corner each is, whatever
// the quad's vertex order (children of different corners are rotated).

#include "strahl/geometry/subdivision_surface.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/glm.hpp>

#include "double_box.h"
#include "double_triangle.h"
#include "strahl/core/error.h"

namespace strahl {

namespace {

// A face parameter pair decoded into its sub-quad (0 for a quad face) and
// the position (s, t) ∈ [0,1]² within it.
struct SubFacePoint {
    uint32_t sub = 0;
    double s = 0.0, t = 0.0;
};

SubFacePoint decode(uint32_t faceSize, double u, double v) {
    SubFacePoint p;
    if (faceSize == 4) {
        p.s = std::clamp(u, 0.0, 1.0);
        p.t = std::clamp(v, 0.0, 1.0);
        return p;
    }
    // Sub-quad (l, h) covers u ∈ 2l + [1/2, 3/2], v ∈ 2h + [1/2, 3/2]; the
    // gaps between are never reported, so rounding (u − 1)/2 finds l.
    const uint32_t l = uint32_t(std::clamp(std::round((u - 1.0) / 2.0), 0.0, 3.0));
    const uint32_t h = uint32_t(std::clamp(std::round((v - 1.0) / 2.0), 0.0, 3.0));
    p.sub = std::min(4 * h + l, faceSize - 1);
    p.s = std::clamp(u - 2.0 * double(p.sub % 4) - 0.5, 0.0, 1.0);
    p.t = std::clamp(v - 2.0 * double(p.sub / 4) - 0.5, 0.0, 1.0);
    return p;
}

Vec3 down(const DVec3& p) { return Vec3(p); }

}  // namespace

SubdivisionSurface::SubdivisionSurface(SubdivisionDesc desc) : desc_(std::move(desc)) {
    const std::string& name = desc_.name;
    refined_ = refineCatmullClark(desc_.cage, desc_.levels, name);
    points_ = std::move(refined_.positions);  // displaced in place below
    if (desc_.displacement) {
        // Unit normals per refined vertex over all its quads, creases or not,
        // so that a displaced crease stays closed.
        std::vector<DVec3> vertexNormal(points_.size(), DVec3(0.0));
        for (const auto& q : refined_.quads) {
            const DVec3 n = glm::cross(points_[q[2]] - points_[q[0]], points_[q[3]] - points_[q[1]]);
            for (uint32_t v : q) vertexNormal[v] += n;
        }
        offsets_.assign(points_.size(), DVec3(0.0));
        for (size_t v = 0; v < points_.size(); ++v) {
            const double len = glm::length(vertexNormal[v]);
            if (len == 0.0) continue;  // a vertex no face uses (holes)
            const DVec3 n = vertexNormal[v] / len;
            const DVec2 uv = refined_.uvs.empty() ? DVec2(0.0) : refined_.uvs[v];
            const double h = desc_.displacement(points_[v], n, uv);
            if (!std::isfinite(h))
                fail(name, ": the displacement is ", h, " at (", points_[v].x, ", ", points_[v].y, ", ",
                     points_[v].z, ")");
            offsets_[v] = h * n;
            points_[v] += offsets_[v];
        }
    }
    const auto normals = cornerNormals(refined_, points_);
    normals_.resize(normals.size());
    for (size_t q = 0; q < normals.size(); ++q)
        for (int i = 0; i < 4; ++i) normals_[q][i] = Vec3(normals[q][i]);

    const size_t faces = desc_.cage.faceSizes.size();
    faceFirstQuad_.assign(faces + 1, 0);
    for (uint32_t f : refined_.quadFace) ++faceFirstQuad_[f + 1];
    for (size_t f = 0; f < faces; ++f) faceFirstQuad_[f + 1] += faceFirstQuad_[f];
    faceCellStart_.assign(faces + 1, 0);
    for (size_t f = 0; f < faces; ++f) faceCellStart_[f + 1] = faceCellStart_[f] + (faceFirstQuad_[f + 1] - faceFirstQuad_[f]);
    cells_.assign(faceCellStart_.back(), 0);
    firstCorner_.assign(refined_.quads.size(), 0);
    quadCell_.assign(refined_.quads.size(), 0);
    faceBounds_.assign(faces, Bounds3{});
    const uint32_t fullSide = 1u << desc_.levels;
    for (uint32_t q = 0; q < refined_.quads.size(); ++q) {
        const uint32_t f = refined_.quadFace[q], n = desc_.cage.faceSizes[f];
        const uint32_t m = n == 4 ? fullSide : fullSide / 2;
        double sMin = 1.0, tMin = 1.0;
        uint32_t sub = 0;
        for (const DVec2& p : refined_.quadParams[q]) {
            const SubFacePoint c = decode(n, p.x, p.y);
            sMin = std::min(sMin, c.s);
            tMin = std::min(tMin, c.t);
            sub = c.sub;
        }
        const uint32_t i = std::min(uint32_t(std::lround(sMin * m)), m - 1);
        const uint32_t j = std::min(uint32_t(std::lround(tMin * m)), m - 1);
        cells_[faceCellStart_[f] + (sub * m + j) * m + i] = q;
        quadCell_[q] = (sub * m + j) * m + i;
        for (int c = 0; c < 4; ++c) {
            const SubFacePoint cp = decode(n, refined_.quadParams[q][c].x, refined_.quadParams[q][c].y);
            if (cp.s == sMin && cp.t == tMin) firstCorner_[q] = uint8_t(c);
        }
        for (uint32_t v : refined_.quads[q]) faceBounds_[f].expand(down(points_[v]));
    }
    // Widen by float rounding of the double points, and give holes (no
    // quads) the box of their control polygon so every face has one.
    size_t first = 0;
    for (size_t f = 0; f < faces; ++f) {
        Bounds3& b = faceBounds_[f];
        if (b.empty())
            for (uint32_t k = 0; k < desc_.cage.faceSizes[f]; ++k) b.expand(down(desc_.cage.positions[desc_.cage.indices[first + k]]));
        const Vec3 pad = (glm::abs(b.min) + glm::abs(b.max)) * 0x1p-20f;
        b.min -= pad;
        b.max += pad;
        first += desc_.cage.faceSizes[f];
    }
    // The corners' parameters and normal groups are in the tables now.
    refined_.quadParams = {};
    refined_.cornerGroup = {};
}

DVec2 SubdivisionSurface::cornerParam(uint32_t face, uint32_t quad, int corner) const noexcept {
    // Counter-clockwise from the cell's (0, 0) corner: (0,0), (1,0), (1,1), (0,1).
    static constexpr int kDx[4] = {0, 1, 1, 0}, kDy[4] = {0, 0, 1, 1};
    const uint32_t n = desc_.cage.faceSizes[face];
    const uint32_t m = n == 4 ? (1u << desc_.levels) : (1u << (desc_.levels - 1));
    const uint32_t cell = quadCell_[quad], sub = cell / (m * m), j = (cell / m) % m, i = cell % m;
    const int k = (corner - firstCorner_[quad] + 4) % 4;
    const double s = double(i + uint32_t(kDx[k])) / m, t = double(j + uint32_t(kDy[k])) / m;
    if (n == 4) return DVec2(s, t);
    return DVec2(2.0 * double(sub % 4) + 0.5 + s, 2.0 * double(sub / 4) + 0.5 + t);
}

bool SubdivisionSurface::locate(uint32_t face, double u, double v, uint32_t& quad, std::array<double, 4>& weights,
                                std::array<double, 4>* dWeightsDu, std::array<double, 4>* dWeightsDv) const noexcept {
    if (face >= primitiveCount() || faceFirstQuad_[face] == faceFirstQuad_[face + 1]) return false;
    const uint32_t n = desc_.cage.faceSizes[face];
    const uint32_t m = n == 4 ? (1u << desc_.levels) : (1u << (desc_.levels - 1));
    const SubFacePoint p = decode(n, u, v);
    const uint32_t i = std::min(uint32_t(p.s * m), m - 1), j = std::min(uint32_t(p.t * m), m - 1);
    quad = cells_[faceCellStart_[face] + (p.sub * m + j) * m + i];
    const double fs = p.s * m - i, ft = p.t * m - j;
    for (int c = 0; c < 4; ++c) {
        const int k = (c - firstCorner_[quad] + 4) % 4;  // 0 … 3: (0,0), (1,0), (1,1), (0,1) of the cell
        const bool right = k == 1 || k == 2, top = k >= 2;
        const double ws = right ? fs : 1.0 - fs, wt = top ? ft : 1.0 - ft;
        weights[c] = ws * wt;
        if (dWeightsDu) (*dWeightsDu)[c] = (right ? 1.0 : -1.0) * wt * m;
        if (dWeightsDv) (*dWeightsDv)[c] = (top ? 1.0 : -1.0) * ws * m;
    }
    return true;
}

Bounds3 SubdivisionSurface::primitiveBounds(uint32_t face) const { return faceBounds_[face]; }

bool SubdivisionSurface::intersect(const Ray& ray, uint32_t face, Hit& hit) const noexcept {
    const DVec3 o(ray.origin), d(ray.dir);
    double t0 = ray.tnear, t1 = ray.tfar;
    const Bounds3& box = faceBounds_[face];
    if (!geometry_detail::clipToBox(o, d, DVec3(box.min), DVec3(box.max), t0, t1)) return false;
    double best = double(ray.tfar);
    bool found = false;
    for (uint32_t q = faceFirstQuad_[face]; q < faceFirstQuad_[face + 1]; ++q) {
        const auto& v = refined_.quads[q];
        const int c00 = firstCorner_[q];
        for (int tri = 0; tri < 2; ++tri) {
            // The cell (c00, c10, c11, c01) as the triangles (c00, c10, c01)
            // and (c10, c11, c01): split along the diagonal from (1, 0) to
            // (0, 1), as Embree splits its grids.
            const int ia = tri == 0 ? c00 : (c00 + 1) % 4, ib = tri == 0 ? (c00 + 1) % 4 : (c00 + 2) % 4,
                      ic = (c00 + 3) % 4;
            double t, b1, b2;
            if (!geometry_detail::rayTriangle(o, d, points_[v[ia]], points_[v[ib]], points_[v[ic]], t, b1, b2)) continue;
            if (!(t > double(ray.tnear) && t < best)) continue;
            best = t;
            found = true;
            const DVec2 uv = (1.0 - b1 - b2) * cornerParam(face, q, ia) + b1 * cornerParam(face, q, ib) +
                             b2 * cornerParam(face, q, ic);
            hit.t = float(t);
            hit.u = float(uv.x);
            hit.v = float(uv.y);
            hit.Ng = Vec3(glm::cross(points_[v[ib]] - points_[v[ia]], points_[v[ic]] - points_[v[ia]]));
        }
    }
    // float(t) may round to tfar itself: the accelerator's interval is open.
    if (found && !(hit.t < ray.tfar)) hit.t = std::nextafter(ray.tfar, 0.0f);
    return found;
}

SurfaceInteraction SubdivisionSurface::interaction(const Ray& ray, const Hit& hit) const {
    SurfaceInteraction si;
    const DVec3 x = DVec3(ray.origin) + double(hit.t) * DVec3(ray.dir);
    si.p = Vec3(x);
    // The hit lies on a float triangle of the tessellation (Embree's or the
    // reference's): bound its error by 2^-17 of the coordinates' scale, well
    // above the rounding of a float triangle test.
    const double scale = std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    si.pError = Vec3(float(scale * 0x1p-17));
    uint32_t quad = 0;
    std::array<double, 4> w{}, dwdu{}, dwdv{};
    DVec3 Ns(0.0), dpdu(0.0), dpdv(0.0);
    DVec2 uv(hit.u, hit.v);
    if (locate(hit.primID, hit.u, hit.v, quad, w, &dwdu, &dwdv)) {
        const auto& v = refined_.quads[quad];
        for (int c = 0; c < 4; ++c) {
            Ns += w[c] * DVec3(normals_[quad][c]);
            dpdu += dwdu[c] * points_[v[c]];
            dpdv += dwdv[c] * points_[v[c]];
        }
        if (!refined_.uvs.empty()) {
            DVec2 duvdu(0.0), duvdv(0.0);
            uv = DVec2(0.0);
            for (int c = 0; c < 4; ++c) {
                uv += w[c] * refined_.uvs[v[c]];
                duvdu += dwdu[c] * refined_.uvs[v[c]];
                duvdv += dwdv[c] * refined_.uvs[v[c]];
            }
            // Tangents along the texture's u and v: invert the Jacobian of
            // (face u, v) → texture uv.
            const double det = duvdu.x * duvdv.y - duvdu.y * duvdv.x;
            if (std::abs(det) > 1e-300) {
                const DVec3 pu = (duvdv.y * dpdu - duvdu.y * dpdv) / det;
                const DVec3 pv = (-duvdv.x * dpdu + duvdu.x * dpdv) / det;
                dpdu = pu;
                dpdv = pv;
            } else {
                dpdu = dpdv = DVec3(0.0);
            }
        }
    }
    DVec3 Ng(hit.Ng);
    const double ngLength = glm::length(Ng);
    const double nsLength = glm::length(Ns);
    Ns = nsLength > 0.0 ? Ns / nsLength : DVec3(0.0, 0.0, 1.0);
    Ng = ngLength > 0.0 ? Ng / ngLength : Ns;
    if (glm::dot(Ns, Ng) < 0.0) Ns = -Ns;
    si.Ng = Vec3(Ng);
    si.Ns = Vec3(Ns);
    si.uv = Vec2(uv);
    si.dpdu = Vec3(dpdu);
    si.dpdv = Vec3(dpdv);
    return si;
}

DVec3 SubdivisionSurface::displacementAt(uint32_t face, float u, float v) const noexcept {
    uint32_t quad = 0;
    std::array<double, 4> w{};
    if (offsets_.empty() || !locate(face, u, v, quad, w)) return DVec3(0.0);
    DVec3 sum(0.0);
    for (int c = 0; c < 4; ++c) sum += w[c] * offsets_[refined_.quads[quad][c]];
    return sum;
}

DVec3 SubdivisionSurface::pointAt(uint32_t face, float u, float v) const noexcept {
    uint32_t quad = 0;
    std::array<double, 4> w{};
    if (!locate(face, u, v, quad, w)) return DVec3(0.0);
    DVec3 sum(0.0);
    for (int c = 0; c < 4; ++c) sum += w[c] * points_[refined_.quads[quad][c]];
    return sum;
}

std::string SubdivisionSurface::describe() const {
    std::ostringstream s;
    const SubdivisionCage& c = desc_.cage;
    s << "subdivision surface: " << c.faceSizes.size() << " faces";
    if (!c.holes.empty()) s << " (" << c.holes.size() << " holes)";
    s << ", " << desc_.levels << " levels (";
    if (!desc_.levelsText.empty()) s << desc_.levelsText << ", ";
    s << tessellationRate() << " segments per edge, "
      << refined_.quads.size() << " quads)";
    if (!c.creaseWeights.empty()) s << ", " << c.creaseWeights.size() << " creases";
    if (!c.cornerWeights.empty()) s << ", " << c.cornerWeights.size() << " corners";
    s << ", boundary " << subdivisionBoundaryName(c.boundary);
    if (displaced()) s << ", displaced by " << desc_.displacementText;
    return s.str();
}

size_t SubdivisionSurface::memoryBytes() const {
    return points_.size() * sizeof(DVec3) + offsets_.size() * sizeof(DVec3) + refined_.uvs.size() * sizeof(DVec2) +
           refined_.quads.size() * (sizeof(refined_.quads[0]) + sizeof(uint32_t) + sizeof(normals_[0]) +
                                    sizeof(quadCell_[0]) + sizeof(firstCorner_[0])) +
           cells_.size() * sizeof(uint32_t) + faceBounds_.size() * sizeof(Bounds3) +
           (faceFirstQuad_.size() + faceCellStart_.size()) * sizeof(uint32_t);
}

}  // namespace strahl
