#include "strahl/geometry/parametric_tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "double_box.h"
#include "strahl/core/error.h"
#include "strahl/core/transform.h"

namespace strahl {

namespace {

using geometry_detail::isFiniteD;

// Border vertices closer than this fraction of the surface's extent are one
// vertex. Rounding makes the two sides of a seam differ by ~1e-16 relative;
// distinct grid points are ~1e-4 apart even at the segment cap.
constexpr double kWeldFraction = 1e-9;

// Spatial hash for welding: a cell as large as the tolerance, so two points
// within it lie in the same or neighbouring cells.
class Welder {
public:
    explicit Welder(double tolerance) : tolerance_(tolerance) {}

    // The first point registered within the tolerance of p, or p itself.
    DVec3 weld(const DVec3& p) {
        const std::array<int64_t, 3> key = cellOf(p);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const auto found = cells_.find(hash({key[0] + dx, key[1] + dy, key[2] + dz}));
                    if (found == cells_.end()) continue;
                    for (const DVec3& q : found->second)
                        if (glm::length(q - p) <= tolerance_) return q;
                }
        cells_[hash(key)].push_back(p);
        return p;
    }

private:
    std::array<int64_t, 3> cellOf(const DVec3& p) const {
        return {static_cast<int64_t>(std::floor(p.x / tolerance_)),
                static_cast<int64_t>(std::floor(p.y / tolerance_)),
                static_cast<int64_t>(std::floor(p.z / tolerance_))};
    }
    static uint64_t hash(const std::array<int64_t, 3>& k) {
        // Distinct cells may share a hash: the bucket holds points, compared exactly.
        return static_cast<uint64_t>(k[0]) * 0x9E3779B97F4A7C15ull ^
               static_cast<uint64_t>(k[1]) * 0xC2B2AE3D27D4EB4Full ^
               static_cast<uint64_t>(k[2]) * 0x165667B19E3779F9ull;
    }
    double tolerance_;
    std::unordered_map<uint64_t, std::vector<DVec3>> cells_;
};

}  // namespace

Tessellation tessellateParametric(const ParametricSurface& surface, const ParametricGrid& grid,
                                  ParametricNormals normals) {
    Tessellation out;
    // Grid points of every patch, in double, before welding.
    std::vector<std::vector<DVec3>> points(grid.patches.size());
    DVec3 lo(num::kInf), hi(-num::kInf);
    for (uint32_t p = 0; p < grid.patches.size(); ++p) {
        const PatchGrid& g = grid.patches[p];
        points[p].reserve(g.u.size() * g.v.size());
        for (const double v : g.v)
            for (const double u : g.u) {
                const DVec3 x = surface.point(p, u, v);
                if (!isFiniteD(x))
                    fail(surface.describe(), ": not finite at (u, v) = (", u, ", ", v, ")");
                points[p].push_back(x);
                lo = glm::min(lo, x);
                hi = glm::max(hi, x);
            }
    }
    Welder welder(kWeldFraction * std::max(glm::length(hi - lo), 1e-300));

    size_t vertices = 0, triangles = 0;
    for (const PatchGrid& g : grid.patches) {
        vertices += g.u.size() * g.v.size();
        triangles += 2 * g.cellCount();
    }
    TriangleMesh& mesh = out.mesh;
    mesh.positions.reserve(vertices + 1);  // + 1: Embree's padding (triangle_mesh.h)
    mesh.indices.reserve(3 * triangles);
    out.params.reserve(vertices);
    if (normals == ParametricNormals::Interpolated) mesh.normals.reserve(vertices);
    out.patchFirstTriangle.reserve(grid.patches.size() + 1);

    for (uint32_t p = 0; p < grid.patches.size(); ++p) {
        out.patchFirstTriangle.push_back(static_cast<uint32_t>(mesh.triangleCount()));
        const PatchGrid& g = grid.patches[p];
        const size_t nu = g.u.size(), nv = g.v.size();
        const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
        for (size_t j = 0; j < nv; ++j)
            for (size_t i = 0; i < nu; ++i) {
                DVec3 x = points[p][j * nu + i];
                if (i == 0 || j == 0 || i + 1 == nu || j + 1 == nv) x = welder.weld(x);
                mesh.positions.push_back(Vec3(x));
                out.params.push_back(Vec2(static_cast<float>(g.u[i]), static_cast<float>(g.v[j])));
                if (normals == ParametricNormals::Interpolated)
                    mesh.normals.push_back(Vec3(surface.normal(p, g.u[i], g.v[j])));
            }
        auto index = [&](size_t i, size_t j) { return base + static_cast<uint32_t>(j * nu + i); };
        auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
            const Vec3 &pa = mesh.positions[a], &pb = mesh.positions[b], &pc = mesh.positions[c];
            if (pa == pb || pb == pc || pa == pc) return;  // collapsed at a pole
            mesh.indices.insert(mesh.indices.end(), {a, b, c});
        };
        for (size_t j = 0; j + 1 < nv; ++j)
            for (size_t i = 0; i + 1 < nu; ++i) {
                // Counter-clockwise in (u, v) so the winding normal follows ∂u f × ∂v f.
                const uint32_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1),
                               d = index(i, j + 1);
                const float ac = glm::length(mesh.positions[a] - mesh.positions[c]);
                const float bd = glm::length(mesh.positions[b] - mesh.positions[d]);
                if (ac <= bd) {
                    emit(a, b, c);
                    emit(a, c, d);
                } else {
                    emit(a, b, d);
                    emit(b, c, d);
                }
            }
    }
    out.patchFirstTriangle.push_back(static_cast<uint32_t>(mesh.triangleCount()));
    if (mesh.triangleCount() == 0) fail(surface.describe(), ": the tessellation has no triangles");
    return out;
}

TessellatedSurface::TessellatedSurface(ParametricSurfacePtr surface, Tessellation&& tessellation,
                                       const Mat4& objectToWorld, ParametricNormals normals, bool flipNormals)
    : surface_(std::move(surface)),
      params_(std::move(tessellation.params)),
      patchFirstTriangle_(std::move(tessellation.patchFirstTriangle)),
      linearToWorld_(glm::dmat3(Mat3(objectToWorld))),
      // A flipped front negates every exact normal.
      normalToWorld_(flipNormals ? -normalMatrix(objectToWorld) : normalMatrix(objectToWorld)),
      normals_(normals) {}

uint32_t TessellatedSurface::patchOf(uint32_t prim) const {
    const auto it = std::upper_bound(patchFirstTriangle_.begin(), patchFirstTriangle_.end(), prim);
    return static_cast<uint32_t>(it - patchFirstTriangle_.begin() - 1);
}

Vec2 TessellatedSurface::parameters(const TriangleMesh& worldMesh, uint32_t prim, float b1,
                                    float b2) const {
    const uint32_t* tri = &worldMesh.indices[3 * size_t(prim)];
    const float b0 = 1.0f - b1 - b2;
    return b0 * params_[tri[0]] + b1 * params_[tri[1]] + b2 * params_[tri[2]];
}

SurfaceInteraction TessellatedSurface::interaction(const TriangleMesh& worldMesh, uint32_t prim,
                                                   float b1, float b2) const {
    SurfaceInteraction si = triangleInteraction(worldMesh, prim, b1, b2);
    const Vec2 uv = parameters(worldMesh, prim, b1, b2);
    const uint32_t patch = patchOf(prim);
    // One evaluation of the partials serves the exact normal and the texture
    // frame; normal() evaluates again only at a singular point (a pole).
    const SurfacePoint s = surface_->partials(patch, uv.x, uv.y);
    if (normals_ == ParametricNormals::Exact) {
        const std::optional<DVec3> regular = ParametricSurface::regularNormal(s);
        const DVec3 n = regular ? *regular : surface_->normal(patch, uv.x, uv.y);
        const Vec3 world = normalToWorld_ * Vec3(n);
        const float len = glm::length(world);
        if (len > 0.0f && std::isfinite(len)) {
            si.Ns = world / len;
            if (glm::dot(si.Ng, si.Ns) < 0.0f) si.Ng = -si.Ng;
        }
    }
    // The mesh is in world space, so tangents are mapped by objectToWorld's
    // linear part.
    surface_->setTextureFrame(si, s, uv.x, uv.y, linearToWorld_);
    return si;
}

size_t TessellatedSurface::memoryBytes() const {
    return sizeof(*this) + params_.capacity() * sizeof(Vec2) +
           patchFirstTriangle_.capacity() * sizeof(uint32_t);
}

}  // namespace strahl
