// Surface of revolution around z through a Catmull–Rom profile; the math is in
// include/strahl/geometry/revolution_surface.h.
//
// Each profile segment is stored in Bézier form (b0 = P_k, b1 = P_k + m_k/3,
// b2 = P_{k+1} − m_{k+1}/3, b3 = P_{k+1}), and all three arithmetics evaluate
// that one polynomial: B(0) = (1,0,0,0) exactly, so s = k gives P_k exactly, and
// the interval bounds (the hull of the segment's control points restricted to
// the parameter range) are bounds of exactly the function the double and Dual2
// evaluations compute.

#include "strahl/geometry/revolution_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <utility>

#include "dual_value.h"
#include "strahl/core/error.h"
#include "strahl/geometry/bezier_patches.h"

namespace strahl {

namespace {

constexpr double kTwoPi = 2.0 * num::kPiD;

using geometry_detail::valueOf;

struct Segment {
    std::array<double, 4> r, z;  // Bézier control values over t ∈ [0,1]
    num::Interval rBox, zBox;    // conservative ranges of the whole segment
};

class Revolution final : public ParametricSurfaceOf<Revolution> {
public:
    explicit Revolution(const std::vector<glm::dvec2>& profile) : points_(profile.size()) {
        const size_t n = profile.size();
        auto tangent = [&](size_t k) {
            if (k == 0) return profile[1] - profile[0];
            if (k == n - 1) return profile[n - 1] - profile[n - 2];
            return 0.5 * (profile[k + 1] - profile[k - 1]);
        };
        for (size_t k = 0; k + 1 < n; ++k) {
            const glm::dvec2 b0 = profile[k], b3 = profile[k + 1];
            const glm::dvec2 b1 = b0 + tangent(k) / 3.0, b2 = b3 - tangent(k + 1) / 3.0;
            Segment s;
            s.r = {b0.x, b1.x, b2.x, b3.x};
            s.z = {b0.y, b1.y, b2.y, b3.y};
            s.rBox = bezier::cubicRange(s.r, num::Interval(0.0, 1.0));
            s.zBox = bezier::cubicRange(s.z, num::Interval(0.0, 1.0));
            segments_.push_back(s);
        }
        domain_ = {0.0, kTwoPi, 0.0, static_cast<double>(n - 1), true, false};
    }

    const ParamDomain& domain() const override { return domain_; }

    // double and Dual2.
    template <class T>
    Point3<T> eval(uint32_t, const T& phi, const T& s) const {
        const auto [k, t] = locate(s);
        const std::array<T, 4> b = bezier::basis(t);
        const Segment& seg = segments_[k];
        T r(0.0), z(0.0);
        for (size_t i = 0; i < 4; ++i) {
            r += b[i] * T(seg.r[i]);
            z += b[i] * T(seg.z[i]);
        }
        return {r * num::cos(phi), r * num::sin(phi), z};
    }

    // Intervals: the hull of r and z over every segment S touches, times the
    // interval cos and sin of Φ.
    Point3<num::Interval> eval(uint32_t, const num::Interval& phi, const num::Interval& s) const {
        if (!(std::isfinite(s.lo) && std::isfinite(s.hi)))
            return {num::Interval::entire(), num::Interval::entire(), num::Interval::entire()};
        const size_t first = segmentOf(s.lo);
        size_t last = segmentOf(s.hi);
        // s.hi on a knot: the segment before ends there, no need for the next.
        if (last > first && s.hi == static_cast<double>(last)) --last;
        num::Interval r, z;
        for (size_t k = first; k <= last; ++k) {
            const auto kd = static_cast<double>(k);
            // Inside the domain s − k is exact (Sterbenz); beyond its ends (an
            // extrapolating end segment) step outwards by an ulp to stay safe.
            double t0 = k == first ? s.lo - kd : 0.0;
            double t1 = k == last ? s.hi - kd : 1.0;
            if (t0 < 0.0) t0 = std::nextafter(t0, -num::kInf);
            if (t1 > 1.0) t1 = std::nextafter(t1, num::kInf);
            const Segment& seg = segments_[k];
            const bool whole = t0 == 0.0 && t1 == 1.0;
            const num::Interval rk = whole ? seg.rBox : bezier::cubicRange(seg.r, {t0, t1});
            const num::Interval zk = whole ? seg.zBox : bezier::cubicRange(seg.z, {t0, t1});
            r = k == first ? rk : num::hull(r, rk);
            z = k == first ? zk : num::hull(z, zk);
        }
        return {r * num::cos(phi), r * num::sin(phi), z};
    }

    SurfacePoint partials(uint32_t, double phi, double s) const override {
        const auto [k, t] = locate(s);
        const std::array<double, 4> b = bezier::basis(t), db = bezier::basisDerivative(t);
        const Segment& seg = segments_[k];
        double r = 0.0, z = 0.0, dr = 0.0, dz = 0.0;
        for (size_t i = 0; i < 4; ++i) {
            r += b[i] * seg.r[i];
            z += b[i] * seg.z[i];
            dr += db[i] * seg.r[i];  // ds = dt on every segment
            dz += db[i] * seg.z[i];
        }
        const double c = std::cos(phi), sn = std::sin(phi);
        return {DVec3(r * c, r * sn, z), DVec3(-r * sn, r * c, 0.0), DVec3(dr * c, dr * sn, dz)};
    }

    std::string describe() const override {
        return concat("surface of revolution (", points_, " profile points)");
    }

private:
    // The segment that evaluates parameter s: floor(s), clamped to the
    // segments (the end segments extrapolate beyond the domain).
    size_t segmentOf(double s) const {
        const double k = std::floor(s);
        if (!(k > 0.0)) return 0;  // also NaN
        return std::min(static_cast<size_t>(std::min(k, 1e18)), segments_.size() - 1);
    }

    template <class T>
    std::pair<size_t, T> locate(const T& s) const {
        const size_t k = segmentOf(valueOf(s));
        return {k, s - T(static_cast<double>(k))};
    }

    std::vector<Segment> segments_;
    size_t points_;
    ParamDomain domain_;
};

}  // namespace

ParametricSurfacePtr makeSurfaceOfRevolution(std::vector<glm::dvec2> profile) {
    const char* what = "surface of revolution";
    if (profile.size() < 2)
        fail(what, ": the profile needs at least 2 points (r, z), got ", profile.size());
    bool offAxis = false;
    for (size_t k = 0; k < profile.size(); ++k) {
        const glm::dvec2 p = profile[k];
        if (!(std::isfinite(p.x) && std::isfinite(p.y)))
            fail(what, ": profile point ", k, " (", p.x, ", ", p.y, ") is not finite");
        if (p.x < 0.0)
            fail(what, ": profile point ", k, " (", p.x, ", ", p.y,
                 ") has a negative radius; r must be >= 0");
        if (k > 0 && p == profile[k - 1])
            fail(what, ": profile points ", k - 1, " and ", k, " are equal (", p.x, ", ", p.y,
                 "); consecutive points must differ");
        offAxis = offAxis || p.x > 0.0;
    }
    if (!offAxis) fail(what, ": every profile point lies on the axis (r = 0)");
    return std::make_shared<Revolution>(profile);
}

}  // namespace strahl
