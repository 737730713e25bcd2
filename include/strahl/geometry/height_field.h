#pragma once
// A height field: a grid of C × R height samples (columns × rows, row-major)
// spread over a sizeX × sizeY rectangle centred on the origin,
//
//     f(u, v) = (u, v, heightScale · h(u, v))
//     on (u, v) ∈ [−sizeX/2, sizeX/2] × [−sizeY/2, sizeY/2],
//
// not periodic. Sample (c, r) — heights[r·C + c] — sits at
//     u = −sizeX/2 + c · sizeX/(C − 1),   v = +sizeY/2 − r · sizeY/(R − 1):
// column 0 is the −x edge and ROW 0 THE +y EDGE, so an image's top row is the
// far (+y) edge when seen from +z with x to the right (as loadHeightImage
// returns it). h is the bicubic uniform Catmull–Rom interpolation of the
// samples (C¹, through every sample; rows and columns beyond the border repeat
// the border sample): with the grid coordinates x = (u + sizeX/2)(C − 1)/sizeX
// = c + t and y = (sizeY/2 − v)(R − 1)/sizeY = r + s,
//
//     h = Σ_a Σ_b w_a(t) w_b(s) p[r − 1 + b][c − 1 + a],   a, b ∈ {0..3},
//     w_0 = (−t + 2t² − t³)/2,  w_1 = (2 − 5t² + 3t³)/2,
//     w_2 = (t + 4t² − 3t³)/2,  w_3 = (−t² + t³)/2.
//
// Outside the rectangle the surface continues flat at its edge height (h is
// evaluated at the clamped grid coordinate), in all three arithmetics.
//
// Normal: ∂u f × ∂v f = (−heightScale ∂h/∂u, −heightScale ∂h/∂v, 1), always
// with a positive z: the normal points up (+z), whatever the heights.
//
// Interval evaluation is conservative: for a sub-rectangle touching at most 16
// grid cells, each cell's bicubic is converted to Bézier form and restricted to
// the sub-rectangle (tight: the box shrinks with the sub-rectangle); for larger
// ones h is bounded by the min m and max M of every sample that influences the
// covered cells, widened by the Catmull–Rom overshoot 9/32 (M − m) (the
// largest total negative weight of the bicubic basis, see height_field.cpp),
// with min/max read from a precomputed pyramid.

#include <vector>

#include "strahl/geometry/parametric_surface.h"

namespace strahl {

// Throws strahl::Error on fewer than 2 × 2 samples, heights.size() ≠
// columns · rows, a non-finite height (naming its column and row),
// non-positive or non-finite sizes, or a non-finite heightScale.
ParametricSurfacePtr makeHeightField(std::vector<float> heights, int columns, int rows,
                                     double sizeX, double sizeY, double heightScale);

}  // namespace strahl
