#include "strahl/integrator/camera_sample.h"

#include "strahl/integrator/surface_hit.h"

namespace strahl {

uint32_t objectId(const Hit& hit) {
    return hit.instID != kInvalidId ? hit.instID : hit.geomID;
}

CameraSample shadeCameraSample(const World& world, const Integrator& integrator, const Ray& ray,
                               const Hit& hit, Sampler& sampler, ShadingStats& stats, bool wantAovs) {
    CameraSample sample;
    if (hit.valid()) {
        const SurfaceHit surface(world, ray, hit);
        sample.radiance = integrator.shade(world, surface, sampler, stats);
        sample.aov.hit = true;
        if (wantAovs) {
            sample.aov.normal = surface.shadingNormal();
            sample.aov.depth = hit.t * glm::length(ray.dir);
            const SurfaceInteraction& si = surface.interaction();
            const ShadingPoint sp = shadingPointAt(si);
            sample.aov.albedo = makeBsdf(surface.material(), sp, world.textures.get()).albedo();
            sample.aov.position = si.p;
            sample.aov.objectId = objectId(hit);
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
