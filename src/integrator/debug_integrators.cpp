// The debug integrators: eyelight, normal, depth, primid. None of them traces
// secondary rays; they show what the first hit is.

#include "debug_integrators.h"

#include "strahl/core/rng.h"

namespace strahl {

Color EyelightIntegrator::shade(const World&, const Ray& ray, const Hit&,
                                const SurfaceInteraction& si, Pcg32&, ShadingStats&) const {
    return Color(std::abs(glm::dot(si.Ns, glm::normalize(ray.dir))));
}

Color NormalIntegrator::shade(const World&, const Ray&, const Hit&, const SurfaceInteraction& si,
                              Pcg32&, ShadingStats&) const {
    return 0.5f * si.Ns + Vec3(0.5f);
}

DepthIntegrator::DepthIntegrator(const World& world) {
    const float diagonal = glm::length(world.bounds().diagonal());
    invScale_ = diagonal > 0.0f ? 1.0f / diagonal : 1.0f;
}

Color DepthIntegrator::shade(const World&, const Ray& ray, const Hit& hit,
                             const SurfaceInteraction&, Pcg32&, ShadingStats&) const {
    // hit.t is in units of |ray.dir|; camera rays are unit length except for
    // callers that pass unnormalised directions, so scale by the length.
    return Color(hit.t * glm::length(ray.dir) * invScale_);
}

Color PrimIdIntegrator::shade(const World&, const Ray&, const Hit& hit,
                              const SurfaceInteraction&, Pcg32&, ShadingStats&) const {
    const uint64_t h = mixBits((uint64_t(hit.geomID) << 32) | hit.primID);
    // Three 8-bit channels of the hash, kept away from black (0.15..1) so every
    // primitive is visible.
    auto channel = [h](int shift) { return 0.15f + 0.85f * float((h >> shift) & 0xFF) / 255.0f; };
    return Color(channel(0), channel(8), channel(16));
}

}  // namespace strahl
