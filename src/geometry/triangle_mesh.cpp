#include "strahl/geometry/triangle_mesh.h"

#include <cmath>

#include "strahl/core/error.h"
#include "strahl/core/motion.h"
#include "strahl/core/ray.h"

namespace strahl {

Bounds3 TriangleMesh::bounds() const {
    Bounds3 b;
    for (const Vec3& p : positions) b.expand(p);
    // Each vertex moves on straight segments between its keyframes.
    for (const std::vector<Vec3>& key : laterPositions)
        for (const Vec3& p : key) b.expand(p);
    return b;
}

Vec3 TriangleMesh::positionAt(uint32_t vertex, float time) const {
    if (laterPositions.empty()) return positions[vertex];
    const KeyframeSegment s = keyframeSegment(keyframeCount(), time);
    const Vec3& a = keyframePositions(s.index)[vertex];
    const Vec3& b = keyframePositions(s.index + 1)[vertex];
    return (1.0f - s.fraction) * a + s.fraction * b;
}

size_t TriangleMesh::memoryBytes() const {
    size_t attributeBytes = 0;
    for (const MeshAttribute& a : attributes) attributeBytes += a.values.capacity() * sizeof(float);
    size_t keyframeBytes = 0;
    for (const std::vector<Vec3>& key : laterPositions) keyframeBytes += key.capacity() * sizeof(Vec3);
    for (const std::vector<Vec3>& key : laterNormals) keyframeBytes += key.capacity() * sizeof(Vec3);
    return keyframeBytes + positions.capacity() * sizeof(Vec3) + normals.capacity() * sizeof(Vec3) +
           uvs.capacity() * sizeof(Vec2) + indices.capacity() * sizeof(uint32_t) +
           faceMaterials.capacity() * sizeof(uint32_t) + attributeBytes;
}

void TriangleMesh::transform(const Mat4& m) {
    for (Vec3& p : positions) p = Vec3(m * Vec4(p, 1.0f));
    for (std::vector<Vec3>& key : laterPositions)
        for (Vec3& p : key) p = Vec3(m * Vec4(p, 1.0f));
    const Mat3 normalMatrix = glm::transpose(glm::inverse(Mat3(m)));
    const auto transformNormals = [&](std::vector<Vec3>& list) {
        for (Vec3& n : list) {
            const Vec3 t = normalMatrix * n;
            const float len = glm::length(t);
            n = len > 0.0f ? t / len : t;
        }
    };
    transformNormals(normals);
    for (std::vector<Vec3>& key : laterNormals) transformNormals(key);
    // A mirroring transform flips the winding order relative to the normals;
    // swap two indices per triangle so front faces stay front faces.
    if (glm::determinant(Mat3(m)) < 0.0f) {
        for (size_t i = 0; i + 2 < indices.size(); i += 3) std::swap(indices[i + 1], indices[i + 2]);
    }
}

void TriangleMesh::validate(const std::string& source) const {
    if (indices.size() % 3 != 0)
        fail(source, ": index count ", indices.size(), " is not a multiple of 3");
    if (!normals.empty() && normals.size() != positions.size())
        fail(source, ": ", normals.size(), " normals for ", positions.size(), " vertices");
    if (!uvs.empty() && uvs.size() != positions.size())
        fail(source, ": ", uvs.size(), " texture coordinates for ", positions.size(), " vertices");
    if (!faceMaterials.empty() && faceMaterials.size() != triangleCount())
        fail(source, ": ", faceMaterials.size(), " face materials for ", triangleCount(),
             " triangles");
    for (const MeshAttribute& a : attributes) {
        const bool perFace = a.scope == MeshAttribute::Scope::Face;
        const size_t items = perFace ? triangleCount() : positions.size();
        if (a.channels < 1 || a.channels > 4 || a.values.size() != items * size_t(a.channels))
            fail(source, ": attribute '", a.name, "' has ", a.values.size(), " values for ", items,
                 perFace ? " triangles" : " vertices", " of ", a.channels, " channels");
    }
    for (size_t i = 0; i < positions.size(); ++i) {
        if (!isFinite(positions[i]))
            fail(source, ": vertex ", i, " has a non-finite coordinate (", positions[i].x, ", ",
                 positions[i].y, ", ", positions[i].z, ")");
    }
    if (keyframeCount() > kMaxKeyframes)
        fail(source, ": ", keyframeCount(), " keyframes of the positions (at most ", kMaxKeyframes, ")");
    for (size_t k = 0; k < laterPositions.size(); ++k) {
        const std::vector<Vec3>& key = laterPositions[k];
        if (key.size() != positions.size())
            fail(source, ": keyframe ", k + 1, " has ", key.size(), " positions for ", positions.size(), " vertices");
        for (size_t i = 0; i < key.size(); ++i)
            if (!isFinite(key[i]))
                fail(source, ": vertex ", i, " has a non-finite coordinate at keyframe ", k + 1, " (", key[i].x, ", ",
                     key[i].y, ", ", key[i].z, ")");
    }
    if (!laterNormals.empty()) {
        if (laterNormals.size() != laterPositions.size())
            fail(source, ": normals for ", laterNormals.size() + 1, " keyframes, positions for ", keyframeCount());
        for (size_t k = 0; k < laterNormals.size(); ++k)
            if (laterNormals[k].size() != positions.size())
                fail(source, ": keyframe ", k + 1, " has ", laterNormals[k].size(), " normals for ", positions.size(),
                     " vertices");
    }
    for (size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= positions.size())
            fail(source, ": triangle ", i / 3, " refers to vertex ", indices[i], " but there are only ",
                 positions.size(), " vertices");
    }
}

namespace {

// Angle-weighted vertex normals of the triangles `indices` over `positions`.
std::vector<Vec3> angleWeightedNormals(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices);

}  // namespace

void TriangleMesh::computeVertexNormals() {
    normals = angleWeightedNormals(positions, indices);
    laterNormals.clear();
    for (const std::vector<Vec3>& key : laterPositions) laterNormals.push_back(angleWeightedNormals(key, indices));
}

namespace {

std::vector<Vec3> angleWeightedNormals(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices) {
    std::vector<glm::dvec3> sum(positions.size(), glm::dvec3(0.0));
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const uint32_t v[3] = {indices[t], indices[t + 1], indices[t + 2]};
        const glm::dvec3 p[3] = {glm::dvec3(positions[v[0]]), glm::dvec3(positions[v[1]]),
                                 glm::dvec3(positions[v[2]])};
        const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double length = glm::length(n);
        if (!(length > 0.0)) continue;  // degenerate: no direction to give
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
            // The corner's angle, by atan2 (accurate also for tiny and obtuse angles).
            const double angle = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
            sum[v[k]] += angle * (n / length);
        }
    }
    std::vector<Vec3> normals(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        const double length = glm::length(sum[i]);
        normals[i] = length > 0.0 ? Vec3(sum[i] / length) : Vec3(0.0f, 0.0f, 1.0f);
    }
    return normals;
}

}  // namespace

void TriangleMesh::flipOrientation() {
    for (size_t t = 0; t + 2 < indices.size(); t += 3) std::swap(indices[t + 1], indices[t + 2]);
    for (Vec3& n : normals) n = -n;
    for (std::vector<Vec3>& key : laterNormals)
        for (Vec3& n : key) n = -n;
}

SurfaceInteraction triangleInteraction(const TriangleMesh& mesh, uint32_t prim, float u, float v, float time) {
    const uint32_t i0 = mesh.indices[3 * size_t(prim)];
    const uint32_t i1 = mesh.indices[3 * size_t(prim) + 1];
    const uint32_t i2 = mesh.indices[3 * size_t(prim) + 2];
    const bool deforms = mesh.deforms();
    const Vec3 p0 = deforms ? mesh.positionAt(i0, time) : mesh.positions[i0];
    const Vec3 p1 = deforms ? mesh.positionAt(i1, time) : mesh.positions[i1];
    const Vec3 p2 = deforms ? mesh.positionAt(i2, time) : mesh.positions[i2];
    const float b0 = 1.0f - u - v;

    SurfaceInteraction si;
    // Rebuild the point from barycentrics: its error is bounded by gamma(7) times
    // the sum of the absolute products (pbrt-v4 Triangle::InteractionFromIntersection),
    // whereas o + t*d would carry the error of t times the ray length. A
    // deforming mesh's vertices carry the rounding of their interpolation
    // (three more operations, as Embree's own).
    si.p = b0 * p0 + u * p1 + v * p2;
    si.pError = gammaBound(deforms ? 10 : 7) * (glm::abs(b0 * p0) + glm::abs(u * p1) + glm::abs(v * p2));

    Vec3 ng = glm::cross(p1 - p0, p2 - p0);
    const float len = glm::length(ng);
    si.Ng = len > 0.0f ? ng / len : Vec3(0.0f, 0.0f, 1.0f);  // degenerate: any unit normal

    si.Ns = si.Ng;
    if (!mesh.normals.empty()) {
        Vec3 n0 = mesh.normals[i0], n1 = mesh.normals[i1], n2 = mesh.normals[i2];
        if (deforms && !mesh.laterNormals.empty()) {
            const KeyframeSegment s = keyframeSegment(mesh.keyframeCount(), time);
            const auto at = [&](size_t k) -> const std::vector<Vec3>& {
                return k == 0 ? mesh.normals : mesh.laterNormals[k - 1];
            };
            const auto blend = [&](uint32_t i) {
                return (1.0f - s.fraction) * at(s.index)[i] + s.fraction * at(s.index + 1)[i];
            };
            n0 = blend(i0);
            n1 = blend(i1);
            n2 = blend(i2);
        }
        const Vec3 ns = b0 * n0 + u * n1 + v * n2;
        const float nsLen = glm::length(ns);
        if (nsLen > 0.0f && std::isfinite(nsLen)) {
            si.Ns = ns / nsLen;
            // Keep the geometric normal on the side the artist's normals point to.
            if (glm::dot(si.Ng, si.Ns) < 0.0f) si.Ng = -si.Ng;
        }
    }
    if (!mesh.uvs.empty()) {
        const Vec2 &t0 = mesh.uvs[i0], &t1 = mesh.uvs[i1], &t2 = mesh.uvs[i2];
        si.uv = b0 * t0 + u * t1 + v * t2;
        // dp/du and dp/dv from the two edge equations dp_k = dpdu du_k + dpdv dv_k
        // (pbrt-v4 Triangle::InteractionFromIntersection), solved by Cramer's
        // rule; a degenerate uv mapping leaves them zero.
        const Vec2 duv02 = t0 - t2, duv12 = t1 - t2;
        const Vec3 dp02 = p0 - p2, dp12 = p1 - p2;
        const float det = duv02.x * duv12.y - duv02.y * duv12.x;
        if (std::abs(det) > 1e-12f) {
            const Vec3 dpdu = (duv12.y * dp02 - duv02.y * dp12) / det;
            const Vec3 dpdv = (duv02.x * dp12 - duv12.x * dp02) / det;
            if (isFinite(dpdu)) si.dpdu = dpdu;
            if (isFinite(dpdv)) si.dpdv = dpdv;
        }
        // Texture footprints: sqrt(uv area / world area) converts a world width
        // into uv units (isotropic average over the triangle).
        if (len > 0.0f) si.uvDensity = std::sqrt(0.5f * std::abs(det) / (0.5f * len));
    } else {
        si.uv = Vec2(u, v);
    }
    si.materialSlot = mesh.faceMaterials.empty() ? 0u : mesh.faceMaterials[prim];
    if (!mesh.attributes.empty()) si.attributes = {&mesh, prim, Vec2(u, v)};
    return si;
}

}  // namespace strahl
