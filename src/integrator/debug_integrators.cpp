// The debug integrators: eyelight, normal, depth, primid. None of them traces
// secondary rays; they show what the first hit is, and only eyelight and
// normal look at more than the accelerator's hit record.

#include "debug_integrators.h"

namespace strahl {

Color EyelightIntegrator::shade(const World&, const SurfaceHit& hit, Sampler&,
                                ShadingStats&) const {
    return Color(std::abs(glm::dot(hit.shadingNormal(), glm::normalize(hit.ray().dir))));
}

Color NormalIntegrator::shade(const World&, const SurfaceHit& hit, Sampler&,
                              ShadingStats&) const {
    return 0.5f * hit.shadingNormal() + Vec3(0.5f);
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
