// Direct lighting: emission plus one estimate per light of the light it sends
// directly to the hit, reflected by the material's BSDF,
//   L(p, wo) = Le + sum_lights f(wo, wi) L_i |cos| / pdf  *  V(p, light),
// with one shadow ray per light. Delta lights (point, spot, projector, directional) are
// exact and noise-free; area and environment lights take one light sample per
// camera sample (no BSDF sampling, no indirect light: use `path` for that).

#include "direct_integrator.h"

#include "shading_context.h"

namespace strahl {

Color DirectIntegrator::shade(const World& world, const SurfaceHit& hit, Sampler& sampler,
                              ShadingStats& stats) const {
    const ShadingContext ctx = makeShadingContext(world, hit, 0.0f);
    Color L = ctx.material->emits() && !hideEmitters_
                  ? emittedTowards(world, ctx, world.areaLightOf(hit.hit()))
                  : Color(0.0f);
    if (ctx.bsdf.isSpecular()) return L;
    for (const Light& light : world.lightSet.lights())
        L += estimateLight(world, ctx, light, sampler.get2D(), 1.0f, LightSampling::LightOnly,
                           stats);
    return L;
}

}  // namespace strahl
