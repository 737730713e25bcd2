#pragma once
// Constructive solid geometry on implicit surfaces (f < 0 inside):
//   union          min(f1, f2, ...)
//   intersection   max(f1, f2, ...)
//   difference     max(f1, −f2, −f3, ...)   (f1 minus the others)
//   smooth_union   smin_k(f1, f2, ...), the polynomial smooth minimum
//                  smin_k(a, b) = min(a, b) − h²k/4, h = max(k − |a − b|, 0)/k
//                  (Quilez), which blends where the operands differ by < k.
// These are exact for signed distance functions and keep the correct zero set
// for any functions that are negative inside. Gradients come from automatic
// differentiation (the branch that is active).
//
// Bounds: union — the union of the operands' boxes; intersection — the
// intersection of those that have one; difference — the first operand's box;
// smooth union — the union grown by k on every side, which contains the blend
// wherever the operands grow at least as fast as the distance from their
// surfaces (signed distances, and the built-ins at unit scale); give the shape
// a box otherwise.

#include <vector>

#include "strahl/core/math.h"
#include "strahl/geometry/implicit_surface.h"

namespace strahl {

enum class CsgOperation { Union, Intersection, Difference, SmoothUnion };

// An operand placed by an affine map (operand space → the CSG's space):
// g(x) = f(M⁻¹x). The zero set moves with M; bounds are the transformed box.
// Throws strahl::Error if M is singular or not finite.
ImplicitSurfacePtr makeTransformed(ImplicitSurfacePtr surface, const Mat4& placement);

// At least two operands; `blend` (k > 0) is used by SmoothUnion only.
ImplicitSurfacePtr makeCsg(CsgOperation op, std::vector<ImplicitSurfacePtr> operands,
                           double blend = 0.0);

}  // namespace strahl
