#pragma once
// Bilinear patches (pbrt-v4's `bilinearmesh`, the quads of a mesh taken as
// the surface through their four corners): corners q00, q10, q11, q01 in order
// around the patch, over [0,1]²
//
//     f(u, v) = (1 − u)(1 − v) q00 + u (1 − v) q10 + u v q11 + (1 − u) v q01
//             = q00 + u (q10 − q00) + v (q01 − q00) + u v d,   d = q00 − q10 + q11 − q01,
//
// a plane when the corners are (d lies in the plane they span), else a
// saddle (a hyperbolic paraboloid). The normal ∂u f × ∂v f points to the side
// from which the corners run counter-clockwise, as a triangle's does.
//
// A patch is a bicubic Bézier patch with the control points P_ij = f(i/3, j/3):
// the Bernstein polynomials reproduce linear functions (Σ_k B_k(t) k/3 = t), so
// the product of two of them, and with it f, is represented exactly ("degree
// elevation"). The patch set is therefore a Bézier patch set
// (bezier_patches.h): tessellated or intersected directly by the parametric
// machinery, which finds shared edges and so keeps a mesh of patches
// watertight.

#include <span>
#include <string>

#include "strahl/geometry/parametric_surface.h"

namespace strahl {

// The patches `corners` (four indices into `positions` per patch, in order
// around it). Throws strahl::Error naming `name` for no patches, a count of
// indices that is not a multiple of 4, an index out of range or a position
// that is not finite.
ParametricSurfacePtr makeBilinearPatchSet(std::span<const DVec3> positions, std::span<const uint32_t> corners,
                                          std::string name);

// Whether the patch q00, q10, q11, q01 is flat: its twist d's component out
// of the plane of the diagonals within `tolerance` × the longer diagonal. A
// flat patch is the two triangles (q00, q10, q11) and (q00, q11, q01).
bool bilinearPatchIsFlat(const DVec3& q00, const DVec3& q10, const DVec3& q11, const DVec3& q01,
                         double tolerance);

}  // namespace strahl
