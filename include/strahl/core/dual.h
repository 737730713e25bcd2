#pragma once
// Forward-mode automatic differentiation: Dual<T, N> carries a value and its N
// partial derivatives, and every operation applies the chain rule. Evaluating
// f(x, y, z) with x = {x0, (1,0,0)}, y = {y0, (0,1,0)}, z = {z0, (0,0,1)} gives
// f and its exact gradient (up to rounding) in one pass — no finite
// differences, no step size to choose.
//
// T is double (gradients for normals) or num::Interval: a Dual<Interval, 1>
// seeded with t ∈ [a, b] along a ray gives bounds on both F(t) = f(o + t·d) and
// F'(t) = ∇f·d over the whole segment, which is what root isolation needs
// (geometry/implicit_root_finder.h).
//
// Non-smooth functions (abs, min, max) take the derivative of the branch that
// is active; where an interval does not decide the branch, the derivative is
// the hull of both branches, which stays conservative.

#include <array>

#include "strahl/core/interval.h"

namespace strahl::num {

template <class T, int N>
struct Dual {
    T v{};
    std::array<T, N> d{};

    Dual() = default;
    Dual(double c) : v(c) {}  // NOLINT: implicit, constants have zero derivative
    Dual(const T& value, const std::array<T, N>& derivs) : v(value), d(derivs) {}

    // A variable: value x, derivative 1 in direction `index`.
    static Dual variable(const T& x, int index) {
        Dual r;
        r.v = x;
        r.d[static_cast<size_t>(index)] = T(1.0);
        return r;
    }

    friend Dual operator+(const Dual& a, const Dual& b) {
        Dual r;
        r.v = a.v + b.v;
        for (int i = 0; i < N; ++i) r.d[i] = a.d[i] + b.d[i];
        return r;
    }
    friend Dual operator-(const Dual& a, const Dual& b) {
        Dual r;
        r.v = a.v - b.v;
        for (int i = 0; i < N; ++i) r.d[i] = a.d[i] - b.d[i];
        return r;
    }
    friend Dual operator-(const Dual& a) {
        Dual r;
        r.v = -a.v;
        for (int i = 0; i < N; ++i) r.d[i] = -a.d[i];
        return r;
    }
    friend Dual operator*(const Dual& a, const Dual& b) {
        Dual r;
        r.v = a.v * b.v;
        for (int i = 0; i < N; ++i) r.d[i] = a.d[i] * b.v + a.v * b.d[i];
        return r;
    }
    friend Dual operator/(const Dual& a, const Dual& b) {
        Dual r;
        r.v = a.v / b.v;
        // (a/b)' = (a' - (a/b) b') / b
        for (int i = 0; i < N; ++i) r.d[i] = (a.d[i] - r.v * b.d[i]) / b.v;
        return r;
    }
    Dual& operator+=(const Dual& b) { return *this = *this + b; }
    Dual& operator-=(const Dual& b) { return *this = *this - b; }
    Dual& operator*=(const Dual& b) { return *this = *this * b; }

    // g(v) with derivative g'(v): the chain rule for every unary function.
    Dual chain(const T& value, const T& derivative) const {
        Dual r;
        r.v = value;
        for (int i = 0; i < N; ++i) r.d[i] = derivative * d[i];
        return r;
    }
};

// Whether a <= b holds for every point of the operands (always decided for double).
inline bool certainlyLessEqual(double a, double b) { return a <= b; }
inline bool certainlyLessEqual(const Interval& a, const Interval& b) { return a.hi <= b.lo; }
// Sign of x: -1, 0 or 1 for double; [-1, 1] where an interval straddles 0.
inline double signOf(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }
inline Interval signOf(const Interval& x) {
    if (x.lo > 0.0) return 1.0;
    if (x.hi < 0.0) return -1.0;
    return {-1.0, 1.0};
}

template <class T, int N>
Dual<T, N> sqr(const Dual<T, N>& a) { return a.chain(sqr(a.v), 2.0 * a.v); }

template <class T, int N>
Dual<T, N> sqrt(const Dual<T, N>& a) {
    const T s = sqrt(a.v);
    return a.chain(s, T(0.5) / s);  // infinite slope at 0: the caller guards normals
}

template <class T, int N>
Dual<T, N> abs(const Dual<T, N>& a) { return a.chain(abs(a.v), signOf(a.v)); }

template <class T, int N>
Dual<T, N> min(const Dual<T, N>& a, const Dual<T, N>& b) {
    if (certainlyLessEqual(a.v, b.v)) return a;
    if (certainlyLessEqual(b.v, a.v)) return b;
    Dual<T, N> r;
    r.v = min(a.v, b.v);
    for (int i = 0; i < N; ++i) r.d[i] = hull(a.d[i], b.d[i]);
    return r;
}

// max(a, b) = −min(−a, −b): negation is exact in both arithmetics.
template <class T, int N>
Dual<T, N> max(const Dual<T, N>& a, const Dual<T, N>& b) {
    return -min(-a, -b);
}

template <class T, int N>
Dual<T, N> exp(const Dual<T, N>& a) {
    const T e = exp(a.v);
    return a.chain(e, e);
}

template <class T, int N>
Dual<T, N> log(const Dual<T, N>& a) { return a.chain(log(a.v), T(1.0) / a.v); }

template <class T, int N>
Dual<T, N> sin(const Dual<T, N>& a) { return a.chain(sin(a.v), cos(a.v)); }

template <class T, int N>
Dual<T, N> cos(const Dual<T, N>& a) { return a.chain(cos(a.v), -sin(a.v)); }

template <class T, int N>
Dual<T, N> tan(const Dual<T, N>& a) {
    const T t = tan(a.v);
    return a.chain(t, T(1.0) + sqr(t));
}

template <class T, int N>
Dual<T, N> atan(const Dual<T, N>& a) { return a.chain(atan(a.v), T(1.0) / (T(1.0) + sqr(a.v))); }

template <class T, int N>
Dual<T, N> powi(const Dual<T, N>& a, int n) {
    if (n == 0) return Dual<T, N>(1.0);
    return a.chain(powi(a.v, n), T(static_cast<double>(n)) * powi(a.v, n - 1));
}

namespace detail {
// Partial derivatives of powr(x, y) = max(x, 0)^y: y x^(y-1) and x^y ln x for
// x > 0. Where the base is clamped (x <= 0) the value depends on neither x nor
// y, so both are 0 there (not NaN from 0 * ln 0); an interval that straddles 0
// gets the hull of both pieces.
inline double powrDx(double x, double y) { return x > 0.0 ? y * std::pow(x, y - 1.0) : 0.0; }
inline double powrDy(double x, double y) { return x > 0.0 ? std::pow(x, y) * std::log(x) : 0.0; }
inline Interval powrDx(const Interval& x, const Interval& y) {
    if (!(x.hi > 0.0)) return 0.0;
    const Interval slope = y * powr(x, y - Interval(1.0));
    return x.lo > 0.0 ? slope : hull(slope, Interval(0.0));
}
inline Interval powrDy(const Interval& x, const Interval& y) {
    if (!(x.hi > 0.0)) return 0.0;
    const Interval slope = powr(x, y) * log(x);
    return x.lo > 0.0 ? slope : hull(slope, Interval(0.0));
}
}  // namespace detail

// x^y for x >= 0 and y constant.
template <class T, int N>
Dual<T, N> powr(const Dual<T, N>& a, double y) {
    return a.chain(powr(a.v, T(y)), detail::powrDx(a.v, T(y)));
}

// x^y with both operands varying: d(x^y) = y x^(y-1) x' + x^y ln x y'.
template <class T, int N>
Dual<T, N> powr(const Dual<T, N>& a, const Dual<T, N>& y) {
    const T dx = detail::powrDx(a.v, y.v), dy = detail::powrDy(a.v, y.v);
    Dual<T, N> r;
    r.v = powr(a.v, y.v);
    for (int i = 0; i < N; ++i) r.d[i] = dx * a.d[i] + dy * y.d[i];
    return r;
}

using Gradient3 = Dual<double, 3>;    // value and ∇f
using RayDual = Dual<Interval, 1>;    // F and F' over a ray segment

}  // namespace strahl::num
