// Ambient occlusion: the cosine-weighted fraction of the hemisphere above the
// hit that is open within a distance,
//   AO = (1/pi) \int_H V(p, w) cos(theta) dw,
// estimated with cosine-weighted directions (pdf cos/pi), so each sample
// contributes 0 or 1 and the estimate is the fraction of unblocked rays.
// The hemisphere is the geometric normal's side facing the viewer.

#include "ao_integrator.h"

#include "strahl/core/sampling.h"
#include "strahl/core/error.h"

namespace strahl {

AoIntegrator::AoIntegrator(const World& world, const IntegratorOptions& options)
    : distance_(options.aoDistance), samples_(options.aoSamples) {
    if (samples_ < 1) fail("ao samples must be at least 1, got ", samples_);
    if (!(distance_ >= 0.0f)) fail("ao distance must be non-negative, got ", distance_);
    // A quarter of the scene's diagonal shows contact shadows without turning
    // into a sky-visibility image.
    if (distance_ == 0.0f) distance_ = 0.25f * glm::length(world.bounds().diagonal());
    if (!(distance_ > 0.0f)) distance_ = 1.0f;
}

Color AoIntegrator::shade(const World& world, const SurfaceHit& hit, Sampler& sampler,
                          ShadingStats& stats) const {
    const SurfaceInteraction& si = hit.interaction();
    const Vec3 wo = -glm::normalize(hit.ray().dir);
    const Vec3 n = glm::dot(si.Ng, wo) < 0.0f ? -si.Ng : si.Ng;
    Vec3 s, t;
    orthonormalBasis(n, s, t);
    int open = 0;
    for (int i = 0; i < samples_; ++i) {
        const Vec3 local = sampleCosineHemisphere(sampler.get2D());
        const Vec3 dir = local.x * s + local.y * t + local.z * n;
        Ray ray = spawnRay(si.p, si.pError, n, dir);
        ray.tfar = distance_;
        ray.time = hit.ray().time;
        ++stats.shadowRays;
        if (!world.accel->occluded(ray)) ++open;
    }
    return Color(static_cast<float>(open) / static_cast<float>(samples_));
}

}  // namespace strahl
