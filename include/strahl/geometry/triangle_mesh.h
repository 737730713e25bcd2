#pragma once
// TriangleMesh: indexed triangles with optional per-vertex normals and UVs, an
// optional per-triangle material slot and named vertex or face attributes.
// Pure data and math, no Embree.

#include <cstdint>
#include <string>
#include <vector>

#include "strahl/core/bounds.h"
#include "strahl/core/math.h"
#include "strahl/geometry/mesh_attribute.h"
#include "strahl/geometry/surface_interaction.h"

namespace strahl {

struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;    // empty, or one per position
    std::vector<Vec2> uvs;        // empty, or one per position
    std::vector<uint32_t> indices;  // three per triangle, counter-clockwise = front
    std::vector<uint32_t> faceMaterials;  // empty, or one slot per triangle
    std::vector<MeshAttribute> attributes;  // what textures may read (mesh_attribute.h)
    // A deforming mesh: its positions at further keyframes, one list per
    // keyframe and one position per vertex; `positions` is the first. With K
    // keyframes in all, keyframe k is the mesh at frame time k / (K − 1),
    // linearly between (core/motion.h, as Embree interpolates vertex time
    // steps). Empty: at rest. Shading normals, if any, follow the same
    // keyframes: `laterNormals` holds them for the later ones.
    std::vector<std::vector<Vec3>> laterPositions;
    std::vector<std::vector<Vec3>> laterNormals;

    size_t triangleCount() const { return indices.size() / 3; }
    size_t vertexCount() const { return positions.size(); }
    bool deforms() const { return !laterPositions.empty(); }
    size_t keyframeCount() const { return 1 + laterPositions.size(); }
    const std::vector<Vec3>& keyframePositions(size_t k) const { return k == 0 ? positions : laterPositions[k - 1]; }
    // Vertex `vertex` at frame time `time` (its position, at rest).
    Vec3 positionAt(uint32_t vertex, float time) const;
    Bounds3 bounds() const;
    size_t memoryBytes() const;

    // Bounds over every keyframe. Applies an affine transform (every keyframe):
    // positions by m, normals by its inverse transpose.
    void transform(const Mat4& m);

    // Sets one shading normal per vertex: the mean of the unit normals of the
    // triangles around it, each weighted by its angle at the vertex (Thürmer
    // and Wüthrich 1998, as Mitsuba computes the normals a file lacks), so the
    // result does not depend on how a face is split into triangles. A vertex
    // of degenerate triangles only gets +z. Call after validate().
    void computeVertexNormals();

    // Turns the surface's front around: every triangle's winding reversed
    // (the counter-clockwise side, which one-sided emitters light, is the
    // other) and every shading normal negated.
    void flipOrientation();

    // Throws strahl::Error naming `source` on a NaN/Inf coordinate, an index out
    // of range, or attribute arrays whose sizes disagree with the positions
    // (or, for face attributes, the triangles), or keyframes that do (more
    // than kMaxKeyframes in all, core/motion.h).
    void validate(const std::string& source) const;

    // Embree reads vertex buffers with 16-byte loads, so a buffer shared with it
    // needs readable memory behind the last vertex: reserve one spare element.
    void reservePadding() {
        positions.reserve(positions.size() + 1);
        for (std::vector<Vec3>& key : laterPositions) key.reserve(key.size() + 1);
    }
    bool isPadded() const {
        for (const std::vector<Vec3>& key : laterPositions)
            if (key.capacity() <= key.size()) return false;
        return positions.capacity() > positions.size();
    }
};

// Interaction on triangle `prim` at Embree barycentrics (u, v), at frame
// time `time` (which only a deforming mesh depends on).
SurfaceInteraction triangleInteraction(const TriangleMesh& mesh, uint32_t prim, float u, float v, float time = 0.0f);

}  // namespace strahl
