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

    size_t triangleCount() const { return indices.size() / 3; }
    size_t vertexCount() const { return positions.size(); }
    Bounds3 bounds() const;
    size_t memoryBytes() const;

    // Applies an affine transform: positions by m, normals by its inverse transpose.
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
    // (or, for face attributes, the triangles).
    void validate(const std::string& source) const;

    // Embree reads vertex buffers with 16-byte loads, so a buffer shared with it
    // needs readable memory behind the last vertex: reserve one spare element.
    void reservePadding() { positions.reserve(positions.size() + 1); }
    bool isPadded() const { return positions.capacity() > positions.size(); }
};

// Interaction on triangle `prim` at Embree barycentrics (u, v).
SurfaceInteraction triangleInteraction(const TriangleMesh& mesh, uint32_t prim, float u, float v);

}  // namespace strahl
