#pragma once
// Catmull-Clark subdivision (Catmull & Clark 1978) with the sharpness rules of
// DeRose, Kass & Truong 1998 (semi-sharp creases and corners), as Embree's
// subdivision geometry and OpenSubdiv define the surface. Pure math, no
// Embree: this is the reference the naive tracer intersects and the data the
// shading of a SubdivisionSurface interpolates (subdivision_surface.h).
//
// One level, for a face f with vertices v_0 … v_{n−1}:
//   face point    F = (1/n) Σ v_i
//   edge point    E = (a + b + F_1 + F_2) / 4          smooth interior edge ab
//                 E = (a + b) / 2                       boundary edge, or sharpness s ≥ 1
//                 E = lerp(smooth, sharp, s)            0 < s < 1
//   vertex point  V = (Q + 2R + (n − 3) v) / n          smooth (fewer than 2 sharp edges)
//                     Q = mean of the adjacent face points, R = mean of the
//                     adjacent edges' midpoints, n = the valence
//                 V = (6v + a + b) / 8                  crease: exactly 2 sharp edges to a and b
//                 V = v                                 corner: more than 2 sharp edges, or a
//                                                       vertex sharpness ≥ 1
//                 the crease rule is blended with the smooth one by the mean
//                 sharpness of its two edges when that is < 1, the corner rule
//                 of a vertex sharpness s < 1 by s; more than 2 sharp edges
//                 make a corner unblended.
// and f becomes n quads (v_i, E_i, F, E_{i−1}), E_i on the edge v_i v_{i+1},
// keeping its winding. A child edge's sharpness is its parent's minus 1 —
// at a crease vertex with sharp edges s and s', by Chaikin's rule
// (3s + s')/4 − 1 — and so is a vertex's (never below 0); boundary edges are
// infinitely sharp (the boundary is a cubic B-spline curve). These are the
// rules of Embree's subdivision (kernels/subdiv/catmullclark_ring.h). After the last level every vertex moves to its
// limit position (all faces are quads by then):
//   smooth    v∞ = (n² v + 4 Σ e_j + Σ d_j) / (n (n + 5))    e_j: edge neighbours,
//                                                            d_j: diagonal corners
//   crease    v∞ = (4v + a + b) / 6
//   corner    v∞ = v
//
// Parameters: every refined quad records the (u, v) of its corners in its
// control face, in Embree's convention (which `strahl`'s hits use too): a
// quad face's own [0,1]² with u from v_0 to v_1 and v from v_0 to v_3; a face
// of n ≠ 4 vertices is split into n quads first, and sub-quad i's local
// (s, t) ∈ [0,1]² (s towards E_i, t towards E_{i−1}) is stored as
// u = 2 (i mod 4) + 1/2 + s, v = 2 ⌊i/4⌋ + 1/2 + t. (Embree documents no
// encoding; this is what its hits report, measured against this code by
// tests/reference/subdivision_agreement_test.cpp.)

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "strahl/core/point3.h"

namespace strahl {

using DVec2 = glm::dvec2;

// How the surface meets its boundary (Embree's subdivision modes).
enum class SubdivisionBoundary {
    Smooth,       // boundary edges are creases: a smooth B-spline boundary curve
    PinCorners,   // … and a boundary vertex of one face stays where it is
    PinBoundary,  // every boundary vertex stays: the boundary is the control polygon
    PinAll,       // every vertex and edge is sharp: each quad is its bilinear patch
};

const char* subdivisionBoundaryName(SubdivisionBoundary mode);  // "smooth", "pin_corners", …
// Throws strahl::Error listing the choices for anything else.
SubdivisionBoundary subdivisionBoundaryFromName(const std::string& name);

// The control mesh ("cage").
struct SubdivisionCage {
    std::vector<DVec3> positions;
    std::vector<uint32_t> faceSizes;  // 3 … 15 vertices per face (Embree's limit)
    std::vector<uint32_t> indices;    // Σ faceSizes, counter-clockwise seen from outside
    std::vector<DVec2> uvs;           // empty, or one per position (subdivided like them)
    std::vector<uint32_t> creaseEdges;  // pairs of vertex indices joined by an edge
    std::vector<float> creaseWeights;   // one sharpness per pair (≥ 0; inf: infinitely sharp)
    std::vector<uint32_t> cornerVertices;
    std::vector<float> cornerWeights;   // one sharpness per corner vertex
    std::vector<uint32_t> holes;        // faces left out: their edges become boundary
    SubdivisionBoundary boundary = SubdivisionBoundary::Smooth;
};

inline constexpr int kMaxFaceSize = 15;
inline constexpr int kMaxSubdivisionLevels = 8;

// The limit surface after `levels` levels (1 … 8), as quads.
struct RefinedSurface {
    int levels = 0;
    std::vector<DVec3> positions;  // every refined vertex, at its limit position
    std::vector<DVec2> uvs;        // the same for the cage's uvs (empty if it has none)
    std::vector<std::array<uint32_t, 4>> quads;     // refined quads, counter-clockwise
    std::vector<uint32_t> quadFace;                 // the control face of each quad
    std::vector<std::array<DVec2, 4>> quadParams;   // each corner's (u, v) in that face
    // Corners that share a smooth normal carry the same group: the corners
    // of one vertex, except across a sharp edge (a crease shows a kink).
    std::vector<std::array<uint32_t, 4>> cornerGroup;
    uint32_t groupCount = 0;
};

// Checks the cage and refines it. Throws strahl::Error naming `name` for a
// face size out of 3 … 15, an index out of range, a face using a vertex
// twice, an edge shared by more than two faces or used twice in one
// direction (inconsistent winding), a crease pair that is not an edge of the
// mesh, a NaN or negative weight, a hole or corner out of range, a
// coordinate that is not finite, or `levels` out of range.
RefinedSurface refineCatmullClark(const SubdivisionCage& cage, int levels, const std::string& name);

// Unit normals per quad corner from `positions` (which may be displaced
// copies of surface.positions), shared within each corner group.
std::vector<std::array<DVec3, 4>> cornerNormals(const RefinedSurface& surface, const std::vector<DVec3>& positions);

}  // namespace strahl
