#pragma once
// Interval arithmetic in double precision, for conservative range bounds:
// if x lies in X then f(x) lies in the interval extension f(X). The implicit
// surface root finder uses it to prove that a ray segment (or a grid cell)
// contains no part of the surface, so it can skip it without missing a hit.
//
// Rounding: every result is widened outwards by a relative 2^-51 (two ulps of
// double) plus 1e-300, which covers the round-to-nearest error of the
// arithmetic and the ≤ 1-ulp error of the libm functions used here (powi,
// whose error grows with the exponent, widens by more). This is
// cheaper than switching the rounding mode (which the compiler may reorder
// around) and than std::nextafter (a library call per bound).
//
// Division by an interval containing 0 and functions outside their domain
// return the whole line [-inf, inf] or clamp to the domain (sqrt, log of a
// negative part), never NaN: an interval that is "too wide" only costs the root
// finder time, a NaN would make it skip a hit.
//
// The functions live in namespace strahl::num with double overloads of the same
// names, so generic code (templated on double, Interval or Dual) reads like the
// formula it evaluates.

#include <algorithm>
#include <cmath>
#include <limits>

namespace strahl::num {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kPiD = 3.14159265358979323846;

inline constexpr double kMaxFinite = std::numeric_limits<double>::max();

namespace detail {
// The widening is capped at the largest double so an infinite bound never
// becomes inf - inf = NaN, and a bound that overflowed to +-inf on its inner
// side becomes the largest finite double: the true value was finite, merely
// too large to represent.
inline double widening(double x) { return std::min(std::abs(x) * 0x1p-51, kMaxFinite) + 1e-300; }
inline double down(double x) { return std::min(x - widening(x), kMaxFinite); }
inline double up(double x) { return std::max(x + widening(x), -kMaxFinite); }
// 0 * inf is 0 for bounds: the point 0 times any finite number in the other
// interval is 0.
inline double mulBound(double a, double b) { return (a == 0.0 || b == 0.0) ? 0.0 : a * b; }
// inf / inf is 0 for bounds: the other corners of a quotient already cover
// every value it could stand for (x / y is monotone in x and in y).
inline double divBound(double a, double b) {
    return (std::isinf(a) && std::isinf(b)) ? 0.0 : a / b;
}
}  // namespace detail

struct Interval {
    double lo = 0.0, hi = 0.0;

    Interval() = default;
    Interval(double x) : lo(x), hi(x) {}  // NOLINT: implicit, so constants mix freely
    Interval(double l, double h) : lo(l), hi(h) {}

    static Interval entire() { return {-kInf, kInf}; }
    // Widened outwards to account for rounding.
    static Interval rounded(double l, double h) { return {detail::down(l), detail::up(h)}; }

    double width() const { return hi - lo; }
    double mid() const { return 0.5 * (lo + hi); }
    bool contains(double x) const { return lo <= x && x <= hi; }
    bool containsZero() const { return lo <= 0.0 && 0.0 <= hi; }

    friend Interval operator+(const Interval& a, const Interval& b) {
        return rounded(a.lo + b.lo, a.hi + b.hi);
    }
    friend Interval operator-(const Interval& a, const Interval& b) {
        return rounded(a.lo - b.hi, a.hi - b.lo);
    }
    friend Interval operator-(const Interval& a) { return {-a.hi, -a.lo}; }
    friend Interval operator*(const Interval& a, const Interval& b) {
        using detail::mulBound;
        const double p1 = mulBound(a.lo, b.lo), p2 = mulBound(a.lo, b.hi);
        const double p3 = mulBound(a.hi, b.lo), p4 = mulBound(a.hi, b.hi);
        return rounded(std::min(std::min(p1, p2), std::min(p3, p4)),
                       std::max(std::max(p1, p2), std::max(p3, p4)));
    }
    friend Interval operator/(const Interval& a, const Interval& b) {
        if (b.containsZero()) return entire();
        using detail::divBound;
        const double p1 = divBound(a.lo, b.lo), p2 = divBound(a.lo, b.hi);
        const double p3 = divBound(a.hi, b.lo), p4 = divBound(a.hi, b.hi);
        return rounded(std::min(std::min(p1, p2), std::min(p3, p4)),
                       std::max(std::max(p1, p2), std::max(p3, p4)));
    }
    Interval& operator+=(const Interval& b) { return *this = *this + b; }
    Interval& operator-=(const Interval& b) { return *this = *this - b; }
    Interval& operator*=(const Interval& b) { return *this = *this * b; }
};

// The smallest interval containing both.
inline Interval hull(const Interval& a, const Interval& b) {
    return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}
inline double hull(double a, double) { return a; }

// ---- functions, with double overloads of the same names --------------------

inline double sqr(double x) { return x * x; }
inline Interval sqr(const Interval& a) {
    if (a.lo >= 0.0) return Interval::rounded(a.lo * a.lo, a.hi * a.hi);
    if (a.hi <= 0.0) return Interval::rounded(a.hi * a.hi, a.lo * a.lo);
    return {0.0, detail::up(std::max(a.lo * a.lo, a.hi * a.hi))};
}

inline double sqrt(double x) { return std::sqrt(std::max(x, 0.0)); }
inline Interval sqrt(const Interval& a) {
    const double lo = std::max(a.lo, 0.0), hi = std::max(a.hi, 0.0);
    return {std::max(0.0, detail::down(std::sqrt(lo))), detail::up(std::sqrt(hi))};
}

inline double abs(double x) { return std::abs(x); }
inline Interval abs(const Interval& a) {
    if (a.lo >= 0.0) return a;
    if (a.hi <= 0.0) return -a;
    return {0.0, std::max(-a.lo, a.hi)};
}

inline double min(double a, double b) { return std::min(a, b); }
inline double max(double a, double b) { return std::max(a, b); }
inline Interval min(const Interval& a, const Interval& b) {
    return {std::min(a.lo, b.lo), std::min(a.hi, b.hi)};
}
inline Interval max(const Interval& a, const Interval& b) {
    return {std::max(a.lo, b.lo), std::max(a.hi, b.hi)};
}

inline double exp(double x) { return std::exp(x); }
inline Interval exp(const Interval& a) {
    return {std::max(0.0, detail::down(std::exp(a.lo))), detail::up(std::exp(a.hi))};
}

// log of a non-positive number is -inf (the limit), never NaN. An interval's
// upper bound stays finite (-max) so that adding +inf later cannot give NaN.
inline double log(double x) { return x > 0.0 ? std::log(x) : -kInf; }
inline Interval log(const Interval& a) {
    const double lo = a.lo > 0.0 ? detail::down(std::log(a.lo)) : -kInf;
    const double hi = a.hi > 0.0 ? detail::up(std::log(a.hi)) : -kMaxFinite;
    return {lo, hi};
}

inline double atan(double x) { return std::atan(x); }
inline Interval atan(const Interval& a) {
    return Interval::rounded(std::atan(a.lo), std::atan(a.hi));
}

namespace detail {
// True if [lo, hi] contains phase + 2*pi*k for some integer k.
inline bool containsPhase(double lo, double hi, double phase) {
    const double twoPi = 2.0 * kPiD;
    return std::ceil((lo - phase) / twoPi) <= std::floor((hi - phase) / twoPi);
}
// Beyond this magnitude the phase test below is off by more than the 1e-15
// widening can absorb (its rounding error grows like |x| * 3e-16).
inline constexpr double kMaxPhaseArgument = 1e8;
inline bool phaseTestIsExact(double lo, double hi) {
    return std::abs(lo) < kMaxPhaseArgument && std::abs(hi) < kMaxPhaseArgument;
}
// Range of sin over [lo, hi]; cos is sin shifted by pi/2.
inline Interval sinRange(double lo, double hi) {
    if (!(hi - lo < 2.0 * kPiD) || !phaseTestIsExact(lo, hi)) return {-1.0, 1.0};
    double l = std::min(std::sin(lo), std::sin(hi)), h = std::max(std::sin(lo), std::sin(hi));
    if (containsPhase(lo, hi, 0.5 * kPiD)) h = 1.0;
    if (containsPhase(lo, hi, -0.5 * kPiD)) l = -1.0;
    // Absolute widening: sin's rounding error is absolute near its zeros.
    return {std::max(-1.0, l - 1e-15), std::min(1.0, h + 1e-15)};
}
}  // namespace detail

inline double sin(double x) { return std::sin(x); }
inline double cos(double x) { return std::cos(x); }
inline Interval sin(const Interval& a) { return detail::sinRange(a.lo, a.hi); }
inline Interval cos(const Interval& a) {
    return detail::sinRange(a.lo + 0.5 * kPiD, a.hi + 0.5 * kPiD);
}

inline double tan(double x) { return std::tan(x); }
inline Interval tan(const Interval& a) {
    // tan is increasing between its poles at pi/2 + k*pi.
    if (!(a.width() < kPiD) || !detail::phaseTestIsExact(a.lo, a.hi) ||
        detail::containsPhase(a.lo, a.hi, 0.5 * kPiD) ||
        detail::containsPhase(a.lo, a.hi, -0.5 * kPiD))
        return Interval::entire();
    const double lo = std::tan(a.lo), hi = std::tan(a.hi);
    // Decreasing ends mean a pole the rounded phase test missed by a hair.
    if (!(lo <= hi)) return Interval::entire();
    return Interval::rounded(lo, hi);
}

// x^n for an integer n (n may be negative).
inline double powi(double x, int n) {
    double r = 1.0, b = x;
    for (int k = n < 0 ? -n : n; k > 0; k >>= 1, b *= b)
        if (k & 1) r *= b;
    return n < 0 ? 1.0 / r : r;
}
namespace detail {
// powi(double) rounds once per multiplication, and the relative errors add up
// along the chain: at most (n - 1) * 2^-53 for x^n. Widen by more than that.
inline double powWidening(double x, int n) {
    const double relative = (static_cast<double>(n) + 1.0) * 0x1p-52;
    return std::min(std::abs(x) * relative, kMaxFinite) + 1e-300;
}
inline double powDown(double x, int n) { return std::min(x - powWidening(x, n), kMaxFinite); }
inline double powUp(double x, int n) { return std::max(x + powWidening(x, n), -kMaxFinite); }
}  // namespace detail

inline Interval powi(const Interval& a, int n) {
    if (n == 0) return 1.0;
    if (n < 0) return Interval(1.0) / powi(a, -n);
    if (n % 2 == 1)  // increasing
        return {detail::powDown(powi(a.lo, n), n), detail::powUp(powi(a.hi, n), n)};
    const Interval m = abs(a);  // even power: x^n = |x|^n, increasing on [0, inf)
    return {std::max(0.0, detail::powDown(powi(m.lo, n), n)), detail::powUp(powi(m.hi, n), n)};
}

// x^y for x >= 0 (a negative base is clamped to 0: the general power is only
// defined there; integer powers go through powi). The clamp adds +0.0: -0.0
// is not below 0.0, so std::max keeps it, and pow(-0.0, y) is -0.0 or -inf for
// odd integer y; -0.0 + 0.0 is +0.0.
inline double clampToNonNegative(double x) { return std::max(x, 0.0) + 0.0; }
inline double powr(double x, double y) { return std::pow(clampToNonNegative(x), y); }
inline Interval powr(const Interval& a, const Interval& y) {
    const double lo = clampToNonNegative(a.lo), hi = clampToNonNegative(a.hi);
    const double c[4] = {std::pow(lo, y.lo), std::pow(lo, y.hi), std::pow(hi, y.lo),
                         std::pow(hi, y.hi)};
    double l = kInf, h = -kInf;
    for (double v : c) {
        l = std::min(l, v);
        h = std::max(h, v);
    }
    // For x >= 0, x^y is monotone in x for fixed y and in y for fixed x, so the
    // extremes over the box sit at its corners.
    return {std::max(0.0, detail::down(l)), detail::up(h)};
}

}  // namespace strahl::num
