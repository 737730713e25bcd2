#pragma once
// World: everything the shading stage reads — shapes (indexed by geomID), their
// material bindings, lights, the background and the accelerator over the shapes.
// Built once by the scene module, then read-only and shared by all threads.

#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/geometry/parametric_tessellation.h"
#include "strahl/geometry/triangle_mesh.h"
#include "strahl/geometry/user_shape.h"
#include "strahl/integrator/light.h"
#include "strahl/material/material.h"
#include "strahl/texture/texture_system.h"

namespace strahl {

// A shape is either a triangle mesh or a user shape (implicit surface, directly
// intersected parametric surface) — exactly one of `mesh` and `user` is used.
struct SceneShape {
    std::string name;
    TriangleMesh mesh;                      // empty for user shapes
    std::shared_ptr<const UserShape> user;  // null for meshes
    // A mesh that tessellates a parametric surface: maps its hits back to the
    // surface for exact normals and (u, v). Null for other shapes.
    std::shared_ptr<const TessellatedSurface> tessellated;
    // materialOfSlot[interaction.materialSlot] indexes World::materials; shapes
    // without face materials use materialOfSlot[0].
    std::vector<uint32_t> materialOfSlot;
    // The alpha cut-out of a mesh whose materials have an opacity (set by
    // World::prepareCutouts), null otherwise.
    std::shared_ptr<const Cutout> cutout;

    bool isMesh() const { return user == nullptr; }
    ShapeRef ref() const {
        return user ? ShapeRef{nullptr, user.get(), nullptr} : ShapeRef{&mesh, nullptr, cutout.get()};
    }
};

// The first error a cut-out met inside the accelerator (a texture lookup
// that failed), which cannot throw there: kept, and rethrown by the renderer.
class CutoutErrors {
public:
    void record(std::exception_ptr error) noexcept;
    void rethrow() const;  // the recorded error, if any

private:
    mutable std::mutex mutex_;
    std::atomic<bool> failed_{false};
    std::exception_ptr first_;
};

// Shapes stored once and placed any number of times by instances (a group of
// the scene file, with nested groups flattened into instances by the builder).
struct Prototype {
    std::string name;
    std::vector<SceneShape> shapes;  // a hit's geomID indexes this list
};

struct SceneInstance {
    uint32_t prototype = 0;  // index into World::prototypes
    Mat4 objectToWorld{1.0f};  // a moving instance's: its first keyframe's
    Mat4 worldToObject{1.0f};
    Mat3 normalToWorld{1.0f};  // inverse transpose of objectToWorld's linear part
    // Empty at rest; else the keyframes (core/motion.h) that place it at a
    // ray's time, and the three matrices above are only its first keyframe's.
    std::vector<Mat4> motion;

    SceneInstance() = default;
    SceneInstance(uint32_t prototypeIndex, const Mat4& toWorld);
    SceneInstance(uint32_t prototypeIndex, std::vector<Mat4> keyframes);

    bool moves() const { return !motion.empty(); }
};

struct World {
    // None of these may be resized once `accel` is built: Embree shares the
    // vertex buffers.
    std::vector<SceneShape> shapes;  // top level: geomID = index
    std::vector<Prototype> prototypes;
    std::vector<SceneInstance> instances;  // instance k has instID shapes.size() + k
    // Not to be resized once prepareLights() ran either: textured triangle
    // lights point at their material.
    std::vector<Material> materials;
    std::vector<Light> lights;  // explicit lights: point, spot, projector, directional, environment
    Color background{0.0f};     // radiance of escaping rays: a constant sky light
    LightSelection lightSelection = LightSelection::Power;  // read by prepareLights()
    std::unique_ptr<Accel> accel;
    std::unique_ptr<TextureSystem> textures;  // null when no material uses a texture
    // Every light the integrators sample: `lights`, the sky of `background`
    // and one triangle light per triangle with uniform emission or emission
    // patterned through its uvs (top level and in each instance). Built by
    // prepareLights() once shapes, instances and materials are final.
    LightSet lightSet;

    void prepareLights();
    // Gives every mesh whose materials have an opacity its Cutout; call once
    // shapes, materials and textures are final and before `accel` is built.
    // Throws strahl::Error for a user shape with such a material, or a
    // textured opacity on a mesh without texture coordinates.
    void prepareCutouts();
    // Throws the first error a cut-out met while tracing, if any (call after
    // ray queries, outside the accelerator).
    void rethrowCutoutError() const;
    bool lightsPrepared() const { return lightsPrepared_; }
    // Whether a ray can meet any emission: an infinite light, or a material
    // that emits (set by prepareLights). When not, rays traced only for the
    // emission they find can be skipped.
    bool emissionReachable() const { return emissionReachable_; }
    // The lightSet index of the emissive triangle a valid hit lies on, or
    // kInvalidId if it is not an area light (no emission, emission mapped
    // triplanar or on a tessellated surface, or a user shape: those are found
    // by BSDF sampling only).
    uint32_t areaLightOf(const Hit& hit) const;
    // Radiance a ray escaping in direction dir receives (all infinite lights).
    Color escapedRadiance(const Vec3& dir) const;

    // The instance a valid hit lies in, or null for a top-level shape.
    const SceneInstance* instance(const Hit& hit) const {
        return hit.instID == kInvalidId ? nullptr : &instances[hit.instID - shapes.size()];
    }
    // The shape a valid hit lies on.
    const SceneShape& shape(const Hit& hit) const {
        const SceneInstance* inst = instance(hit);
        return inst ? prototypes[inst->prototype].shapes[hit.geomID] : shapes[hit.geomID];
    }
    // The full surface interaction of a valid hit (two-phase intersection), in
    // world space.
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const;
    const Material& material(const Hit& hit, const SurfaceInteraction& si) const {
        return materials[shape(hit).materialOfSlot[si.materialSlot]];
    }
    // What the accelerators are built over (the IDs of accel.h).
    AccelScene accelScene() const;
    Bounds3 bounds() const;
    // Stored once: the meshes' triangles and the user shapes' primitives, top
    // level and prototypes.
    size_t triangleCount() const;
    size_t userPrimitiveCount() const;
    // As rendered: every instance counts its prototype's triangles again.
    size_t instancedTriangleCount() const;
    size_t shapeMemoryBytes() const;
    // Whether some instance moves or some mesh deforms (camera rays then
    // sample the shutter).
    bool hasMotion() const;

private:
    // (instID, geomID) of an emitting shape -> offset into areaLightOfPrim_,
    // which holds the light index of each of its triangles (or kInvalidId).
    std::unordered_map<uint64_t, uint32_t> emitterOffset_;
    std::vector<uint32_t> areaLightOfPrim_;
    bool lightsPrepared_ = false;
    bool emissionReachable_ = true;
    std::unique_ptr<CutoutErrors> cutoutErrors_;
};

}  // namespace strahl
