// EmbreeSceneAccel: device, scene and ray queries shared by every Embree-backed
// Accel (see embree_scene.h). The static_asserts below are what makes the
// zero-copy packet queries safe.

#include "embree_scene.h"

#include <algorithm>
#include <cstddef>
#include <iterator>

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
static_assert(kInvalidId == RTC_INVALID_GEOMETRY_ID);

RTCBuildQuality embreeQuality(BvhQuality quality) {
    switch (quality) {
        case BvhQuality::Low: return RTC_BUILD_QUALITY_LOW;
        case BvhQuality::Medium: return RTC_BUILD_QUALITY_MEDIUM;
        case BvhQuality::High: return RTC_BUILD_QUALITY_HIGH;
    }
    fail("invalid BvhQuality value ", static_cast<int>(quality));
}

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
    rh.ray.time = ray.time;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

}  // namespace

EmbreeSceneAccel::EmbreeSceneAccel(const AccelBuildOptions& options)
    : device_(options.threads, options.memoryLimitBytes, options.memoryBaselineBytes),
      progress_(options.progress),
      quality_(embreeQuality(options.quality)),
      flags_(options.compact ? RTC_SCENE_FLAG_COMPACT : RTC_SCENE_FLAG_NONE) {
    scene_ = rtcNewScene(device_.handle());
    device_.check("creating the scene");
    configure(scene_);
    if (progress_) rtcSetSceneProgressMonitorFunction(scene_, &EmbreeSceneAccel::onProgress, this);
}

void EmbreeSceneAccel::configure(RTCScene scene) const {
    rtcSetSceneBuildQuality(scene, quality_);
    rtcSetSceneFlags(scene, flags_);
}

EmbreeSceneAccel::~EmbreeSceneAccel() {
    if (scene_) rtcReleaseScene(scene_);
    for (RTCScene prototype : prototypes_) rtcReleaseScene(prototype);
}

void EmbreeSceneAccel::attach(RTCGeometry geometry, unsigned geomID, const Bounds3& bounds,
                              const char* what) {
    attachTo(scene_, geometry, geomID, what);
    bounds_.expand(bounds);
}

void EmbreeSceneAccel::attachTo(RTCScene scene, RTCGeometry geometry, unsigned geomID,
                                const char* what) {
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(scene, geometry, geomID);
    rtcReleaseGeometry(geometry);
    device_.check(what);
}

RTCScene EmbreeSceneAccel::newPrototypeScene() {
    prototypes_.reserve(prototypes_.size() + 1);  // so push_back cannot throw and leak
    RTCScene scene = rtcNewScene(device_.handle());
    device_.check("creating a prototype scene");
    configure(scene);
    prototypes_.push_back(scene);
    return scene;
}

void EmbreeSceneAccel::commitPrototype(RTCScene scene) {
    rtcCommitScene(scene);
    device_.check("building a prototype's BVH");
}

void EmbreeSceneAccel::commit() {
    rtcCommitScene(scene_);
    device_.check("building the BVH");
}

Hit EmbreeSceneAccel::intersect(const Ray& ray) const {
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
    hit.instID = rh.hit.instID[0];
    if (!quadTables_.empty())
        if (const QuadFaces* quads = quadsOf(hit.instID, hit.geomID)) toTriangleHit(*quads, hit.primID, hit.u, hit.v);
    return hit;
}

bool EmbreeSceneAccel::occluded(const Ray& ray) const {
    RTCIntersectContext context = makeContext(RayCoherence::Incoherent);
    RTCRay r = toEmbree(ray).ray;
    rtcOccluded1(scene_, &context, &r);
    return r.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

namespace {

// Embree 3.13 traces a packet wider than the CPU's native width (16 lanes
// without AVX-512, 8 without AVX) as a ray stream, and a stream ignores the
// valid mask: it traces the inactive lanes too and writes their hits, against
// rtcIntersect8/16's documented "hit data of inactive rays is not changed"
// (seen with Debian's 3.13.5 on an AVX2 machine: inactive lanes came back
// with the hits of their rays). A stream's own mark of an inactive ray is
// tnear > tfar, so an emulated packet's inactive lanes carry that mark for
// the call and get their own tnear and tfar back after it.
template <class Packet>
class InactiveLanesMarked {
public:
    InactiveLanesMarked(const int* valid, Packet& packet, bool emulated)
        : valid_(valid), packet_(packet), emulated_(emulated) {
        if (!emulated_) return;
        for (int i = 0; i < Packet::kWidth; ++i) {
            if (valid_[i] == -1) continue;
            tnear_[i] = packet_.tnear[i];
            tfar_[i] = packet_.tfar[i];
            packet_.tnear[i] = 1.0f;  // tnear > tfar: inactive
            packet_.tfar[i] = 0.0f;
        }
    }
    ~InactiveLanesMarked() {
        if (!emulated_) return;
        for (int i = 0; i < Packet::kWidth; ++i) {
            if (valid_[i] == -1) continue;
            packet_.tnear[i] = tnear_[i];
            packet_.tfar[i] = tfar_[i];
        }
    }
    InactiveLanesMarked(const InactiveLanesMarked&) = delete;
    InactiveLanesMarked& operator=(const InactiveLanesMarked&) = delete;

private:
    const int* valid_;
    Packet& packet_;
    bool emulated_;
    float tnear_[Packet::kWidth] = {}, tfar_[Packet::kWidth] = {};
};

}  // namespace

void EmbreeSceneAccel::intersect8(const int* valid, RayHitPacket8& packet, RayCoherence c) const {
    RTCIntersectContext context = makeContext(c);
    {
        const InactiveLanesMarked marked(valid, packet, !device_.supportsNative8());
        rtcIntersect8(valid, scene_, &context, reinterpret_cast<RTCRayHit8*>(&packet));
    }
    if (!quadTables_.empty()) toTriangleHits(valid, packet);
}

void EmbreeSceneAccel::intersect16(const int* valid, RayHitPacket16& packet,
                                   RayCoherence c) const {
    RTCIntersectContext context = makeContext(c);
    {
        const InactiveLanesMarked marked(valid, packet, !device_.supportsNative16());
        rtcIntersect16(valid, scene_, &context, reinterpret_cast<RTCRayHit16*>(&packet));
    }
    if (!quadTables_.empty()) toTriangleHits(valid, packet);
}

void EmbreeSceneAccel::traceAsQuads(size_t scene, unsigned geomID, const QuadFaces* faces) {
    if (quadTables_.size() <= scene) quadTables_.resize(scene + 1);
    std::vector<const QuadFaces*>& table = quadTables_[scene];
    if (table.size() <= geomID) table.resize(geomID + 1, nullptr);
    table[geomID] = faces;
    quadTableBytes_ += faces->memoryBytes();
}

void EmbreeSceneAccel::setInstances(size_t topLevelShapes, std::vector<uint32_t> prototypeOfInstance) {
    topLevelShapes_ = topLevelShapes;
    prototypeOfInstance_ = std::move(prototypeOfInstance);
}

const QuadFaces* EmbreeSceneAccel::quadsOf(uint32_t instID, uint32_t geomID) const {
    size_t scene = 0;
    if (instID != RTC_INVALID_GEOMETRY_ID) scene = 1 + size_t(prototypeOfInstance_[instID - topLevelShapes_]);
    if (scene >= quadTables_.size()) return nullptr;
    const std::vector<const QuadFaces*>& table = quadTables_[scene];
    return geomID < table.size() ? table[geomID] : nullptr;
}

template <class Packet>
void EmbreeSceneAccel::toTriangleHits(const int* valid, Packet& packet) const {
    for (size_t i = 0; i < std::size(packet.geomID); ++i) {
        if (valid[i] != -1 || packet.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
        if (const QuadFaces* quads = quadsOf(packet.instID[i], packet.geomID[i]))
            toTriangleHit(*quads, packet.primID[i], packet.u[i], packet.v[i]);
    }
}

int EmbreeSceneAccel::nativePacketWidth() const {
    if (device_.supportsNative16()) return 16;
    if (device_.supportsNative8()) return 8;
    return 1;
}

bool EmbreeSceneAccel::onProgress(void* self, double fraction) {
    auto* accel = static_cast<EmbreeSceneAccel*>(self);
    accel->progress_(std::clamp(fraction, 0.0, 1.0));
    return true;  // never cancel
}

}  // namespace strahl
