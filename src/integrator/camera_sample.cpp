#include "strahl/integrator/camera_sample.h"

#include "strahl/integrator/surface_hit.h"

namespace strahl {

CameraSample shadeCameraSample(const World& world, const Integrator& integrator, const Ray& ray,
                               const Hit& hit, SampleRng& rng, ShadingStats& stats, bool wantAovs) {
    CameraSample sample;
    if (hit.valid()) {
        const SurfaceHit surface(world, ray, hit);
        sample.radiance = integrator.shade(world, surface, rng, stats);
        sample.aov.hit = true;
        if (wantAovs) {
            sample.aov.normal = surface.shadingNormal();
            sample.aov.depth = hit.t * glm::length(ray.dir);
            sample.aov.albedo = surface.material().diffuse;
        }
    } else {
        sample.radiance = integrator.miss(world, ray);
    }
    // A non-finite sample would poison the pixel's mean forever; drop its
    // radiance (the AOVs are finite by construction).
    if (!isFinite(sample.radiance)) sample.radiance = Color(0.0f);
    return sample;
}

}  // namespace strahl
