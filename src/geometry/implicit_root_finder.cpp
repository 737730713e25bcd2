#include "strahl/geometry/implicit_root_finder.h"

#include <cmath>

namespace strahl {

namespace {

// Depth-first search keeps at most one pending sibling per level, and each
// level halves the segment: 64 levels take any double segment below one ulp.
constexpr int kMaxDepth = 64;
// Interval evaluations per call before the search gives up (see the header):
// a smooth surface needs a few dozen; 4096 is reached only by functions that
// interval arithmetic cannot separate from 0, e.g. f = (x − x)².
constexpr int kSegmentBudget = 4096;
constexpr int kMaxNewtonSteps = 64;

double valueAt(const ImplicitSurface& f, const DVec3& o, const DVec3& d, double t) {
    return f.value(o + t * d);
}

// Whether end values fa, fb bracket a root: not both strictly of one sign
// (a zero counts), and neither NaN.
bool bracketsRoot(double fa, double fb) {
    return (fa <= 0.0 && fb >= 0.0) || (fa >= 0.0 && fb <= 0.0);
}

// The mean-value form F(T) ⊆ F(m) + F'(T)·(T − m), m the midpoint. The natural
// interval extension overestimates by O(width) — every occurrence of t is
// treated as independent — which near a tangency leaves thousands of tiny
// segments undecided; the mean-value form overestimates by O(width²) there.
// F(m) is enclosed rigorously by interval evaluation at the (rounded) point.
bool meanValueRangeContainsZero(const ImplicitSurface& f, const DVec3& o, const DVec3& d,
                                double a, double b, const num::Interval& slope) {
    const double m = 0.5 * (a + b);
    const num::Interval point = num::Interval(m);
    const num::Interval Fm = f.evaluate(IntervalBox{num::Interval(o.x) + point * num::Interval(d.x),
                                                    num::Interval(o.y) + point * num::Interval(d.y),
                                                    num::Interval(o.z) + point * num::Interval(d.z)});
    const num::Interval range = Fm + slope * num::Interval(a - m, b - m);
    return !(range.lo > 0.0 || range.hi < 0.0);  // NaN: cannot exclude
}

}  // namespace

ImplicitRoot refineRoot(const ImplicitSurface& f, const DVec3& o, const DVec3& d, double a,
                        double b, double fa, double fb, RootFinderStats* stats) noexcept {
    if (fa == 0.0) return {a, 0.0};
    if (fb == 0.0) return {b, 0.0};
    double t = 0.5 * (a + b), step = b - a;
    for (int i = 0; i < kMaxNewtonSteps; ++i) {
        const DVec3 p = o + t * d;
        const num::Gradient3 g = f.evaluate(Point3<num::Gradient3>{
            num::Gradient3::variable(p.x, 0), num::Gradient3::variable(p.y, 1),
            num::Gradient3::variable(p.z, 2)});
        if (stats) ++stats->newtonSteps;
        const double F = g.v;
        if (F == 0.0) return {t, 0.0};
        // Keep the sign change inside [a, b].
        if ((F < 0.0) == (fa < 0.0)) {
            a = t;
            fa = F;
        } else {
            b = t;
        }
        const double slope = g.d[0] * d.x + g.d[1] * d.y + g.d[2] * d.z;
        const double newton = t - F / slope;
        const double previous = t;
        t = (newton > a && newton < b) ? newton : 0.5 * (a + b);  // NaN/inf fail the test
        step = std::abs(t - previous);
        // Converged when the step (or the bracket) is down to a few ulps of t.
        const double ulps = 4.0 * std::numeric_limits<double>::epsilon() * std::abs(t);
        if (step <= ulps || b - a <= ulps) break;
    }
    // Quadratic convergence makes the last step an upper bound on the error
    // (the bracket bounds it in any case).
    const double error = std::min(b - a, 2.0 * step) +
                         4.0 * std::numeric_limits<double>::epsilon() * std::abs(t);
    return {t, error};
}

std::optional<ImplicitRoot> findFirstRoot(const ImplicitSurface& f, const DVec3& o, const DVec3& d,
                                          double tmin, double tmax, double tolerance,
                                          RootFinderStats* stats) noexcept {
    if (!(tmin <= tmax) || !std::isfinite(tmin) || !std::isfinite(tmax)) return std::nullopt;
    struct Segment {
        double a, b;
    };
    Segment stack[kMaxDepth + 2];
    int top = 0;
    stack[top++] = {tmin, tmax};
    int budget = kSegmentBudget;
    while (top > 0) {
        const Segment s = stack[--top];
        if (--budget < 0) return ImplicitRoot{0.5 * (s.a + s.b), 0.5 * (s.b - s.a)};
        if (stats) ++stats->segments;
        const num::RayDual F = f.alongRay(o, d, num::Interval(s.a, s.b));
        if (!F.v.containsZero()) continue;  // proof: no root here (NaN bounds fail this too)
        if (!meanValueRangeContainsZero(f, o, d, s.a, s.b, F.d[0])) continue;
        if (!F.d[0].containsZero()) {
            // Monotone: a root exactly when the end values differ in sign.
            const double fa = valueAt(f, o, d, s.a), fb = valueAt(f, o, d, s.b);
            if (!bracketsRoot(fa, fb)) continue;
            return refineRoot(f, o, d, s.a, s.b, fa, fb, stats);
        }
        const double mid = 0.5 * (s.a + s.b);
        if (s.b - s.a <= tolerance || top >= kMaxDepth || mid <= s.a || mid >= s.b) {
            // Unresolved at the resolution asked for. A sign change still gives
            // an accurate root; otherwise it is a tangent or sub-tolerance hit.
            const double fa = valueAt(f, o, d, s.a), fb = valueAt(f, o, d, s.b);
            if (bracketsRoot(fa, fb)) return refineRoot(f, o, d, s.a, s.b, fa, fb, stats);
            return ImplicitRoot{mid, 0.5 * (s.b - s.a)};
        }
        stack[top++] = {mid, s.b};  // the far half waits
        stack[top++] = {s.a, mid};  // the near half is searched first
    }
    return std::nullopt;
}

}  // namespace strahl
