#pragma once
// World: everything the shading stage reads — meshes (indexed by geomID), their
// material bindings, lights, the background and the accelerator over the meshes.
// Built once by the scene module, then read-only and shared by all threads.

#include <memory>
#include <string>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/geometry/triangle_mesh.h"
#include "strahl/integrator/light.h"
#include "strahl/integrator/material.h"

namespace strahl {

struct MeshGeometry {
    std::string name;
    TriangleMesh mesh;
    // materialOfSlot[mesh.faceMaterials[prim]] indexes World::materials; a mesh
    // without face materials uses materialOfSlot[0].
    std::vector<uint32_t> materialOfSlot;
};

struct World {
    // Must not be resized once `accel` is built: Embree shares the vertex buffers.
    std::vector<MeshGeometry> meshes;
    std::vector<Material> materials;
    std::vector<Light> lights;
    Color background{0.0f};
    std::unique_ptr<Accel> accel;

    // The full surface interaction of a valid hit (two-phase intersection).
    SurfaceInteraction interaction(const Hit& hit) const {
        return triangleInteraction(meshes[hit.geomID].mesh, hit.primID, hit.u, hit.v);
    }
    const Material& material(const Hit& hit, const SurfaceInteraction& si) const {
        return materials[meshes[hit.geomID].materialOfSlot[si.materialSlot]];
    }
    Bounds3 bounds() const;
    size_t triangleCount() const;
    size_t meshMemoryBytes() const;
};

}  // namespace strahl
