#pragma once
// ImplicitShape: an implicit surface placed in the world, as a UserShape.
//
// The surface's domain — its own bounds, clipped to the shape's box — is cut
// into a grid of cells, and only cells whose interval range contains 0 are kept
// (a proof that the others hold no surface). Each kept cell is one primitive,
// so the BVH culls empty space and a ray searches only the cells it crosses.
// Surfaces with a closed form (sphere, quadric) are one primitive.
//
// Intersection happens in object space, in double: the ray is mapped by the
// inverse transform (t is unchanged by an affine map), clipped to the cell, and
// handed to the closed form or to findFirstRoot(). The hit stores the root's
// t-uncertainty in Hit::u, and interaction() turns it into the point's error
// bound, so secondary rays are offset by exactly the solver's tolerance.
//
// Normals are n = ∇f/‖∇f‖ mapped by the inverse transpose, pointing to f > 0
// (outside). Where the gradient vanishes or is not finite (a cusp, the apex of
// a cone) the normal faces the incoming ray instead: never NaN.

#include <optional>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "strahl/geometry/implicit_root_finder.h"
#include "strahl/geometry/implicit_surface.h"
#include "strahl/geometry/user_shape.h"

namespace strahl {

struct ImplicitShapeOptions {
    std::optional<Bounds3> box;    // object-space clip box; required if the surface has no bounds
    int cellsPerAxis = 0;          // 0: automatic — 1 with a closed form, else 32
    // Root tolerance as a fraction of the domain's diagonal: 1e-6 keeps hit
    // points well inside the 1e-5 relative accuracy tested, and stays above the
    // double-precision noise of high-degree polynomials.
    double relativeTolerance = 1e-6;
};

class ImplicitShape final : public UserShape {
public:
    // Throws strahl::Error if the domain is not finite, the transform is
    // singular or not finite, or no cell of the domain can contain the surface.
    ImplicitShape(ImplicitSurfacePtr surface, const Mat4& objectToWorld,
                  const ImplicitShapeOptions& options);

    uint32_t primitiveCount() const override { return static_cast<uint32_t>(cells_.size()); }
    Bounds3 primitiveBounds(uint32_t prim) const override { return worldBounds_[prim]; }
    bool intersect(const Ray& ray, uint32_t prim, Hit& hit) const noexcept override;
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const override;
    Bounds3 bounds() const override { return bounds_; }
    std::string describe() const override;
    const char* primitiveNoun() const override { return "cells"; }
    size_t memoryBytes() const override;

    const ImplicitSurface& surface() const { return *surface_; }
    // Root tolerance in object-space distance.
    double tolerance() const { return tolerance_; }
    // The object-space domain the cells tile.
    const DVec3& domainMin() const { return domainMin_; }
    const DVec3& domainMax() const { return domainMax_; }

private:
    struct Cell {
        DVec3 min, max;  // object space
    };

    // The first closed-form root inside the cell's [t0, t1] and the ray's
    // (tnear, tfar), its error still to be estimated.
    std::optional<ImplicitRoot> closedFormRoot(const Ray& ray, const DVec3& o, const DVec3& d,
                                               double t0, double t1) const noexcept;
    // The first root findFirstRoot() finds there, to the shape's tolerance.
    std::optional<ImplicitRoot> searchedRoot(const Ray& ray, const DVec3& o, const DVec3& d,
                                             double t0, double t1) const noexcept;

    ImplicitSurfacePtr surface_;
    glm::dmat4 toObject_;
    glm::dmat3 toWorldLinear_, normalToWorld_;
    DVec3 domainMin_, domainMax_;
    double tolerance_ = 0.0;
    bool closedForm_ = false;
    std::vector<Cell> cells_;
    std::vector<Bounds3> worldBounds_;
    Bounds3 bounds_;  // union of worldBounds_
};

}  // namespace strahl
