#pragma once
// World: everything the shading stage reads — shapes (indexed by geomID), their
// material bindings, lights, the background and the accelerator over the shapes.
// Built once by the scene module, then read-only and shared by all threads.

#include <memory>
#include <string>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/geometry/triangle_mesh.h"
#include "strahl/geometry/user_shape.h"
#include "strahl/integrator/light.h"
#include "strahl/integrator/material.h"

namespace strahl {

// A shape is either a triangle mesh or a user shape (implicit surface, directly
// intersected parametric surface) — exactly one of `mesh` and `user` is used.
struct SceneShape {
    std::string name;
    TriangleMesh mesh;                      // empty for user shapes
    std::shared_ptr<const UserShape> user;  // null for meshes
    // materialOfSlot[interaction.materialSlot] indexes World::materials; shapes
    // without face materials use materialOfSlot[0].
    std::vector<uint32_t> materialOfSlot;

    bool isMesh() const { return user == nullptr; }
    ShapeRef ref() const { return user ? ShapeRef{nullptr, user.get()} : ShapeRef{&mesh, nullptr}; }
};

struct World {
    // Must not be resized once `accel` is built: Embree shares the vertex buffers.
    std::vector<SceneShape> shapes;
    std::vector<Material> materials;
    std::vector<Light> lights;
    Color background{0.0f};
    std::unique_ptr<Accel> accel;

    // The full surface interaction of a valid hit (two-phase intersection).
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const {
        const SceneShape& shape = shapes[hit.geomID];
        if (shape.user) return shape.user->interaction(ray, hit);
        return triangleInteraction(shape.mesh, hit.primID, hit.u, hit.v);
    }
    const Material& material(const Hit& hit, const SurfaceInteraction& si) const {
        return materials[shapes[hit.geomID].materialOfSlot[si.materialSlot]];
    }
    // The list the accelerators are built over (geomID = index).
    std::vector<ShapeRef> shapeRefs() const;
    Bounds3 bounds() const;
    size_t triangleCount() const;  // of the meshes
    size_t userPrimitiveCount() const;
    size_t shapeMemoryBytes() const;
};

}  // namespace strahl
