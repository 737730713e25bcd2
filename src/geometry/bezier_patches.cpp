// Bicubic Bézier patch sets and the cubic range bounds (blossoming) behind the
// interval evaluation of the patch set, the surface of revolution and the
// height field. The math is in include/strahl/geometry/bezier_patches.h.

#include "strahl/geometry/bezier_patches.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "double_box.h"
#include "strahl/core/error.h"

namespace strahl {

namespace bezier {

namespace {

// Rounding allowance, relative to the largest control point: the blossom is
// six levels of (1 − t)·a + t·b, each adding at most ~3 ulps (18 in all), and
// the double evaluation it is compared with adds ~20 more. 2^-45 (256 ulps)
// covers both with a wide margin and still costs nothing in tightness
// (2.8e-14 relative).
constexpr double kRounding = 0x1p-45;

// How much one level of the blossom can grow values and their rounding errors:
// |1 − t| + |t|, which is 1 inside [0,1].
double growth(double a, double b) {
    return std::max(std::abs(1.0 - a) + std::abs(a), std::abs(1.0 - b) + std::abs(b));
}

double lerp(double a, double b, double t) {
    return (1.0 - t) * a + t * b;
}

// The blossom c(t1, t2, t3) of the cubic with control points c: de Casteljau
// with a different parameter on each level. It is symmetric in its arguments,
// and c(t, t, t) is the point at t.
double blossom(const std::array<double, 4>& c, double t1, double t2, double t3) {
    const double a = lerp(c[0], c[1], t1), b = lerp(c[1], c[2], t1), d = lerp(c[2], c[3], t1);
    return lerp(lerp(a, b, t2), lerp(b, d, t2), t3);
}

double maxAbs(const double* c, size_t n) {
    double m = 0.0;
    for (size_t k = 0; k < n; ++k) m = std::max(m, std::abs(c[k]));
    return m;
}

bool finiteInterval(const num::Interval& t) {
    return std::isfinite(t.lo) && std::isfinite(t.hi);
}

// [lo, hi] widened by `slack`; the whole line if anything overflowed.
num::Interval widened(double lo, double hi, double slack) {
    const num::Interval r(lo - slack, hi + slack);
    if (!(std::isfinite(r.lo) && std::isfinite(r.hi))) return num::Interval::entire();
    return r;
}

}  // namespace

std::array<double, 4> restrictCubic(const std::array<double, 4>& c, double a, double b) {
    return {blossom(c, a, a, a), blossom(c, a, a, b), blossom(c, a, b, b), blossom(c, b, b, b)};
}

num::Interval cubicRange(const std::array<double, 4>& c, const num::Interval& t, double magnitude) {
    if (!finiteInterval(t)) return num::Interval::entire();
    const std::array<double, 4> q = restrictCubic(c, t.lo, t.hi);
    const auto [lo, hi] = std::minmax({q[0], q[1], q[2], q[3]});
    const double g = growth(t.lo, t.hi);
    const double slack = kRounding * std::max(maxAbs(c.data(), 4), magnitude) * g * g * g + 1e-300;
    return widened(lo, hi, slack);
}

num::Interval bicubicRange(const std::array<double, 16>& c, const num::Interval& u,
                           const num::Interval& v, double magnitude) {
    if (!finiteInterval(u) || !finiteInterval(v)) return num::Interval::entire();
    // Restrict every column (fixed j) along u, then every row along v.
    std::array<double, 16> d;
    for (size_t j = 0; j < 4; ++j) {
        const std::array<double, 4> q =
            restrictCubic({c[j], c[4 + j], c[8 + j], c[12 + j]}, u.lo, u.hi);
        for (size_t i = 0; i < 4; ++i) d[4 * i + j] = q[i];
    }
    double lo = num::kInf, hi = -num::kInf;
    for (size_t i = 0; i < 4; ++i) {
        const std::array<double, 4> q =
            restrictCubic({d[4 * i], d[4 * i + 1], d[4 * i + 2], d[4 * i + 3]}, v.lo, v.hi);
        for (const double x : q) {
            lo = std::min(lo, x);
            hi = std::max(hi, x);
        }
    }
    const double gu = growth(u.lo, u.hi), gv = growth(v.lo, v.hi);
    const double g = gu * gu * gu * gv * gv * gv;
    const double slack = kRounding * std::max(maxAbs(c.data(), 16), magnitude) * g + 1e-300;
    return widened(lo, hi, slack);
}

}  // namespace bezier

namespace {

using geometry_detail::isFiniteD;

class BezierPatchSet final : public ParametricSurfaceOf<BezierPatchSet> {
public:
    BezierPatchSet(std::vector<BezierPatch> patches, std::string name)
        : patches_(std::move(patches)), name_(std::move(name)) {
        // The coordinates again as one array per axis, for the interval bounds.
        coords_.resize(patches_.size());
        for (size_t p = 0; p < patches_.size(); ++p)
            for (size_t k = 0; k < 16; ++k)
                for (int axis = 0; axis < 3; ++axis)
                    coords_[p][axis][k] = patches_[p].points[k][axis];
    }

    uint32_t patchCount() const override { return static_cast<uint32_t>(patches_.size()); }
    const ParamDomain& domain() const override { return domain_; }

    // double and Dual2: the Bernstein sum.
    template <class T>
    Point3<T> eval(uint32_t patch, const T& u, const T& v) const {
        const std::array<T, 4> bu = bezier::basis(u), bv = bezier::basis(v);
        const BezierPatch& net = patches_[patch];
        T x(0.0), y(0.0), z(0.0);
        for (size_t i = 0; i < 4; ++i) {
            T rx(0.0), ry(0.0), rz(0.0);  // row i evaluated at v
            for (size_t j = 0; j < 4; ++j) {
                const DVec3& p = net.points[4 * i + j];
                rx += bv[j] * T(p.x);
                ry += bv[j] * T(p.y);
                rz += bv[j] * T(p.z);
            }
            x += bu[i] * rx;
            y += bu[i] * ry;
            z += bu[i] * rz;
        }
        return {x, y, z};
    }

    // Intervals: the box of the control net restricted to U × V. (A better
    // match than the template for Interval arguments, so ParametricSurfaceOf
    // picks it.)
    Point3<num::Interval> eval(uint32_t patch, const num::Interval& u,
                               const num::Interval& v) const {
        const auto& c = coords_[patch];
        return {bezier::bicubicRange(c[0], u, v), bezier::bicubicRange(c[1], u, v),
                bezier::bicubicRange(c[2], u, v)};
    }

    SurfacePoint partials(uint32_t patch, double u, double v) const override {
        const std::array<double, 4> bu = bezier::basis(u), bv = bezier::basis(v);
        const std::array<double, 4> du = bezier::basisDerivative(u);
        const std::array<double, 4> dv = bezier::basisDerivative(v);
        const BezierPatch& net = patches_[patch];
        SurfacePoint s;
        for (size_t i = 0; i < 4; ++i)
            for (size_t j = 0; j < 4; ++j) {
                const DVec3& p = net.points[4 * i + j];
                s.p += (bu[i] * bv[j]) * p;
                s.dpdu += (du[i] * bv[j]) * p;
                s.dpdv += (bu[i] * dv[j]) * p;
            }
        return s;
    }

    std::string describe() const override {
        return concat("bezier patches", name_.empty() ? "" : " '", name_, name_.empty() ? "" : "'",
                      " (", patches_.size(), patches_.size() == 1 ? " patch)" : " patches)");
    }

private:
    std::vector<BezierPatch> patches_;
    std::vector<std::array<std::array<double, 16>, 3>> coords_;  // [patch][axis][4i + j]
    std::string name_;
    ParamDomain domain_;  // [0,1]², not periodic
};

}  // namespace

ParametricSurfacePtr makeBezierPatchSet(std::vector<BezierPatch> patches, std::string name) {
    const std::string what =
        name.empty() ? std::string("bezier patches") : concat("bezier patches '", name, "'");
    if (patches.empty()) fail(what, ": no patches");
    if (patches.size() > UINT32_MAX) fail(what, ": too many patches (", patches.size(), ")");
    for (size_t p = 0; p < patches.size(); ++p)
        for (size_t k = 0; k < 16; ++k) {
            const DVec3& q = patches[p].points[k];
            if (!isFiniteD(q))
                fail(what, ": control point ", k, " of patch ", p, " is not finite (", q.x, " ",
                     q.y, " ", q.z, ")");
        }
    return std::make_shared<BezierPatchSet>(std::move(patches), std::move(name));
}

}  // namespace strahl
