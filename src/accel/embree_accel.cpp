// EmbreeAccel: triangle meshes and user shapes in one Embree 3 scene.
//
// Invariants:
//  - geomID == index of the shape in the span handed to buildEmbreeAccel
//    (rtcAttachGeometryByID), so shading finds a hit's shape without a map.
//  - Every UserShape goes through one generic user-geometry adapter (the
//    callbacks below), following the Embree 3 contract of ../shared/GUIDE.md §3:
//    callbacks handle any packet width N, read valid[] only, accept a hit only
//    inside (tnear, tfar) — the shape's own intersect() guarantees that — write
//    tfar/u/v/Ng/primID/geomID and instID on a hit and nothing on a miss, and
//    set tfar = -inf for an occlusion. Shapes' intersect() is noexcept, so no
//    exception can cross Embree.
//  - Vertex and index buffers are shared with Embree (zero copy) when the
//    mesh's position vector has the spare element Embree's 16-byte vertex loads
//    need (TriangleMesh::reservePadding); otherwise they are copied once into an
//    Embree-owned buffer — correct, but it costs memory, so the scene builder
//    always pads.
//  - strahl's RayHitPacket<N> is handed to rtcIntersectN by reinterpret_cast;
//    the static_asserts below pin every field offset to RTCRayHitN.
//  - No exception ever crosses an Embree call: errors are recorded by the device
//    callback and thrown after the call returns (EmbreeDevice::check).

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <vector>

#include "embree_device.h"
#include "strahl/accel/accel.h"
#include "strahl/core/error.h"

namespace strahl {

namespace {

#define STRAHL_SAME_OFFSET(N, ours, theirs)                                          \
    static_assert(offsetof(RayHitPacket<N>, ours) == offsetof(RTCRayHit##N, theirs), \
                  "RayHitPacket<" #N ">::" #ours " does not match RTCRayHit" #N)
#define STRAHL_CHECK_PACKET_LAYOUT(N)                                                        \
    static_assert(sizeof(RayHitPacket<N>) == sizeof(RTCRayHit##N));                          \
    static_assert(alignof(RayHitPacket<N>) >= alignof(RTCRayHit##N));                        \
    STRAHL_SAME_OFFSET(N, org_x, ray.org_x); STRAHL_SAME_OFFSET(N, org_y, ray.org_y);        \
    STRAHL_SAME_OFFSET(N, org_z, ray.org_z); STRAHL_SAME_OFFSET(N, tnear, ray.tnear);        \
    STRAHL_SAME_OFFSET(N, dir_x, ray.dir_x); STRAHL_SAME_OFFSET(N, dir_y, ray.dir_y);        \
    STRAHL_SAME_OFFSET(N, dir_z, ray.dir_z); STRAHL_SAME_OFFSET(N, time, ray.time);          \
    STRAHL_SAME_OFFSET(N, tfar, ray.tfar); STRAHL_SAME_OFFSET(N, mask, ray.mask);            \
    STRAHL_SAME_OFFSET(N, id, ray.id); STRAHL_SAME_OFFSET(N, flags, ray.flags);              \
    STRAHL_SAME_OFFSET(N, Ng_x, hit.Ng_x); STRAHL_SAME_OFFSET(N, Ng_y, hit.Ng_y);            \
    STRAHL_SAME_OFFSET(N, Ng_z, hit.Ng_z); STRAHL_SAME_OFFSET(N, u, hit.u);                  \
    STRAHL_SAME_OFFSET(N, v, hit.v); STRAHL_SAME_OFFSET(N, primID, hit.primID);              \
    STRAHL_SAME_OFFSET(N, geomID, hit.geomID); STRAHL_SAME_OFFSET(N, instID, hit.instID)

static_assert(RTC_MAX_INSTANCE_LEVEL_COUNT == 1, "packets carry one instance level");
STRAHL_CHECK_PACKET_LAYOUT(8);
STRAHL_CHECK_PACKET_LAYOUT(16);
static_assert(sizeof(Vec3) == 3 * sizeof(float), "vertex buffers are shared as RTC_FORMAT_FLOAT3");
static_assert(kInvalidId == RTC_INVALID_GEOMETRY_ID);

RTCIntersectContext makeContext(RayCoherence coherence) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = coherence == RayCoherence::Coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                                        : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    return context;
}

RTCRayHit toEmbree(const Ray& ray) {
    RTCRayHit rh;
    rh.ray.org_x = ray.origin.x;
    rh.ray.org_y = ray.origin.y;
    rh.ray.org_z = ray.origin.z;
    rh.ray.dir_x = ray.dir.x;
    rh.ray.dir_y = ray.dir.y;
    rh.ray.dir_z = ray.dir.z;
    rh.ray.tnear = ray.tnear;
    rh.ray.tfar = ray.tfar;
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

// ---- the generic user-geometry adapter --------------------------------------

Ray rayFromN(RTCRayN* rays, unsigned N, unsigned i) {
    Ray ray;
    ray.origin = Vec3(RTCRayN_org_x(rays, N, i),
                      RTCRayN_org_y(rays, N, i),
                      RTCRayN_org_z(rays, N, i));
    ray.dir = Vec3(RTCRayN_dir_x(rays, N, i),
                   RTCRayN_dir_y(rays, N, i),
                   RTCRayN_dir_z(rays, N, i));
    ray.tnear = RTCRayN_tnear(rays, N, i);
    ray.tfar = RTCRayN_tfar(rays, N, i);
    return ray;
}

void userBounds(const RTCBoundsFunctionArguments* args) {
    const auto* shape = static_cast<const UserShape*>(args->geometryUserPtr);
    const Bounds3 b = shape->primitiveBounds(args->primID);
    args->bounds_o->lower_x = b.min.x;
    args->bounds_o->lower_y = b.min.y;
    args->bounds_o->lower_z = b.min.z;
    args->bounds_o->upper_x = b.max.x;
    args->bounds_o->upper_y = b.max.y;
    args->bounds_o->upper_z = b.max.z;
}

void userIntersect(const RTCIntersectFunctionNArguments* args) {
    const auto* shape = static_cast<const UserShape*>(args->geometryUserPtr);
    const unsigned N = args->N;
    RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, N);
    RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, N);
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        Hit hit;
        if (!shape->intersect(rayFromN(rays, N, i), args->primID, hit)) continue;
        RTCRayN_tfar(rays, N, i) = hit.t;
        RTCHitN_Ng_x(hits, N, i) = hit.Ng.x;
        RTCHitN_Ng_y(hits, N, i) = hit.Ng.y;
        RTCHitN_Ng_z(hits, N, i) = hit.Ng.z;
        RTCHitN_u(hits, N, i) = hit.u;
        RTCHitN_v(hits, N, i) = hit.v;
        RTCHitN_primID(hits, N, i) = args->primID;
        RTCHitN_geomID(hits, N, i) = args->geomID;
        for (unsigned level = 0; level < RTC_MAX_INSTANCE_LEVEL_COUNT; ++level)
            RTCHitN_instID(hits, N, i, level) = args->context->instID[level];
    }
}

void userOccluded(const RTCOccludedFunctionNArguments* args) {
    const auto* shape = static_cast<const UserShape*>(args->geometryUserPtr);
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        if (shape->occluded(rayFromN(args->ray, N, i), args->primID))
            RTCRayN_tfar(args->ray, N, i) = -kInfinity;
    }
}

// ---- the accelerator -----------------------------------------------------------

class EmbreeAccel final : public Accel {
public:
    EmbreeAccel(std::span<const ShapeRef> shapes, const AccelBuildOptions& options)
        : device_(options.threads), progress_(options.progress) {
        scene_ = rtcNewScene(device_.handle());
        device_.check("creating the scene");
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
        if (progress_) rtcSetSceneProgressMonitorFunction(scene_, &EmbreeAccel::onProgress, this);
        for (size_t i = 0; i < shapes.size(); ++i) {
            if (shapes[i].mesh)
                attachMesh(*shapes[i].mesh, static_cast<unsigned>(i));
            else
                attachUserShape(*shapes[i].user, static_cast<unsigned>(i));
            bounds_.expand(shapes[i].bounds());
        }
        rtcCommitScene(scene_);
        device_.check("building the BVH");
    }

    ~EmbreeAccel() override {
        if (scene_) rtcReleaseScene(scene_);
    }

    Hit intersect(const Ray& ray) const override {
        RTCIntersectContext context = makeContext(RayCoherence::Incoherent);
        RTCRayHit rh = toEmbree(ray);
        rtcIntersect1(scene_, &context, &rh);
        Hit hit;
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
        hit.t = rh.ray.tfar;
        hit.u = rh.hit.u;
        hit.v = rh.hit.v;
        hit.Ng = Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
        hit.geomID = rh.hit.geomID;
        hit.primID = rh.hit.primID;
        return hit;
    }

    bool occluded(const Ray& ray) const override {
        RTCIntersectContext context = makeContext(RayCoherence::Incoherent);
        RTCRay r = toEmbree(ray).ray;
        rtcOccluded1(scene_, &context, &r);
        return r.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
    }

    void intersect8(const int* valid, RayHitPacket8& packet, RayCoherence c) const override {
        RTCIntersectContext context = makeContext(c);
        rtcIntersect8(valid, scene_, &context, reinterpret_cast<RTCRayHit8*>(&packet));
    }

    void intersect16(const int* valid, RayHitPacket16& packet, RayCoherence c) const override {
        RTCIntersectContext context = makeContext(c);
        rtcIntersect16(valid, scene_, &context, reinterpret_cast<RTCRayHit16*>(&packet));
    }

    int nativePacketWidth() const override {
        if (device_.supportsNative16()) return 16;
        if (device_.supportsNative8()) return 8;
        return 1;
    }

    Bounds3 bounds() const override { return bounds_; }
    size_t memoryBytes() const override { return device_.bytesInUse(); }

private:
    void attachMesh(const TriangleMesh& mesh, unsigned geomID) {
        RTCGeometry geom = rtcNewGeometry(device_.handle(), RTC_GEOMETRY_TYPE_TRIANGLE);
        const size_t nv = mesh.vertexCount(), nt = mesh.triangleCount();
        if (mesh.isPadded()) {
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       mesh.positions.data(), 0, sizeof(Vec3), nv);
        } else {
            void* dst = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                sizeof(Vec3), nv);
            if (dst) std::memcpy(dst, mesh.positions.data(), nv * sizeof(Vec3));
        }
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                   mesh.indices.data(), 0, 3 * sizeof(uint32_t), nt);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(scene_, geom, geomID);
        rtcReleaseGeometry(geom);
        device_.check("adding a triangle mesh");
    }

    void attachUserShape(const UserShape& shape, unsigned geomID) {
        const uint32_t count = shape.primitiveCount();
        for (uint32_t prim = 0; prim < count; ++prim) {
            const Bounds3 b = shape.primitiveBounds(prim);
            if (b.empty() || !isFinite(b.min) || !isFinite(b.max))
                fail("shape ", geomID, ": primitive ", prim, " has no finite bounds");
        }
        RTCGeometry geom = rtcNewGeometry(device_.handle(), RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, count);
        rtcSetGeometryUserData(geom, const_cast<UserShape*>(&shape));
        rtcSetGeometryBoundsFunction(geom, &userBounds, nullptr);
        rtcSetGeometryIntersectFunction(geom, &userIntersect);
        rtcSetGeometryOccludedFunction(geom, &userOccluded);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(scene_, geom, geomID);
        rtcReleaseGeometry(geom);
        device_.check("adding a user shape");
    }

    static bool onProgress(void* self, double fraction) {
        auto* accel = static_cast<EmbreeAccel*>(self);
        accel->progress_(std::clamp(fraction, 0.0, 1.0));
        return true;  // never cancel
    }

    EmbreeDevice device_;
    std::function<void(double)> progress_;
    RTCScene scene_ = nullptr;
    Bounds3 bounds_;
};

}  // namespace

std::unique_ptr<Accel> buildEmbreeAccel(std::span<const ShapeRef> shapes,
                                        const AccelBuildOptions& options) {
    return std::make_unique<EmbreeAccel>(shapes, options);
}

std::unique_ptr<Accel> buildEmbreeAccel(std::span<const TriangleMesh* const> meshes,
                                        const AccelBuildOptions& options) {
    std::vector<ShapeRef> shapes;
    shapes.reserve(meshes.size());
    for (const TriangleMesh* mesh : meshes) shapes.push_back(ShapeRef{mesh, nullptr});
    return std::make_unique<EmbreeAccel>(shapes, options);
}

const char* embreeVersion() { return RTC_VERSION_STRING; }

}  // namespace strahl
