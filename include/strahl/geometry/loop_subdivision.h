#pragma once
// Loop subdivision (Loop 1987, with Warren's weights), as pbrt-v4's
// `loopsubdiv` shape computes it: each level splits every triangle into four
// and moves every vertex to a weighted mean of its neighbours, and the result
// is a triangle mesh whose vertices lie on the limit surface. Pure math, no
// Embree.
//
// One level, for a vertex v of valence n with neighbours p_k:
//   interior vertex:  v' = (1 − n β) v + β Σ p_k,   β = 3/16 (n = 3), 3/(8n) (n > 3)
//   boundary vertex:  v' = 3/4 v + 1/8 (b_0 + b_1)  (b_i its neighbours along the boundary)
//   new vertex on an interior edge ab with opposite vertices c, d:
//                     e = 3/8 (a + b) + 1/8 (c + d)
//   new vertex on a boundary edge:  e = (a + b) / 2
// and the triangle (a, b, c) becomes (a, ab, ca), (b, bc, ab), (c, ca, bc),
// (ab, bc, ca), keeping its winding. After the last level every vertex moves
// to its limit position:
//   interior:  v∞ = (1 − n γ) v + γ Σ p_k,  γ = 1 / (n + 3 / (8 β))
//   boundary:  v∞ = 3/5 v + 1/5 (b_0 + b_1)
// A vertex on more than two boundary edges (where surfaces meet at a point)
// stays where it is. The shading normals are the angle-weighted means of the
// final triangles' normals (TriangleMesh::computeVertexNormals); pbrt takes
// the limit surface's tangents instead, which these approach level by level.

#include <string>

#include "strahl/geometry/triangle_mesh.h"

namespace strahl {

// The most levels: each multiplies the triangles by four (8 levels turn one
// triangle into 65,536).
inline constexpr int kMaxLoopLevels = 8;

// `control`'s positions and indices subdivided `levels` times (0 … 8) and
// moved to the limit surface, with smooth normals. Throws strahl::Error
// naming `source` for an edge shared by more than two triangles (the scheme
// needs a manifold surface), a degenerate triangle (two equal indices), a
// level out of range or a result of more than 2^28 triangles.
TriangleMesh loopSubdivide(const TriangleMesh& control, int levels, const std::string& source);

}  // namespace strahl
