#pragma once
// EmbreeSceneAccel: what every Embree-backed Accel shares, whatever its scene
// holds — the device, one scene with strahl's build settings and progress
// callback, and the ray queries. Internal to src/accel/: only this module may
// see Embree types.
//
// A subclass attaches its geometry in its constructor (attach()) and then
// builds the BVH (commit()). The base owns the scene, so a subclass
// constructor that throws half way still releases it.
//
// Queries: single rays go through an RTCRayHit; packets are handed to
// rtcIntersect8/16 by reinterpret_cast of strahl's RayHitPacket<N>, whose every
// field offset embree_scene.cpp pins to RTCRayHitN with static_asserts. No
// exception ever crosses an Embree call: errors are recorded by the device
// callback and thrown after the call returns (EmbreeDevice::check).

#include <embree3/rtcore.h>

#include <functional>
#include <vector>

#include "embree_device.h"
#include "strahl/accel/accel.h"
#include "strahl/accel/quad_faces.h"

namespace strahl {

class EmbreeSceneAccel : public Accel {
public:
    ~EmbreeSceneAccel() override;
    EmbreeSceneAccel(const EmbreeSceneAccel&) = delete;
    EmbreeSceneAccel& operator=(const EmbreeSceneAccel&) = delete;

    Hit intersect(const Ray& ray) const override;
    bool occluded(const Ray& ray) const override;
    void intersect8(const int* valid, RayHitPacket8& packet, RayCoherence c) const override;
    void intersect16(const int* valid, RayHitPacket16& packet, RayCoherence c) const override;
    int nativePacketWidth() const override;
    Bounds3 bounds() const override { return bounds_; }
    size_t memoryBytes() const override { return device_.bytesInUse() + quadTableBytes_; }

protected:
    // Creates the device (options.threads and memory limit) and an empty scene
    // of options.quality (compact if asked) that reports progress to
    // options.progress.
    explicit EmbreeSceneAccel(const AccelBuildOptions& options);

    RTCDevice device() const { return device_.handle(); }
    RTCBuildQuality quality() const { return quality_; }
    // Commits `geometry`, attaches it to the top-level scene as `geomID`, drops
    // the caller's reference and throws strahl::Error "Embree: <what>: ..." if
    // Embree reported an error.
    void attach(RTCGeometry geometry, unsigned geomID, const Bounds3& bounds, const char* what);
    // The same into another scene (an instanced prototype); bounds not tracked.
    void attachTo(RTCScene scene, RTCGeometry geometry, unsigned geomID, const char* what);
    // A new empty scene with the top-level scene's build settings, owned (and
    // released) by this accelerator, for prototypes that instances place. The
    // i-th made is prototypeScene(i).
    RTCScene newPrototypeScene();
    RTCScene prototypeScene(size_t i) const { return prototypes_[i]; }
    size_t prototypeCount() const { return prototypes_.size(); }
    // Builds a prototype scene's BVH.
    void commitPrototype(RTCScene scene);
    // Builds the BVH over everything attached.
    void commit();

    // Meshes traced as Embree quads: every query turns a hit on one back into
    // a hit on the mesh's triangle (toTriangleHit), so callers only ever see
    // triangle indices. `scene` is 0 for the top level, p + 1 for prototype p;
    // `faces` must outlive the accelerator.
    void traceAsQuads(size_t scene, unsigned geomID, const QuadFaces* faces);
    // Which prototype each instance places (instance k has the top-level ID
    // topLevelShapes + k), for hits inside instances.
    void setInstances(size_t topLevelShapes, std::vector<uint32_t> prototypeOfInstance);

private:
    // The quads of the mesh a hit is on, or null when it is not traced as quads.
    const QuadFaces* quadsOf(uint32_t instID, uint32_t geomID) const;
    template <class Packet>
    void toTriangleHits(const int* valid, Packet& packet) const;

    static bool onProgress(void* self, double fraction);
    // Build quality and flags of the options, for the top-level scene and prototypes.
    void configure(RTCScene scene) const;

    EmbreeDevice device_;
    std::function<void(double)> progress_;
    RTCBuildQuality quality_;
    RTCSceneFlags flags_;
    RTCScene scene_ = nullptr;
    std::vector<RTCScene> prototypes_;
    Bounds3 bounds_;
    // [scene][geomID] as traceAsQuads() describes; empty when no mesh is.
    std::vector<std::vector<const QuadFaces*>> quadTables_;
    size_t quadTableBytes_ = 0;
    size_t topLevelShapes_ = 0;
    std::vector<uint32_t> prototypeOfInstance_;
};

}  // namespace strahl
