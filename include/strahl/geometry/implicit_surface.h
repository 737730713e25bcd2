#pragma once
// ImplicitSurface: a function f: R³ → R whose kernel {x | f(x) = 0} is the
// surface; f < 0 is the inside, and the outward normal is ∇f/‖∇f‖.
//
// Every implicit surface can be evaluated in four arithmetics, which is all
// the root finder and the shading need:
//   double      f(x)                            point values (refinement)
//   Interval    f(X) ⊇ {f(x) | x ∈ X}           culling cells, isolating roots
//   Gradient3   f(x) and ∇f(x)                  normals (automatic differentiation)
//   RayDual     F(T) and F'(T) on a ray segment root isolation: F(t) = f(o + t·d)
// Built-ins also give their gradient by hand (gradient()); the tests check it
// against the automatic one.
//
// Surfaces are written once as a template `T eval(const Point<T>&)` and made
// into an ImplicitSurface by ImplicitSurfaceOf<Derived> (below), so the four
// arithmetics can never disagree about the formula.
//
// Functions work in double: a quartic such as the torus loses all its digits to
// cancellation in float near the surface.

#include <memory>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "strahl/core/bounds.h"
#include "strahl/core/dual.h"
#include "strahl/core/interval.h"
#include "strahl/core/point3.h"

namespace strahl {

using IntervalBox = Point3<num::Interval>;

class ImplicitSurface {
public:
    virtual ~ImplicitSurface() = default;

    virtual double evaluate(const Point3<double>& p) const = 0;
    virtual num::Interval evaluate(const IntervalBox& box) const = 0;
    virtual num::Gradient3 evaluate(const Point3<num::Gradient3>& p) const = 0;
    virtual num::RayDual evaluate(const Point3<num::RayDual>& p) const = 0;

    // A box that contains the whole surface, if the function knows one (a
    // sphere does, a plane or a formula does not).
    virtual std::optional<Bounds3> bounds() const = 0;

    // The gradient: by hand for built-ins, else automatic differentiation.
    virtual DVec3 gradient(const DVec3& x) const { return automaticGradient(x); }

    // Whether the ray roots have a closed form (sphere, quadric); if not, the
    // generic root finder is used.
    virtual bool hasClosedForm() const { return false; }
    // With a closed form: the real roots of f(o + t·d) in increasing order, and
    // how many there are.
    virtual int closedFormRoots(const DVec3& /*o*/, const DVec3& /*d*/, double /*roots*/[4]) const {
        return 0;
    }

    // A short description for messages and `strahl info`, e.g. "torus R=1 r=0.25".
    virtual std::string describe() const = 0;

    // ---- conveniences over evaluate() ---------------------------------------
    double value(const DVec3& x) const { return evaluate(Point3<double>{x.x, x.y, x.z}); }
    num::Interval range(const IntervalBox& box) const { return evaluate(box); }
    num::Interval range(const Bounds3& box) const;
    DVec3 automaticGradient(const DVec3& x) const;
    // F(t) = f(o + t·d) and F'(t) = ∇f·d for all t in `t`.
    num::RayDual alongRay(const DVec3& o, const DVec3& d, const num::Interval& t) const;
};

// Implements the four evaluate() overloads with Derived::eval<T>(const Point3<T>&).
template <class Derived>
class ImplicitSurfaceOf : public ImplicitSurface {
public:
    double evaluate(const Point3<double>& p) const final { return self().eval(p); }
    num::Interval evaluate(const IntervalBox& p) const final { return self().eval(p); }
    num::Gradient3 evaluate(const Point3<num::Gradient3>& p) const final {
        return self().eval(p);
    }
    num::RayDual evaluate(const Point3<num::RayDual>& p) const final { return self().eval(p); }

private:
    const Derived& self() const { return static_cast<const Derived&>(*this); }
};

using ImplicitSurfacePtr = std::shared_ptr<const ImplicitSurface>;

}  // namespace strahl
