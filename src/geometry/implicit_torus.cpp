// "torus": f = (x² + y² + z² + R² − r²)² − 4R²(x² + y²), around the z axis.
// docs/implicit-surfaces.md has the derivations.
//
//   key            value                         default
//   major_radius   > 0, centre to tube centre     1
//   minor_radius   > 0, the tube's                0.25

#include <array>
#include <memory>

#include "implicit_builtin.h"

namespace strahl::implicit_detail {

// The quartic is intersected by the generic interval root finder rather than a
// closed-form quartic solver: Ferrari's formulas lose most digits exactly where
// rays graze the tube, while interval isolation + Newton is both robust and
// accurate to the tolerance asked for.
class Torus final : public ImplicitSurfaceOf<Torus> {
public:
    Torus(double R, double r) : R_(R), r_(r) {}

    // The quartic (x² + y² + z² + R² − r²)² − 4R²ρ², ρ = √(x² + y²), evaluated
    // in its factored form ((ρ − R)² + z² − r²)·((ρ + R)² + z² − r²): the same
    // polynomial, but without the cancellation of two large squares, which in
    // interval arithmetic made almost every cell of the box look like it holds
    // surface. The second factor is ≥ R² − r² > 0, so the zero set is the
    // first factor's: the tube around the circle ρ = R.
    template <class T>
    T eval(const Point3<T>& p) const {
        const T rho = sqrt(sqr(p.x) + sqr(p.y));
        const T z2 = sqr(p.z) - r_ * r_;
        return (sqr(rho - R_) + z2) * (sqr(rho + R_) + z2);
    }
    DVec3 gradient(const DVec3& v) const override {
        const double s = glm::dot(v, v) + R_ * R_ - r_ * r_;
        return DVec3(4.0 * v.x * s - 8.0 * R_ * R_ * v.x, 4.0 * v.y * s - 8.0 * R_ * R_ * v.y,
                     4.0 * v.z * s);
    }
    std::optional<Bounds3> bounds() const override {
        const float outer = static_cast<float>(R_ + r_), tube = static_cast<float>(r_);
        return Bounds3{Vec3(-outer, -outer, -tube), Vec3(outer, outer, tube)};
    }
    std::string describe() const override { return concat("torus R=", R_, " r=", r_); }

private:
    double R_, r_;
};

}  // namespace strahl::implicit_detail

namespace strahl {

ImplicitSurfacePtr makeImplicitTorus(double majorRadius, double minorRadius) {
    implicit_detail::requirePositive("major_radius", majorRadius);
    implicit_detail::requirePositive("minor_radius", minorRadius);
    return std::make_shared<implicit_detail::Torus>(majorRadius, minorRadius);
}

namespace {

ImplicitSurfacePtr parseImplicitTorus(const SurfaceParameters& p) {
    p.requireKeys({"type", "transform", "major_radius", "minor_radius"});
    const double R = p.number("major_radius", 1.0), r = p.number("minor_radius", 0.25);
    return p.checked([&] { return makeImplicitTorus(R, r); });
}

constexpr std::array<std::string_view, 1> kImplicitTorusNames = {"torus"};

}  // namespace

extern const ImplicitKind kImplicitTorus;
const ImplicitKind kImplicitTorus{kImplicitTorusNames, &parseImplicitTorus};

}  // namespace strahl
