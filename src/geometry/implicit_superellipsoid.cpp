// "superellipsoid": Barr's f = (|x/a|^(2/e2) + |y/b|^(2/e2))^(e2/e1) + |z/c|^(2/e1) − 1.
// docs/implicit-surfaces.md has the derivations.
//
//   key      value                                 default
//   radii    [a, b, c], each > 0                    [1, 1, 1]
//   e1, e2   exponents in [0.01, 10]                1, 1

#include <array>
#include <memory>

#include "implicit_builtin.h"

namespace strahl::implicit_detail {

class Superellipsoid final : public ImplicitSurfaceOf<Superellipsoid> {
public:
    Superellipsoid(const DVec3& radii, double e1, double e2)
        : radii_(radii), e1_(e1), e2_(e2), p_(2.0 / e2), q_(2.0 / e1), s_(e2 / e1) {}

    template <class T>
    T eval(const Point3<T>& v) const {
        const T planar = powr(abs(v.x / radii_.x), p_) + powr(abs(v.y / radii_.y), p_);
        return powr(planar, s_) + powr(abs(v.z / radii_.z), q_) - 1.0;
    }
    DVec3 gradient(const DVec3& v) const override {
        // d/dx |x/a|^p = p |x/a|^(p-1) sign(x) / a, zero at x = 0 for p > 1.
        auto term = [](double x, double a, double p) {
            if (x == 0.0) return 0.0;
            return p * std::pow(std::abs(x / a), p - 1.0) * (x > 0.0 ? 1.0 : -1.0) / a;
        };
        const double planar = std::pow(std::abs(v.x / radii_.x), p_) +
                              std::pow(std::abs(v.y / radii_.y), p_);
        const double outer = planar > 0.0 ? s_ * std::pow(planar, s_ - 1.0) : 0.0;
        return DVec3(outer * term(v.x, radii_.x, p_), outer * term(v.y, radii_.y, p_),
                     term(v.z, radii_.z, q_));
    }
    std::optional<Bounds3> bounds() const override {
        const Vec3 r(radii_);
        return Bounds3{-r, r};
    }
    std::string describe() const override {
        return concat("superellipsoid e1=", e1_, " e2=", e2_);
    }

private:
    DVec3 radii_;
    double e1_, e2_, p_, q_, s_;
};

}  // namespace strahl::implicit_detail

namespace strahl {

ImplicitSurfacePtr makeSuperellipsoid(const DVec3& radii, double e1, double e2) {
    implicit_detail::requirePositive("radii.x", radii.x);
    implicit_detail::requirePositive("radii.y", radii.y);
    implicit_detail::requirePositive("radii.z", radii.z);
    implicit_detail::requirePositive("e1", e1);
    implicit_detail::requirePositive("e2", e2);
    // Exponents 2/e must stay representable: below 0.01 the surface is a box to
    // within rounding and the powers overflow.
    if (e1 < 0.01 || e2 < 0.01 || e1 > 10.0 || e2 > 10.0)
        fail("superellipsoid exponents e1, e2 must lie in [0.01, 10]");
    return std::make_shared<implicit_detail::Superellipsoid>(radii, e1, e2);
}

namespace {

ImplicitSurfacePtr parseImplicitSuperellipsoid(const SurfaceParameters& p) {
    p.requireKeys({"type", "transform", "radii", "e1", "e2"});
    const DVec3 r = p.vec3("radii", DVec3(1.0));
    const double e1 = p.number("e1", 1.0), e2 = p.number("e2", 1.0);
    return p.checked([&] { return makeSuperellipsoid(r, e1, e2); });
}

constexpr std::array<std::string_view, 1> kImplicitSuperellipsoidNames = {"superellipsoid"};

}  // namespace

extern const ImplicitKind kImplicitSuperellipsoid;
const ImplicitKind kImplicitSuperellipsoid{kImplicitSuperellipsoidNames,
                                           &parseImplicitSuperellipsoid};

}  // namespace strahl
