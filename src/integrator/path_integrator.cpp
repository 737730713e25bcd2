// Unidirectional path tracing with next-event estimation and multiple
// importance sampling (Veach 1997, ch. 9; pbrt-v4 PathIntegrator::Li).
//
// At every non-specular vertex two strategies estimate direct light: a light
// sample (sampleDirectLight) and the next BSDF-sampled ray, if it happens to
// reach an emitter. Each is weighted by the power heuristic of its own density
// against the other's, both as solid-angle densities at the vertex:
//   light sample:  w = p_light^2 / (p_light^2 + p_bsdf^2)
//   BSDF hit:      w = p_bsdf^2  / (p_bsdf^2 + p_light^2)
// with p_light = P(choose light) * pdfLi. Emitters seen by the camera or after
// a specular bounce have weight 1 (no light sample could have found them), as
// have emitters that are not light-sampled (textured emission, user shapes).
//
// Russian roulette from bounce russianRouletteDepth on: continue with probability
// q = min(1, max(beta * etaScale) / russianRouletteThreshold), dividing beta by
// q; etaScale undoes the 1/eta^2 radiance scaling of refraction so paths inside
// glass are not killed for it (pbrt-v4). With threshold 1 this is pbrt-v4's
// rule; a smaller threshold leaves every path whose throughput is above it
// alone, so roulette ends only the paths that can bring little light.
//
// Filter glossy (Cycles' "filter glossy", off by default, biased): a path
// remembers the smallest density of its rough bounces so far, p_min (a diffuse
// bounce has at most 1/pi). At every later vertex, with the user's value F,
// b = p_min / F; if b < 1 every glossy and specular lobe there is roughened to
// at least alpha = sqrt(1 - b) / 2 (Bsdf::roughened): after a diffuse bounce,
// sharp reflections and refractions, which only a lucky BSDF sample could
// find lights through, turn into rough ones that light sampling reaches.
// Caustic fireflies go, and caustics blur. (The formula is Cycles'.)
//
// Sample clamping (Cycles' "clamp direct/indirect", off by default, biased):
// the light a sample gathers is kept in three sums by the reflections it took
// to reach the camera: none (emitters seen, never clamped), one (direct) and
// more (indirect). At the end the direct and the indirect sum are each scaled
// down so that their largest channel is at most their clamp.

#include "path_integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "shading_context.h"
#include "strahl/core/sampling.h"

namespace strahl {

namespace {

// `light` scaled down so its largest channel is at most `limit` (0: as is).
Color clamped(const Color& light, float limit) {
    const float largest = maxComponent(light);
    return limit > 0.0f && largest > limit ? light * (limit / largest) : light;
}

}  // namespace

Color PathIntegrator::shade(const World& world, const SurfaceHit& first, Sampler& sampler,
                            ShadingStats& stats) const {
    const LightSampling mode = options_.sampling;
    // Without clamping every contribution goes into L in path order (the
    // images of unclamped renders do not depend on the clamp code); with it,
    // direct (one reflection before the camera) and indirect (more) light
    // are summed apart, to be clamped at the end.
    const bool clamping = options_.clampDirect > 0.0f || options_.clampIndirect > 0.0f;
    Color L(0.0f), direct(0.0f), indirect(0.0f), beta(1.0f);
    const auto add = [&](const Color& light, int reflections) {
        (!clamping || reflections == 0 ? L : reflections == 1 ? direct : indirect) += light;
    };
    bool specularBounce = false;
    float etaScale = 1.0f;
    float prevBsdfPdf = 0.0f;
    LightSampleContext prevContext;
    float pathLength = 0.0f;
    float minBouncePdf = std::numeric_limits<float>::infinity();  // filter glossy's p_min

    Ray ray = first.ray();
    Hit hit = first.hit();
    for (int depth = 0;; ++depth) {
        // The weight of an emitter reached by this ray (BSDF sampling);
        // `light` is its index in the light set, kInvalidId if it is not
        // light-sampled.
        const auto emitterWeight = [&](uint32_t light, const Vec3& dir, const Vec3& pLight) {
            if (depth == 0 || specularBounce || light == kInvalidId) return 1.0f;
            if (mode == LightSampling::BsdfOnly) return 1.0f;
            if (mode == LightSampling::LightOnly) return 0.0f;
            const float lightPdf = world.lightSet.pmf(light, prevContext) *
                                   pdfLi(world.lightSet.lights()[light], prevContext, dir, pLight);
            return powerHeuristic(1, prevBsdfPdf, 1, lightPdf);
        };

        if (!hit.valid()) {
            if (depth == 0 && options_.hideEmitters) break;
            const Vec3 dir = glm::normalize(ray.dir);
            for (uint32_t i : world.lightSet.infiniteLights()) {
                const Light& light = world.lightSet.lights()[i];
                const Color Le = infiniteLe(light, dir);
                if (maxComponent(Le) > 0.0f) add(beta * Le * emitterWeight(i, dir, Vec3(0.0f)), depth);
            }
            break;
        }

        const SurfaceHit surface(world, ray, hit);
        pathLength += hit.t * glm::length(ray.dir);
        const float footprint = options_.coneWidth + options_.coneAngle * pathLength;
        ShadingContext ctx = makeShadingContext(world, surface, footprint);
        if (options_.filterGlossy > 0.0f) {
            const float blurPdf = minBouncePdf / options_.filterGlossy;
            if (blurPdf < 1.0f) ctx.bsdf = ctx.bsdf.roughened(0.5f * std::sqrt(1.0f - blurPdf));
        }

        if (ctx.material->emits() && !(depth == 0 && options_.hideEmitters)) {
            const uint32_t areaLight = world.areaLightOf(hit);
            const Color Le = emittedTowards(world, ctx, areaLight);
            if (maxComponent(Le) > 0.0f)
                add(beta * Le * emitterWeight(areaLight, -ctx.wo, ctx.si->p), depth);
        }
        if (depth >= options_.maxDepth) break;

        if (!ctx.bsdf.isSpecular() && mode != LightSampling::BsdfOnly)
            add(beta * sampleDirectLight(world, ctx, sampler, mode, stats), depth + 1);

        // The last bounce can only bring emission (the loop ends where its ray
        // lands): with none in the scene its light is 0, so it is not taken.
        if (depth + 1 >= options_.maxDepth && !world.emissionReachable()) break;

        const float uLobe = sampler.get1D();
        const std::optional<BsdfSample> bs = ctx.bsdf.sample(ctx.toLocal(ctx.wo), uLobe,
                                                             sampler.get2D());
        if (!bs || !(bs->pdf > 0.0f)) break;
        const Vec3 wi = ctx.toWorld(bs->wi);
        // Reflection must stay on wo's side of the geometry, transmission cross
        // it — except for a fibre, whose light leaves it anywhere around
        // (a flat ribbon's bent shading normal is no side of its geometry).
        const bool sameSide = glm::dot(wi, ctx.ng) * glm::dot(ctx.wo, ctx.ng) > 0.0f;
        if (sameSide == bs->transmission && !ctx.bsdf.isFibre()) break;
        beta *= bs->f * (std::abs(bs->wi.z) * ctx.terminatorShadowing(wi) / bs->pdf);
        if (!isFinite(beta) || maxComponent(beta) <= 0.0f) break;
        specularBounce = bs->specular;
        prevBsdfPdf = bs->pdf;
        if (!bs->specular) minBouncePdf = std::min(minBouncePdf, bs->pdf);
        if (bs->transmission) etaScale *= bs->eta * bs->eta;
        prevContext = ctx.lightContext();

        ray = ctx.spawn(wi);
        hit = world.accel->intersect(ray);
        ++stats.bounceRays;

        // The BSDF sample just taken is bounce depth + 1.
        if (options_.russianRoulette && depth + 1 >= options_.russianRouletteDepth) {
            const float q =
                std::min(1.0f, maxComponent(beta * etaScale) / options_.russianRouletteThreshold);
            if (q < 1.0f) {
                if (sampler.get1D() >= q) break;
                beta /= q;
            }
        }
    }
    if (!clamping) return L;
    return L + clamped(direct, options_.clampDirect) + clamped(indirect, options_.clampIndirect);
}

}  // namespace strahl
