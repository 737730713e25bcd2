// "sphere": the sphere of radius r, parametrised by the polar angle and the azimuth.
// parametric_builtins.h and docs/parametric-surfaces.md give the parametrisation.
//
//   key      value   default
//   radius   > 0     1

#include <array>
#include <string_view>

#include "parametric_builtin.h"

namespace strahl::parametric_detail {

class Sphere final : public ParametricSurfaceOf<Sphere> {
public:
    explicit Sphere(double r) : r_(r) { domain_ = {0.0, num::kPiD, 0.0, kTwoPi, false, true}; }

    template <class T>
    Point3<T> eval(uint32_t, const T& rho, const T& phi) const {
        const T s = sin(rho);
        return {T(r_) * s * cos(phi), T(r_) * s * sin(phi), T(r_) * cos(rho)};
    }
    SurfacePoint partials(uint32_t, double rho, double phi) const override {
        const double sr = std::sin(rho), cr = std::cos(rho), sp = std::sin(phi), cp = std::cos(phi);
        return {r_ * DVec3(sr * cp, sr * sp, cr), r_ * DVec3(cr * cp, cr * sp, -sr),
                r_ * DVec3(-sr * sp, sr * cp, 0.0)};
    }
    const ParamDomain& domain() const override { return domain_; }
    std::string describe() const override { return concat("sphere r=", r_); }

private:
    double r_;
    ParamDomain domain_;
};

}  // namespace strahl::parametric_detail

namespace strahl {

ParametricSurfacePtr makeParametricSphere(double radius) {
    parametric_detail::requirePositive("radius", radius);
    return std::make_shared<parametric_detail::Sphere>(radius);
}

namespace {

ParametricSurfacePtr parseParametricSphere(const SurfaceParameters& p) {
    p.requireKeys({"type", "radius"});
    const double r = p.number("radius", 1.0);
    return p.checked([&] { return makeParametricSphere(r); });
}

constexpr std::array<std::string_view, 1> kParametricSphereNames = {"sphere"};

}  // namespace

extern const ParametricKind kParametricSphere;
const ParametricKind kParametricSphere{kParametricSphereNames, &parseParametricSphere};

}  // namespace strahl
