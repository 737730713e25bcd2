// "torus": the ring torus around the z axis, major radius R, minor radius r.
// parametric_builtins.h and docs/parametric-surfaces.md give the parametrisation.
//
//   key            value                   default
//   major_radius   > minor_radius           1
//   minor_radius   > 0                      0.25

#include <array>
#include <string_view>

#include "parametric_builtin.h"

namespace strahl::parametric_detail {

class Torus final : public ParametricSurfaceOf<Torus> {
public:
    Torus(double R, double r) : R_(R), r_(r) { domain_ = {0.0, kTwoPi, 0.0, kTwoPi, true, true}; }

    template <class T>
    Point3<T> eval(uint32_t, const T& u, const T& v) const {
        const T ring = T(R_) + T(r_) * cos(v);
        return {ring * cos(u), ring * sin(u), T(r_) * sin(v)};
    }
    SurfacePoint partials(uint32_t, double u, double v) const override {
        const double su = std::sin(u), cu = std::cos(u), sv = std::sin(v), cv = std::cos(v);
        const double ring = R_ + r_ * cv;
        return {DVec3(ring * cu, ring * su, r_ * sv), DVec3(-ring * su, ring * cu, 0.0),
                DVec3(-r_ * sv * cu, -r_ * sv * su, r_ * cv)};
    }
    const ParamDomain& domain() const override { return domain_; }
    std::string describe() const override { return concat("torus R=", R_, " r=", r_); }

private:
    double R_, r_;
    ParamDomain domain_;
};

}  // namespace strahl::parametric_detail

namespace strahl {

ParametricSurfacePtr makeParametricTorus(double majorRadius, double minorRadius) {
    parametric_detail::requirePositive("major_radius", majorRadius);
    parametric_detail::requirePositive("minor_radius", minorRadius);
    if (!(minorRadius < majorRadius))
        fail("minor_radius (", minorRadius, ") must be below major_radius (", majorRadius,
             "): a self-intersecting torus has no single outside");
    return std::make_shared<parametric_detail::Torus>(majorRadius, minorRadius);
}

namespace {

ParametricSurfacePtr parseParametricTorus(const SurfaceParameters& p) {
    p.requireKeys({"type", "major_radius", "minor_radius"});
    const double R = p.number("major_radius", 1.0), r = p.number("minor_radius", 0.25);
    return p.checked([&] { return makeParametricTorus(R, r); });
}

constexpr std::array<std::string_view, 1> kParametricTorusNames = {"torus"};

}  // namespace

extern const ParametricKind kParametricTorus;
const ParametricKind kParametricTorus{kParametricTorusNames, &parseParametricTorus};

}  // namespace strahl
