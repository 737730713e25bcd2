#pragma once
// ParametricShape: the direct mode of a parametric surface — no triangles; a
// ray is intersected with f itself by Newton's method, as a UserShape.
//
// Primitives: the cells of a ParametricGrid (sub-patches), each with a
// conservative box from interval evaluation of f over its parameter rectangle.
//
// Intersection (object space, double): solve
//     F(t, u, v) = o + t·d − f(u, v) = 0,   Jacobian J = [d, −∂u f, −∂v f],
// by Newton's method, seeded where the ray crosses the planes of the two
// triangles spanned by the sub-patch's corners (its planar approximation),
// and from the sub-patch's centre if neither seed converges. Iterates stay
// inside the sub-patch grown by a quarter on each side, so Newton cannot run
// off to another part of the surface or outside the domain. Where J is
// singular (a pole, a grazing ray) the step is the Levenberg–Marquardt one,
// (JᵀJ + λI)δ = −JᵀF, which stays finite and still converges to a root at a
// pole (‖F‖ → 0 with u or v undetermined).
//
// A root is accepted only if it converged (‖F‖ below the tolerance after
// polishing), lies in (tnear, tfar), and lies in the sub-patch's own half-open
// rectangle [u_a, u_b) × [v_a, v_b) — closed at a domain border that is not a
// seam, and wrapped (mirrored for a twisted seam) across periodic seams — so
// every point of the surface is owned by exactly one sub-patch: no double and
// no missing hits along sub-patch borders. Roots within 1e-9 of a sub-patch's
// width from a breakpoint are snapped onto it first, so two neighbours that
// find the same border root with different rounding still agree on its owner.
//
// Hit records: t, Ng (the exact normal), and in u, v the position inside the
// sub-patch, in [0, 1]²; interaction() re-evaluates f there in double.

#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "strahl/geometry/parametric_grid.h"
#include "strahl/geometry/parametric_surface.h"
#include "strahl/geometry/user_shape.h"

namespace strahl {

struct ParametricShapeOptions {
    // Sub-patches: a grid refined until each is nearly flat (chordal error
    // below this fraction of the surface's extent), which keeps the planar
    // seeds close to the root and a ray from crossing one sub-patch twice
    // except at grazing angles. 0: a uniform grid of initialSegments.
    double flatness = 2e-3;
    int initialSegments = 4;  // per patch and direction
    int maxSegments = 256;    // per patch and direction
    // Newton's convergence bound on ‖F‖ as a fraction of the surface's extent.
    double relativeTolerance = 1e-9;
    // The front is the other side: the normal is −∂u f × ∂v f.
    bool flipNormals = false;
};

class ParametricShape final : public UserShape {
public:
    // Throws strahl::Error if the transform is singular or not finite or the
    // surface's sub-patch bounds are not finite.
    ParametricShape(ParametricSurfacePtr surface, const Mat4& objectToWorld,
                    const ParametricShapeOptions& options);

    uint32_t primitiveCount() const override { return static_cast<uint32_t>(cells_.size()); }
    Bounds3 primitiveBounds(uint32_t prim) const override { return worldBounds_[prim]; }
    bool intersect(const Ray& ray, uint32_t prim, Hit& hit) const noexcept override;
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const override;
    Bounds3 bounds() const override { return bounds_; }
    std::string describe() const override;
    const char* primitiveNoun() const override { return "sub-patches"; }
    size_t memoryBytes() const override;

    const ParametricSurface& surface() const { return *surface_; }
    // Object-space distance below which ‖F‖ counts as converged.
    double tolerance() const { return tolerance_; }
    // The surface parameters (u, v) and patch of a hit this shape reported.
    DVec3 hitParameters(const Hit& hit) const;  // (u, v, patch)

private:
    struct Cell {
        uint32_t patch;
        double u0, u1, v0, v1;  // own rectangle
        bool closedU, closedV;  // whether u1 (v1) belongs to it: a border that is not a seam
        DVec3 corner[4];        // f at (u0,v0), (u1,v0), (u1,v1), (u0,v1): the planar seeds
        DVec3 boxMin, boxMax;   // object-space bounds (interval evaluation)
    };
    // A parameter rectangle inside a cell (the cell itself, or a quarter of a
    // quarter... where a grazing ray makes the search split it).
    struct Rect {
        double u0, u1, v0, v1;
        bool closedU, closedV;
    };
    struct Root {
        double t, u, v;
    };
    struct Best {
        Root root{0.0, 0.0, 0.0};
        float t = 0.0f;
        bool found = false;
    };

    void search(const Cell& cell, const Rect& rect, const DVec3 (&corner)[4], const DVec3& o,
                const DVec3& d, float tnear, Best& best, int depth) const noexcept;
    bool solve(const Cell& cell, const Rect& rect, const DVec3& o, const DVec3& d, double u,
               double v, double t, Root& root) const noexcept;
    bool owns(const Cell& cell, const Rect& rect, double& u, double& v) const noexcept;

    ParametricSurfacePtr surface_;
    glm::dmat4 toWorld_, toObject_;
    glm::dmat3 normalToWorld_;
    double tolerance_ = 0.0;
    std::vector<Cell> cells_;
    std::vector<Bounds3> worldBounds_;
    Bounds3 bounds_;
};

}  // namespace strahl
