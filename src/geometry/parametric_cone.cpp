// "cone": the side of the cone of base radius r and apex at height h above it.
// parametric_builtins.h and docs/parametric-surfaces.md give the parametrisation.
//
//   key      value   default
//   radius   > 0     1
//   height   > 0     1

#include <array>
#include <string_view>

#include "parametric_builtin.h"

namespace strahl::parametric_detail {

class Cone final : public ParametricSurfaceOf<Cone> {
public:
    Cone(double r, double h) : r_(r), h_(h) { domain_ = {0.0, kTwoPi, 0.0, 1.0, true, false}; }

    template <class T>
    Point3<T> eval(uint32_t, const T& phi, const T& s) const {
        const T radius = T(r_) * (T(1.0) - s);
        return {radius * cos(phi), radius * sin(phi), T(h_) * s};
    }
    SurfacePoint partials(uint32_t, double phi, double s) const override {
        const double sp = std::sin(phi), cp = std::cos(phi), radius = r_ * (1.0 - s);
        return {DVec3(radius * cp, radius * sp, h_ * s), DVec3(-radius * sp, radius * cp, 0.0),
                DVec3(-r_ * cp, -r_ * sp, h_)};
    }
    const ParamDomain& domain() const override { return domain_; }
    std::string describe() const override { return concat("cone r=", r_, " h=", h_); }

private:
    double r_, h_;
    ParamDomain domain_;
};

}  // namespace strahl::parametric_detail

namespace strahl {

ParametricSurfacePtr makeParametricCone(double radius, double height) {
    parametric_detail::requirePositive("radius", radius);
    parametric_detail::requirePositive("height", height);
    return std::make_shared<parametric_detail::Cone>(radius, height);
}

namespace {

ParametricSurfacePtr parseParametricCone(const SurfaceParameters& p) {
    p.requireKeys({"type", "radius", "height"});
    const double r = p.number("radius", 1.0), h = p.number("height", 1.0);
    return p.checked([&] { return makeParametricCone(r, h); });
}

constexpr std::array<std::string_view, 1> kParametricConeNames = {"cone"};

}  // namespace

extern const ParametricKind kParametricCone;
const ParametricKind kParametricCone{kParametricConeNames, &parseParametricCone};

}  // namespace strahl
