#pragma once
// UserShape: a shape that finds its own ray hits — implicit surfaces, directly
// intersected parametric patches — instead of being handed to the accelerator
// as triangles. An accelerator sees it as primitiveCount() independent
// primitives with conservative boxes: Embree through one generic user-geometry
// adapter (accel/), the naive tracer (reference/) by calling intersect() on
// every primitive. Both call exactly this code, so they agree by construction.
// The exceptions are a CurveSet (curve_set.h) and a SubdivisionSurface
// (subdivision_surface.h): Embree intersects them with its own native
// geometry, and intersect() is then the independent reference the naive
// tracer uses and the agreement tests compare against.
//
// Two-phase intersection: intersect() fills only the preliminary Hit (t, u, v,
// Ng); shading later asks interaction() for the full SurfaceInteraction of the
// closest hit. What u and v mean is the shape's own business (an implicit
// surface stores its root's t-uncertainty in u, so the solver tolerance travels
// with the hit to the ray-spawning code).
//
// Thread safety and exceptions: intersect() and occluded() are called from
// many threads at once and from inside Embree, so they are const, lock-free and
// noexcept.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "strahl/core/bounds.h"
#include "strahl/core/ray.h"
#include "strahl/geometry/cutout.h"
#include "strahl/geometry/surface_interaction.h"
#include "strahl/geometry/triangle_mesh.h"

namespace strahl {

class CurveSet;
class SubdivisionSurface;

class UserShape {
public:
    virtual ~UserShape() = default;

    virtual uint32_t primitiveCount() const = 0;
    // Finite and conservative: every hit on primitive `prim` lies inside.
    virtual Bounds3 primitiveBounds(uint32_t prim) const = 0;

    // The nearest hit on primitive `prim` with ray.tnear < t < ray.tfar. On a hit
    // writes hit.t, hit.u, hit.v and hit.Ng (unnormalised is fine) and returns
    // true; the IDs are the caller's job. On a miss leaves `hit` untouched.
    virtual bool intersect(const Ray& ray, uint32_t prim, Hit& hit) const noexcept = 0;
    // Whether primitive `prim` has any hit with ray.tnear < t < ray.tfar.
    virtual bool occluded(const Ray& ray, uint32_t prim) const noexcept {
        Hit hit;
        return intersect(ray, prim, hit);
    }

    // The full interaction for a hit this shape reported for `ray`.
    virtual SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const = 0;

    // Union of the primitive boxes.
    virtual Bounds3 bounds() const;
    // For messages and `strahl info`: what the shape is ("implicit torus R=1
    // r=0.25") and what its primitives are called ("cells").
    virtual std::string describe() const { return "user shape"; }
    virtual const char* primitiveNoun() const { return "primitives"; }
    // Bytes held by the shape (its own tables, not counting the accelerator).
    virtual size_t memoryBytes() const = 0;
    // The curves, if this shape is a CurveSet (which Embree intersects
    // natively); null for every other shape.
    virtual const CurveSet* asCurves() const { return nullptr; }
    // The surface, if this shape is a SubdivisionSurface (which Embree
    // tessellates natively); null for every other shape.
    virtual const SubdivisionSurface* asSubdivision() const { return nullptr; }
};

// One entry of the list an accelerator is built over: exactly one of mesh and
// user is set. Its position in the list is the geomID the accelerator
// reports. A mesh may have a cut-out (null: solid everywhere).
struct ShapeRef {
    const TriangleMesh* mesh = nullptr;
    const UserShape* user = nullptr;
    const Cutout* cutout = nullptr;

    Bounds3 bounds() const { return mesh ? mesh->bounds() : user->bounds(); }
};

// The list for a scene of meshes only.
std::vector<ShapeRef> meshShapeRefs(std::span<const TriangleMesh* const> meshes);

}  // namespace strahl
