// "sphere": f = x² + y² + z² − r², with a closed-form, cancellation-free ray
// intersection.
// docs/implicit-surfaces.md has the derivations.
//
//   key      value                    default
//   radius   > 0                      1

#include <array>
#include <memory>

#include "implicit_builtin.h"

namespace strahl::implicit_detail {

class Sphere final : public ImplicitSurfaceOf<Sphere> {
public:
    explicit Sphere(double r) : r_(r) {}

    template <class T>
    T eval(const Point3<T>& p) const {
        return sqr(p.x) + sqr(p.y) + sqr(p.z) - r_ * r_;
    }
    DVec3 gradient(const DVec3& x) const override { return 2.0 * x; }
    std::optional<Bounds3> bounds() const override {
        const float r = static_cast<float>(r_);
        return Bounds3{Vec3(-r), Vec3(r)};
    }
    bool hasClosedForm() const override { return true; }
    int closedFormRoots(const DVec3& o, const DVec3& d, double roots[4]) const override {
        // Δ/4 = (o·d)² − |d|²(|o|² − r²) loses every digit when the ray starts
        // far away; the equal form |d|²(r² − |o − (o·d/|d|²) d|²) measures the
        // distance of the ray to the centre directly (Haines et al., "Precision
        // Improvements for Ray/Sphere Intersection", Ray Tracing Gems ch. 7).
        const double a = glm::dot(d, d), halfB = glm::dot(o, d);
        const DVec3 closest = o - (halfB / a) * d;
        const double disc = a * (r_ * r_ - glm::dot(closest, closest));
        return solveQuadratic(a, 2.0 * halfB, glm::dot(o, o) - r_ * r_, 4.0 * disc, roots);
    }
    std::string describe() const override { return concat("sphere r=", r_); }

private:
    double r_;
};

}  // namespace strahl::implicit_detail

namespace strahl {

ImplicitSurfacePtr makeImplicitSphere(double radius) {
    implicit_detail::requirePositive("radius", radius);
    return std::make_shared<implicit_detail::Sphere>(radius);
}

namespace {

ImplicitSurfacePtr parseImplicitSphere(const SurfaceParameters& p) {
    p.requireKeys({"type", "transform", "radius"});
    const double r = p.number("radius", 1.0);
    return p.checked([&] { return makeImplicitSphere(r); });
}

constexpr std::array<std::string_view, 1> kImplicitSphereNames = {"sphere"};

}  // namespace

extern const ImplicitKind kImplicitSphere;
const ImplicitKind kImplicitSphere{kImplicitSphereNames, &parseImplicitSphere};

}  // namespace strahl
