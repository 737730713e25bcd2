// "mobius": the Möbius strip of centre-line radius R and half-width w.
// parametric_builtins.h and docs/parametric-surfaces.md give the parametrisation.
//
//   key          value        default
//   radius       > 0          1
//   half_width   < radius     0.3

#include <array>
#include <string_view>

#include "parametric_builtin.h"

namespace strahl::parametric_detail {

class Mobius final : public ParametricSurfaceOf<Mobius> {
public:
    Mobius(double R, double w) : R_(R) {
        domain_ = {0.0, kTwoPi, -w, w, true, false};
        domain_.twistedU = true;
    }

    template <class T>
    Point3<T> eval(uint32_t, const T& u, const T& s) const {
        const T half = T(0.5) * u;
        const T ring = T(R_) + s * cos(half);
        return {ring * cos(u), ring * sin(u), s * sin(half)};
    }
    SurfacePoint partials(uint32_t, double u, double s) const override {
        const double su = std::sin(u), cu = std::cos(u);
        const double sh = std::sin(0.5 * u), ch = std::cos(0.5 * u);
        const double ring = R_ + s * ch;
        // d(ring)/du = −s sin(u/2)/2
        const double dring = -0.5 * s * sh;
        return {DVec3(ring * cu, ring * su, s * sh),
                DVec3(dring * cu - ring * su, dring * su + ring * cu, 0.5 * s * ch),
                DVec3(ch * cu, ch * su, sh)};
    }
    const ParamDomain& domain() const override { return domain_; }
    std::string describe() const override {
        return concat("mobius R=", R_, " w=", domain_.v1);
    }

private:
    double R_;
    ParamDomain domain_;
};

}  // namespace strahl::parametric_detail

namespace strahl {

ParametricSurfacePtr makeMobiusStrip(double radius, double halfWidth) {
    parametric_detail::requirePositive("radius", radius);
    parametric_detail::requirePositive("half_width", halfWidth);
    if (!(halfWidth < radius))
        fail("half_width (", halfWidth, ") must be below radius (", radius, ")");
    return std::make_shared<parametric_detail::Mobius>(radius, halfWidth);
}

namespace {

ParametricSurfacePtr parseParametricMobius(const SurfaceParameters& p) {
    p.requireKeys({"type", "radius", "half_width"});
    const double R = p.number("radius", 1.0), w = p.number("half_width", 0.3);
    return p.checked([&] { return makeMobiusStrip(R, w); });
}

constexpr std::array<std::string_view, 1> kParametricMobiusNames = {"mobius"};

}  // namespace

extern const ParametricKind kParametricMobius;
const ParametricKind kParametricMobius{kParametricMobiusNames, &parseParametricMobius};

}  // namespace strahl
