// "cylinder": the side of the cylinder of radius r around z, from z_min to z_max.
// parametric_builtins.h and docs/parametric-surfaces.md give the parametrisation.
//
//   key            value                 default
//   radius         > 0                    1
//   z_min, z_max   z_min < z_max           -1, 1

#include <array>
#include <string_view>

#include "parametric_builtin.h"

namespace strahl::parametric_detail {

class Cylinder final : public ParametricSurfaceOf<Cylinder> {
public:
    Cylinder(double r, double z0, double z1) : r_(r) { domain_ = {0.0, kTwoPi, z0, z1, true, false}; }

    template <class T>
    Point3<T> eval(uint32_t, const T& phi, const T& z) const {
        return {T(r_) * cos(phi), T(r_) * sin(phi), z};
    }
    SurfacePoint partials(uint32_t, double phi, double z) const override {
        const double s = std::sin(phi), c = std::cos(phi);
        return {DVec3(r_ * c, r_ * s, z), DVec3(-r_ * s, r_ * c, 0.0), DVec3(0.0, 0.0, 1.0)};
    }
    const ParamDomain& domain() const override { return domain_; }
    std::string describe() const override {
        return concat("cylinder r=", r_, " z=[", domain_.v0, ", ", domain_.v1, "]");
    }

private:
    double r_;
    ParamDomain domain_;
};

}  // namespace strahl::parametric_detail

namespace strahl {

ParametricSurfacePtr makeParametricCylinder(double radius, double zMin, double zMax) {
    parametric_detail::requirePositive("radius", radius);
    if (!(std::isfinite(zMin) && std::isfinite(zMax) && zMin < zMax))
        fail("z_min must be below z_max, both finite (got ", zMin, " and ", zMax, ")");
    return std::make_shared<parametric_detail::Cylinder>(radius, zMin, zMax);
}

namespace {

ParametricSurfacePtr parseParametricCylinder(const SurfaceParameters& p) {
    p.requireKeys({"type", "radius", "z_min", "z_max"});
    const double r = p.number("radius", 1.0), z0 = p.number("z_min", -1.0),
                 z1 = p.number("z_max", 1.0);
    return p.checked([&] { return makeParametricCylinder(r, z0, z1); });
}

constexpr std::array<std::string_view, 1> kParametricCylinderNames = {"cylinder"};

}  // namespace

extern const ParametricKind kParametricCylinder;
const ParametricKind kParametricCylinder{kParametricCylinderNames, &parseParametricCylinder};

}  // namespace strahl
