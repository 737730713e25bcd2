#pragma once
// ParametricSurface: an explicit surface, the range {f(p₁, p₂) | (p₁, p₂) ∈ P}
// of a parameter function f: P ⊂ R² → R³ over a rectangular domain P. A ray
// o + t·d hits it where F(t, p₁, p₂) = o + t·d − f(p₁, p₂) = 0, and the normal
// there is n = ∂₁f × ∂₂f (docs/parametric-surfaces.md has the math).
//
// In code p₁ and p₂ are called u and v. A surface may be a set of patches that
// share one domain (the 32 bicubic Bézier patches of the Utah teapot, each over
// [0,1]²); a single surface is one patch. Domains may be periodic in u or v (the
// φ of a sphere): f(u0, v) = f(u1, v) then, and the seam is not an edge.
//
// Every surface is evaluated in three arithmetics:
//   double          f(u, v)                       points (tessellation, Newton)
//   num::Interval   ⊇ {f(u, v) | u ∈ U, v ∈ V}    conservative sub-patch bounds
//   Dual2           f, ∂u f and ∂v f              partials (automatic differentiation)
// Built-ins also give their partials by hand (partials()); the tests check them
// against the automatic ones. Surfaces are written once as a template
// `Point3<T> eval(uint32_t patch, const T& u, const T& v)` and made into a
// ParametricSurface by ParametricSurfaceOf<Derived>, so the three arithmetics
// cannot disagree about the formula.
//
// Surfaces are immutable and evaluated from many threads at once.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <glm/mat3x3.hpp>

#include "strahl/core/dual.h"
#include "strahl/core/interval.h"
#include "strahl/core/point3.h"
#include "strahl/geometry/surface_interaction.h"

namespace strahl {

using Dual2 = num::Dual<double, 2>;  // a value with its ∂/∂u and ∂/∂v

struct ParamDomain {
    double u0 = 0.0, u1 = 1.0;  // p₁ ∈ [u0, u1]
    double v0 = 0.0, v1 = 1.0;  // p₂ ∈ [v0, v1]
    // The edges u = u0 and u = u1 are one seam, not a border: f(u1, v) = f(u0, v),
    // or f(u1, v) = f(u0, v0 + v1 − v) if twistedU (a Möbius strip).
    bool periodicU = false;
    bool periodicV = false;  // f(u, v1) = f(u, v0)
    bool twistedU = false;

    double width() const { return u1 - u0; }
    double height() const { return v1 - v0; }
};

// A point of the surface with its first partial derivatives.
struct SurfacePoint {
    DVec3 p{0.0};
    DVec3 dpdu{0.0};
    DVec3 dpdv{0.0};
};

class ParametricSurface {
public:
    virtual ~ParametricSurface() = default;

    // Patches all share domain(); patch indices run over [0, patchCount()).
    virtual uint32_t patchCount() const { return 1; }
    virtual const ParamDomain& domain() const = 0;

    virtual Point3<double> evaluate(uint32_t patch, double u, double v) const = 0;
    virtual Point3<num::Interval> evaluate(uint32_t patch, const num::Interval& u,
                                           const num::Interval& v) const = 0;
    virtual Point3<Dual2> evaluate(uint32_t patch, const Dual2& u, const Dual2& v) const = 0;

    // f and its partials: by hand for built-ins, else automatic differentiation.
    virtual SurfacePoint partials(uint32_t patch, double u, double v) const {
        return automaticPartials(patch, u, v);
    }

    // A short description for messages and `strahl info`, e.g. "torus R=1 r=0.25".
    virtual std::string describe() const = 0;

    // ---- conveniences over evaluate() ---------------------------------------
    DVec3 point(uint32_t patch, double u, double v) const;
    SurfacePoint automaticPartials(uint32_t patch, double u, double v) const;

    // The unit normal ∂u f × ∂v f / ‖·‖ at (u, v). Where the cross product
    // vanishes (the pole of a sphere, the apex of a cone) it is the limit taken
    // from inside the domain: the normal a small step towards the domain's
    // centre. Returns a zero vector only if that limit does not exist either.
    DVec3 normal(uint32_t patch, double u, double v) const;
    // The unit ∂u f × ∂v f of partials already evaluated, or nullopt at a
    // singular point (where normal() takes the limit from inside instead).
    static std::optional<DVec3> regularNormal(const SurfacePoint& s);

    // The texture frame of a hit at (u, v) whose partials are s, for both
    // rendering modes: si.uv = (u, v) normalised over the domain (so a texture
    // wraps exactly at a periodic seam); by the chain rule ∂p/∂uv.x = width ·
    // ∂u f and ∂p/∂uv.y = height · ∂v f, mapped to world space by `linear`
    // (objectToWorld's linear part) into si.dpdu; si.uvDensity = 1 / sqrt(world
    // area per unit uv area), or left 0 where that area vanishes (a pole).
    void setTextureFrame(SurfaceInteraction& si, const SurfacePoint& s, double u, double v,
                         const glm::dmat3& linear) const;
};

// Implements the evaluate() overloads with Derived::eval<T>(patch, u, v).
template <class Derived>
class ParametricSurfaceOf : public ParametricSurface {
public:
    Point3<double> evaluate(uint32_t patch, double u, double v) const final {
        return self().eval(patch, u, v);
    }
    Point3<num::Interval> evaluate(uint32_t patch, const num::Interval& u,
                                   const num::Interval& v) const final {
        return self().eval(patch, u, v);
    }
    Point3<Dual2> evaluate(uint32_t patch, const Dual2& u, const Dual2& v) const final {
        return self().eval(patch, u, v);
    }

private:
    const Derived& self() const { return static_cast<const Derived&>(*this); }
};

using ParametricSurfacePtr = std::shared_ptr<const ParametricSurface>;

// The diagonal of the box around a 5 x 5 grid of points of every patch: the
// length that relative tolerances and error bounds are fractions of.
double parametricExtent(const ParametricSurface& surface);

// Throws strahl::Error naming the surface if its domain is empty, inverted or
// not finite, or if f or its partials are not finite at a grid of sample points
// (a formula that divides by zero inside its domain).
void validateParametricSurface(const ParametricSurface& surface);

}  // namespace strahl
