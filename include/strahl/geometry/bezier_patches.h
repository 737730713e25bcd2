#pragma once
// Bicubic Bézier patch sets (the Utah teapot is 32 of them), and the cubic
// Bézier range bounds that the patch set, the surface of revolution and the
// height field use for their interval evaluation.
//
// A patch is 4 × 4 control points P_ij, i along u and j along v, stored
// row-major as points[4i + j]. Over [0,1]²
//
//     f(u, v) = Σ_i Σ_j B_i(u) B_j(v) P_ij,   B_k(t) = C(3,k) t^k (1 − t)^(3−k),
//     ∂u f    = Σ_i Σ_j B_i'(u) B_j(v) P_ij   (∂v f alike),
//
// B_0' = −3(1−t)², B_1' = 3(1−t)² − 6t(1−t), B_2' = 6t(1−t) − 3t², B_3' = 3t².
// The corners are P_00, P_03, P_30 and P_33; the normal ∂u f × ∂v f follows the
// patch's own (u, v) orientation (the classic teapot data turns it inwards,
// into the pot, on all 32 patches — see meshio/bezier_file.h).
//
// Interval evaluation: the control net is restricted to the sub-rectangle
// [u.lo, u.hi] × [v.lo, v.hi] by blossoming (the Bézier control points of the
// same polynomial over the smaller rectangle), and the patch lies in the
// bounding box of those 16 points (convex hull property). The box shrinks
// linearly with the sub-rectangle, so small sub-patches get tight bounds.

#include <array>
#include <string>
#include <vector>

#include "strahl/geometry/parametric_surface.h"

namespace strahl {

struct BezierPatch {
    std::array<DVec3, 16> points;  // points[4*i + j]: i along u, j along v
};

// A ParametricSurface with one patch per entry, each over [0,1]² (not periodic).
// `name` is only used in describe() and messages (e.g. the file it came from).
// Throws strahl::Error on an empty set or a non-finite control point (naming
// the patch and the point).
ParametricSurfacePtr makeBezierPatchSet(std::vector<BezierPatch> patches, std::string name);

namespace bezier {

// The cubic Bernstein polynomials B_0..B_3 at t (any arithmetic).
template <class T>
std::array<T, 4> basis(const T& t) {
    const T s = T(1.0) - t;
    return {s * s * s, T(3.0) * t * s * s, T(3.0) * t * t * s, t * t * t};
}

// Their derivatives B_0'..B_3' at t.
inline std::array<double, 4> basisDerivative(double t) {
    const double s = 1.0 - t;
    return {-3.0 * s * s, 3.0 * s * s - 6.0 * t * s, 6.0 * t * s - 3.0 * t * t, 3.0 * t * t};
}

// The control points of the cubic with control points c (over [0,1]) restricted
// to [a, b] and reparametrised over [0,1]: the blossom values
// c(a,a,a), c(a,a,b), c(a,b,b), c(b,b,b). a and b may lie outside [0,1].
std::array<double, 4> restrictCubic(const std::array<double, 4>& c, double a, double b);

// Conservative bounds of the cubic with control points c over t ∈ T: the hull
// of the restricted control points, widened for rounding by a relative 2^-45
// of max(|c_k|, magnitude) (times the growth of the blossom when T leaves
// [0,1]). `magnitude` lets a caller whose control points were computed from
// larger numbers account for their rounding. Non-finite input gives [-inf, inf].
num::Interval cubicRange(const std::array<double, 4>& c, const num::Interval& t,
                         double magnitude = 0.0);

// The same for the bicubic with control points c[4*i + j] (i along u) over U × V.
num::Interval bicubicRange(const std::array<double, 16>& c, const num::Interval& u,
                           const num::Interval& v, double magnitude = 0.0);

}  // namespace bezier

}  // namespace strahl
