// Direct lighting from delta lights on Lambertian surfaces:
//   L(p, wo) = Le + sum_lights (rho / pi) * E_light * max(0, N . wi) * V(p, light)
// where E_light is the irradiance a surface facing the light would receive
// (I / r^2 for a point light, E for a directional light) and V the visibility
// found by one occlusion ray, spawned from the hit point's error bound rather
// than an absolute epsilon (core/ray.h).

#include "direct_integrator.h"

namespace strahl {

Color DirectIntegrator::shade(const World& world, const SurfaceHit& hit, SampleRng&,
                              ShadingStats& stats) const {
    const SurfaceInteraction& si = hit.interaction();
    const Material& material = hit.material();
    const Vec3 wo = -glm::normalize(hit.ray().dir);

    // Two-sided surfaces: flip both normals to the side the ray arrives from.
    Vec3 ng = si.Ng, ns = si.Ns;
    if (glm::dot(ng, wo) < 0.0f) {
        ng = -ng;
        ns = -ns;
    }
    // Interpolated normals can face away from the viewer near silhouettes; fall
    // back to the geometric normal there instead of shading black.
    if (glm::dot(ns, wo) <= 0.0f) ns = ng;

    Color L = material.emission;
    const Color brdf = material.diffuse * kInvPi;
    if (maxComponent(brdf) <= 0.0f) return L;

    for (const Light& light : world.lights) {
        const LightSample ls = sampleLight(light, si.p);
        const float cosTheta = glm::dot(ns, ls.wi);
        // The light must be above both the shading and the geometric surface,
        // otherwise the shadow ray would start inside the surface.
        if (cosTheta <= 0.0f || glm::dot(ng, ls.wi) <= 0.0f || maxComponent(ls.Li) <= 0.0f)
            continue;
        const Ray shadow = ls.atInfinity ? spawnRay(si.p, si.pError, ng, ls.wi)
                                         : spawnRayTo(si.p, si.pError, ng, ls.position);
        ++stats.shadowRays;
        if (world.accel->occluded(shadow)) continue;
        L += brdf * ls.Li * cosTheta;
    }
    return L;
}

}  // namespace strahl
