#pragma once
// Internal to the geometry module: what the built-in implicit surfaces
// (implicit_<kind>.cpp) share. Each kind is one template eval<T>() — the
// formula, evaluated in double, interval and dual arithmetic alike — plus a
// gradient written by hand, which the tests hold against automatic
// differentiation.

#include <cmath>
#include <utility>

#include "strahl/core/error.h"
#include "strahl/geometry/implicit_builtins.h"
#include "strahl/geometry/implicit_kinds.h"

namespace strahl::implicit_detail {

using num::abs;
using num::cos;
using num::max;
using num::powi;
using num::powr;
using num::sin;
using num::sqr;
using num::sqrt;

inline void requireFinite(const char* name, double value) {
    if (!std::isfinite(value)) fail("parameter '", name, "' is not a finite number");
}
inline void requirePositive(const char* name, double value) {
    requireFinite(name, value);
    if (!(value > 0.0)) fail("parameter '", name, "' must be > 0 (got ", value, ")");
}

// Real roots of a t² + b t + c = 0 in increasing order, without the
// cancellation of the schoolbook formula: q = −(b + sign(b)·√Δ)/2 has no
// subtraction of near-equal numbers, and the roots are q/a and c/q (Press et
// al., Numerical Recipes §5.6). A vanishing `a` degrades to the linear root.
inline int solveQuadratic(double a, double b, double c, double discriminant, double roots[4]) {
    if (a == 0.0) {
        if (b == 0.0) return 0;
        roots[0] = -c / b;
        return 1;
    }
    if (discriminant < 0.0) return 0;
    const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
    double t0 = q / a, t1 = q != 0.0 ? c / q : -t0;
    if (t0 > t1) std::swap(t0, t1);
    roots[0] = t0;
    roots[1] = t1;
    return 2;
}

}  // namespace strahl::implicit_detail
