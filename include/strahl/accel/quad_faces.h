#pragma once
// QuadFaces: a triangle mesh's consecutive triangle pairs seen as quads, for
// Embree's quad geometry (RTC_GEOMETRY_TYPE_QUAD). A quad is one primitive
// where its two triangles are two: the BVH has half the leaves and a quad
// leaf stores four corners where two triangle leaves store six.
//
// The mesh itself stays triangles — shading, the naive tracer, light sampling
// and cut-outs all speak triangle indices — and nothing about its surface
// changes: two consecutive triangles t, t+1 that share an edge (in opposite
// directions, as neighbours of one winding do) are, rotated, (a, b, c) and
// (a, c, d), and Embree's quad (d, a, b, c) is exactly those two triangles:
// Embree splits a quad (q0, q1, q2, q3) into (q0, q1, q3) = (d, a, c) and
// (q2, q3, q1) = (b, c, a), along the shared diagonal a–c. That is how every
// loader's fan splits a quad face (a, b, c, d), and how the parametric
// tessellator splits its grid cells along either diagonal. A triangle left
// without a partner becomes the degenerate quad (a, b, c, c), whose second
// half Embree never hits.
//
// A hit on quad k at Embree's quad coordinates (u, v) — u + v < 1 on the
// first triangle, u + v >= 1 on the second, whose own coordinates Embree
// reports as (1 - u, 1 - v) — maps back to one triangle and its barycentrics
// with toTriangleHit.

#include <cstdint>
#include <vector>

#include "strahl/geometry/triangle_mesh.h"

namespace strahl {

struct QuadFace {
    uint32_t firstTriangle = 0;  // the face's triangle, or the first of its two
    uint8_t firstRotation = 0;   // (a, b, c) is triangle firstTriangle rotated left by this
    uint8_t secondRotation = 0;  // (a, c, d) is triangle firstTriangle + 1 rotated left by this
    bool pair = false;           // two triangles, or one (the degenerate quad)
};

struct QuadFaces {
    std::vector<uint32_t> corners;  // four per face, in Embree's order
    // One per face; empty when face k is exactly triangles 2k and 2k + 1
    // unrotated (a whole mesh of fan-split quads), which needs no table.
    std::vector<QuadFace> faces;
    size_t faceCount = 0;
    size_t pairedTriangles = 0;  // triangles that found a partner

    size_t memoryBytes() const {
        return corners.capacity() * sizeof(uint32_t) + faces.capacity() * sizeof(QuadFace);
    }
};

// Pairs consecutive triangles greedily, in mesh order (t with t + 1 when they
// share an edge, else t alone).
QuadFaces pairTriangles(const TriangleMesh& mesh);

// Which meshes are traced as quads (bench_quads measures both ways):
//  - Auto: meshes of at least kQuadsFromTriangles triangles, kQuadsAutoPaired
//    of them paired. There quads halve the BVH's leaves and save a fifth to
//    a quarter of its bytes, and rays get faster (1.04-1.16x on a 0.5-4 M
//    triangle grid), since traversal dominates; on small and architectural
//    meshes (Sponza, the conference room) Embree's quad test — two triangles
//    from four corners, where a triangle leaf holds precomputed edges — costs
//    more than the saved steps (0.88x the Mrays/s).
//  - Always: every mesh at least half of whose triangles pair (below that the
//    degenerate quads of lone triangles, each testing an empty second half,
//    outweigh the saved primitives).
//  - Never: triangles only.
enum class QuadPolicy { Auto, Always, Never };
inline constexpr size_t kQuadsFromTriangles = size_t(1) << 19;
inline constexpr double kQuadsAutoPaired = 0.9;

// Whether a mesh of `triangleCount` triangles is traced as quads under
// `policy`: the pairing is then `pairs()` (called only when needed).
template <class Pairs>
bool tracesAsQuads(QuadPolicy policy, size_t triangleCount, const Pairs& pairs);

// Turns a hit on quad `prim` at Embree's quad coordinates (u, v) into the
// triangle index and that triangle's barycentrics (weights of its second and
// third corner), in place.
void toTriangleHit(const QuadFaces& quads, uint32_t& prim, float& u, float& v);

template <class Pairs>
bool tracesAsQuads(QuadPolicy policy, size_t triangleCount, const Pairs& pairs) {
    if (policy == QuadPolicy::Never || triangleCount == 0) return false;
    if (policy == QuadPolicy::Auto && triangleCount < kQuadsFromTriangles) return false;
    const double paired = double(pairs().pairedTriangles) / double(triangleCount);
    return paired >= (policy == QuadPolicy::Auto ? kQuadsAutoPaired : 0.5);
}

}  // namespace strahl
