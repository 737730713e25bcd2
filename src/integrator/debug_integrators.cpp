// The debug integrators: eyelight, normal, depth, primid. None of them traces
// secondary rays; they show what the first hit is, and only eyelight and
// normal look at more than the accelerator's hit record.

#include "debug_integrators.h"

#include <optional>

namespace strahl {

namespace {

// Shades the lanes of a camera packet whose shading normal needs no surface
// interaction (SurfaceHit::normalWithoutInteraction) with color(unit normal,
// direction), and misses black (DebugIntegrator::miss); other lanes are left
// to shade().
template <class ColorOf>
uint32_t shadeFlatMeshLanes(const World& world, const CameraLanes& lanes, Color* radiance,
                            const ColorOf& color) {
    uint32_t shaded = 0;
    for (int lane = 0; lane < lanes.count; ++lane) {
        if (lanes.valid[lane] != -1) continue;
        Hit hit;
        hit.geomID = lanes.geomID[lane];
        if (!hit.valid()) {
            radiance[lane] = Color(0.0f);
            shaded |= 1u << lane;
            continue;
        }
        hit.instID = lanes.instID[lane];
        hit.Ng = Vec3(lanes.ngX[lane], lanes.ngY[lane], lanes.ngZ[lane]);
        const std::optional<Vec3> normal = SurfaceHit::normalWithoutInteraction(world, hit);
        if (!normal) continue;
        const Color c = color(*normal, Vec3(lanes.dirX[lane], lanes.dirY[lane], lanes.dirZ[lane]));
        radiance[lane] = isFinite(c) ? c : Color(0.0f);
        shaded |= 1u << lane;
    }
    return shaded;
}

// The two integrators' formulas, shared by shade() and shadeCameraLanes so
// that both give the same bits.
Color eyelight(const Vec3& normal, const Vec3& dir) {
    return Color(std::abs(glm::dot(normal, glm::normalize(dir))));
}
Color normalColor(const Vec3& normal, const Vec3&) { return 0.5f * normal + Vec3(0.5f); }

}  // namespace

Color EyelightIntegrator::shade(const World&, const SurfaceHit& hit, Sampler&,
                                ShadingStats&) const {
    return eyelight(hit.shadingNormal(), hit.ray().dir);
}

uint32_t EyelightIntegrator::shadeCameraLanes(const World& world, const CameraLanes& lanes,
                                              Color* radiance) const {
    return shadeFlatMeshLanes(world, lanes, radiance, eyelight);
}

Color NormalIntegrator::shade(const World&, const SurfaceHit& hit, Sampler&,
                              ShadingStats&) const {
    return normalColor(hit.shadingNormal(), hit.ray().dir);
}

uint32_t NormalIntegrator::shadeCameraLanes(const World& world, const CameraLanes& lanes,
                                            Color* radiance) const {
    return shadeFlatMeshLanes(world, lanes, radiance, normalColor);
}

DepthIntegrator::DepthIntegrator(const World& world) {
    const float diagonal = glm::length(world.bounds().diagonal());
    invScale_ = diagonal > 0.0f ? 1.0f / diagonal : 1.0f;
}

Color DepthIntegrator::shade(const World&, const SurfaceHit& hit, Sampler&, ShadingStats&) const {
    // hit.t is in units of |ray.dir|: scale to a distance for any direction length.
    return Color(hit.hit().t * glm::length(hit.ray().dir) * invScale_);
}

Color PrimIdIntegrator::shade(const World&, const SurfaceHit& hit, Sampler&,
                              ShadingStats&) const {
    // Instances of one prototype get different colours: the instance ID is
    // mixed in (top-level shapes keep the plain (geomID, primID) hash).
    const Hit& id = hit.hit();
    const uint64_t instance = id.instID == kInvalidId ? 0 : mixBits(id.instID);
    const uint64_t h = mixBits(((uint64_t(id.geomID) << 32) | id.primID) ^ instance);
    // Three 8-bit channels of the hash, kept away from black (0.15..1) so every
    // primitive is visible.
    auto channel = [h](int shift) { return 0.15f + 0.85f * float((h >> shift) & 0xFF) / 255.0f; };
    return Color(channel(0), channel(8), channel(16));
}

}  // namespace strahl
