#pragma once
// The equal-area octahedral map between the unit sphere and the unit square
// (Clarberg 2008, "Fast Equal-Area Mapping of the (Hemi)Sphere using SIMD"),
// the layout of pbrt-v4's environment images. The sphere is split into eight
// octants around +z; an octant's spherical triangle maps to a right triangle of
// the square [-1, 1]² by
//
//   r = √(1 − |z|),   φ = (2/π) · atan(min(|x|, |y|) / max(|x|, |y|))
//   (|x| ≥ |y|):  u' = r (1 − φ),  v' = r φ       (swapped when |x| < |y|)
//
// which preserves area because the area of the spherical cap 1 − |z| = r² is
// the area of the diamond |u'| + |v'| ≤ r. The lower hemisphere (z < 0) folds
// out to the square's corners: (u', v') → (1 − v', 1 − u'). Signs follow x and
// y, and [-1, 1]² is shifted to [0, 1]². Every texel of a square image therefore
// covers the same solid angle, 4π / texels.

#include "strahl/core/math.h"

namespace strahl {

// The point of [0, 1]² of a unit direction.
Vec2 equalAreaSphereToSquare(const Vec3& direction);
// The unit direction of a point of [0, 1]² (the inverse).
Vec3 equalAreaSquareToSphere(const Vec2& point);

}  // namespace strahl
