#pragma once
// Accel: the ray-query interface every tracer of strahl implements — Embree's
// BVH here, the naive loop over all primitives in the reference module. Callers
// never see Embree types: packets are strahl's own SoA layout (core/packet.h).
//
// Geometry IDs are stable and computable: the i-th top-level shape handed to a
// builder has geomID i, and primID is the triangle index within a mesh or the
// primitive index within a user shape. With instancing (AccelScene), instance k
// has the top-level ID shapes.size() + k, reported as Hit::instID; geomID then
// indexes the instanced prototype's own shape list (see Hit in core/ray.h).

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "strahl/accel/quad_faces.h"
#include "strahl/core/bounds.h"
#include "strahl/core/math.h"
#include "strahl/core/motion.h"
#include "strahl/core/packet.h"
#include "strahl/core/transform.h"
#include "strahl/core/ray.h"
#include "strahl/geometry/triangle_mesh.h"
#include "strahl/geometry/user_shape.h"

namespace strahl {

// How camera packets should be traced.
enum class RayCoherence { Coherent, Incoherent };

class Accel {
public:
    virtual ~Accel() = default;

    // Closest hit in (ray.tnear, ray.tfar); an invalid Hit if none.
    virtual Hit intersect(const Ray& ray) const = 0;
    // Any hit in (ray.tnear, ray.tfar).
    virtual bool occluded(const Ray& ray) const = 0;

    // Packet queries: lanes with valid[i] == -1 are traced, 0 are ignored. On
    // return a lane's geomID is kInvalidId for a miss; otherwise tfar, u, v, Ng,
    // primID and geomID describe the closest hit.
    virtual void intersect8(const int* valid, RayHitPacket8& packet, RayCoherence c) const = 0;
    virtual void intersect16(const int* valid, RayHitPacket16& packet, RayCoherence c) const = 0;

    // intersect8/16 under one name, for code templated on the packet width.
    void intersectPacket(const int* valid, RayHitPacket8& packet, RayCoherence c) const {
        intersect8(valid, packet, c);
    }
    void intersectPacket(const int* valid, RayHitPacket16& packet, RayCoherence c) const {
        intersect16(valid, packet, c);
    }

    // The widest packet the implementation traces natively (16, 8 or 1).
    virtual int nativePacketWidth() const = 0;

    virtual Bounds3 bounds() const = 0;
    // Bytes held by the acceleration structure itself (not the meshes).
    virtual size_t memoryBytes() const = 0;
};

// One placement of a prototype.
struct AccelInstance {
    uint32_t prototype = 0;    // index into AccelScene::prototypes
    Mat4 objectToWorld{1.0f};  // affine and invertible; a moving instance's first keyframe
    // Empty for an instance at rest; else its keyframes (at least two, each
    // affine and invertible), placed at the ray's time (core/motion.h).
    std::vector<Mat4> motion;

    AccelInstance() = default;
    AccelInstance(uint32_t prototypeIndex, const Mat4& toWorld, std::vector<Mat4> keyframes = {})
        : prototype(prototypeIndex), objectToWorld(toWorld), motion(std::move(keyframes)) {}

    bool moves() const { return !motion.empty(); }
    Mat4 objectToWorldAt(float time) const { return moves() ? keyframeAt(motion, time) : objectToWorld; }
    Bounds3 boundsOf(const Bounds3& objectBounds) const {
        return moves() ? keyframeBounds(motion, objectBounds) : transformBounds(objectToWorld, objectBounds);
    }
};

// What an accelerator is built over: top-level shapes plus instancing — each
// prototype is a list of shapes stored (and, for Embree, given a BVH) once and
// placed by any number of instances. One level: prototypes hold no instances
// (the scene builder flattens nested groups).
struct AccelScene {
    std::vector<ShapeRef> shapes;                  // geomID = index
    std::vector<std::vector<ShapeRef>> prototypes;  // geomID = index within the prototype
    std::vector<AccelInstance> instances;          // instID = shapes.size() + index

    uint32_t instanceId(size_t instance) const {
        return static_cast<uint32_t>(shapes.size() + instance);
    }
};

// Embree's BVH builders (docs/memory.md compares them): Low is the Morton
// builder (fastest build, slower rays), Medium binned SAH (the default), High
// SAH with spatial splits (slowest build, fastest rays, more memory).
enum class BvhQuality { Low, Medium, High };

const char* bvhQualityName(BvhQuality quality);  // "low", "medium", "high"
// Throws strahl::Error listing the choices for anything else.
BvhQuality bvhQualityFromName(const std::string& name);

struct AccelBuildOptions {
    int threads = 0;  // 0: all hardware threads
    BvhQuality quality = BvhQuality::Medium;
    // Embree's compact mode: indexed triangles and smaller nodes, about half
    // the BVH memory for somewhat slower rays (docs/memory.md).
    bool compact = false;
    // Which meshes whose triangles come in pairs sharing an edge (quad faces,
    // tessellated grids) are traced as Embree quads: the same surface in half
    // the primitives (accel/quad_faces.h says when that pays).
    QuadPolicy quads = QuadPolicy::Auto;
    // When not 0: Embree's allocations fail once memoryBaselineBytes plus the
    // bytes Embree holds would pass this, and the build throws strahl::Error
    // saying so — instead of the process being killed by the kernel.
    size_t memoryLimitBytes = 0;
    size_t memoryBaselineBytes = 0;  // what the process holds outside Embree
    // Called with the build's progress fraction in [0, 1], possibly from several
    // threads at once; must not throw.
    std::function<void(double)> progress;
};

// Builds an Embree BVH over the shapes (which must outlive the Accel): meshes as
// Embree triangles — their vertex buffers shared with Embree, not copied, when
// reservePadding() was called — user shapes as Embree user geometry, each
// prototype as its own Embree scene and each instance as an Embree instance of
// it. Throws strahl::Error if Embree reports an error or a prototype index is
// out of range.
std::unique_ptr<Accel> buildEmbreeAccel(const AccelScene& scene, const AccelBuildOptions& options);
// The same without instancing.
std::unique_ptr<Accel> buildEmbreeAccel(std::span<const ShapeRef> shapes,
                                        const AccelBuildOptions& options);
// The same for a list of meshes only.
std::unique_ptr<Accel> buildEmbreeAccel(std::span<const TriangleMesh* const> meshes,
                                        const AccelBuildOptions& options);

// Embree's version string, e.g. "3.13.5", and the ISA it picked at run time.
const char* embreeVersion();

}  // namespace strahl
