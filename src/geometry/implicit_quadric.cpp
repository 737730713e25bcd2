// "quadric": any quadric (ellipsoid, cylinder, cone, paraboloid, hyperboloid,
// plane) from its ten coefficients; closed form. Most are unbounded: the shape
// needs a box.
// docs/implicit-surfaces.md has the derivations.
//
//   key            value                                           default
//   coefficients   {xx, yy, zz, xy, yz, xz, x, y, z, c}: finite     each 0

#include <array>
#include <memory>

#include "implicit_builtin.h"

namespace strahl::implicit_detail {

class Quadric final : public ImplicitSurfaceOf<Quadric> {
public:
    explicit Quadric(const QuadricCoefficients& q) : q_(q) {}

    template <class T>
    T eval(const Point3<T>& p) const {
        return q_.xx * sqr(p.x) + q_.yy * sqr(p.y) + q_.zz * sqr(p.z) + q_.xy * p.x * p.y +
               q_.yz * p.y * p.z + q_.xz * p.x * p.z + q_.x * p.x + q_.y * p.y + q_.z * p.z + q_.c;
    }
    DVec3 gradient(const DVec3& v) const override {
        return DVec3(2 * q_.xx * v.x + q_.xy * v.y + q_.xz * v.z + q_.x,
                     2 * q_.yy * v.y + q_.xy * v.x + q_.yz * v.z + q_.y,
                     2 * q_.zz * v.z + q_.yz * v.y + q_.xz * v.x + q_.z);
    }
    std::optional<Bounds3> bounds() const override { return std::nullopt; }
    bool hasClosedForm() const override { return true; }
    int closedFormRoots(const DVec3& o, const DVec3& d, double roots[4]) const override {
        // f(o + t d) = a t² + b t + c with a = f₂(d) (the quadratic part at d),
        // b = ∇f(o)·d, c = f(o).
        const double a = q_.xx * d.x * d.x + q_.yy * d.y * d.y + q_.zz * d.z * d.z +
                         q_.xy * d.x * d.y + q_.yz * d.y * d.z + q_.xz * d.x * d.z;
        const double b = glm::dot(gradient(o), d);
        const double c = eval(Point3<double>{o.x, o.y, o.z});
        return solveQuadratic(a, b, c, b * b - 4.0 * a * c, roots);
    }
    std::string describe() const override { return "quadric"; }

private:
    QuadricCoefficients q_;
};

}  // namespace strahl::implicit_detail

namespace strahl {

ImplicitSurfacePtr makeImplicitQuadric(const QuadricCoefficients& q) {
    const double all[] = {q.xx, q.yy, q.zz, q.xy, q.yz, q.xz, q.x, q.y, q.z, q.c};
    const char* names[] = {"xx", "yy", "zz", "xy", "yz", "xz", "x", "y", "z", "c"};
    bool anyNonZero = false;
    for (int i = 0; i < 10; ++i) {
        implicit_detail::requireFinite(names[i], all[i]);
        anyNonZero = anyNonZero || (i < 9 && all[i] != 0.0);
    }
    if (!anyNonZero) fail("quadric coefficients are all zero apart from the constant");
    return std::make_shared<implicit_detail::Quadric>(q);
}

namespace {

ImplicitSurfacePtr parseImplicitQuadric(const SurfaceParameters& p) {
    p.requireKeys({"type", "transform", "coefficients"});
    const auto c = p.child("coefficients");
    c->requireKeys({"xx", "yy", "zz", "xy", "yz", "xz", "x", "y", "z", "c"});
    QuadricCoefficients q;
    q.xx = c->number("xx", 0.0);
    q.yy = c->number("yy", 0.0);
    q.zz = c->number("zz", 0.0);
    q.xy = c->number("xy", 0.0);
    q.yz = c->number("yz", 0.0);
    q.xz = c->number("xz", 0.0);
    q.x = c->number("x", 0.0);
    q.y = c->number("y", 0.0);
    q.z = c->number("z", 0.0);
    q.c = c->number("c", 0.0);
    return p.checked([&] { return makeImplicitQuadric(q); });
}

constexpr std::array<std::string_view, 1> kImplicitQuadricNames = {"quadric"};

}  // namespace

extern const ImplicitKind kImplicitQuadric;
const ImplicitKind kImplicitQuadric{kImplicitQuadricNames, &parseImplicitQuadric};

}  // namespace strahl
