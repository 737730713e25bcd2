#include "shading_context.h"

#include "strahl/core/sampling.h"

namespace strahl {

Color ShadingContext::fCos(const Vec3& wi) const {
    if (bsdf.isOpaque() && glm::dot(wi, ng) <= 0.0f) return Color(0.0f);
    const Vec3 wiLocal = toLocal(wi);
    return bsdf.f(toLocal(wo), wiLocal) * (std::abs(wiLocal.z) * terminatorShadowing(wi));
}

float ShadingContext::terminatorShadowing(const Vec3& wi) const {
    if (terminatorAlpha2 <= 0.0f) return 1.0f;
    const float c = glm::dot(wi, unmappedNormal);
    if (c <= 0.0f) return 0.0f;
    const float tan2 = (1.0f - c * c) / (c * c);
    return 2.0f / (1.0f + std::sqrt(1.0f + terminatorAlpha2 * tan2));
}

namespace {

// Where a ray towards direction `dir` leaves a fibre: the point of its
// cross-section facing dir (dir's part normal to the axis), and that radial
// direction as the normal to offset along.
bool fibreExit(const ShadingContext& ctx, const Vec3& dir, Vec3& p, Vec3& normal) {
    const SurfaceInteraction& si = *ctx.si;
    if (!(si.fibreRadius > 0.0f) || !ctx.bsdf.isFibre()) return false;
    const float tangentLength = glm::length(si.dpdu);
    if (!(tangentLength > 0.0f)) return false;
    const Vec3 axis = si.dpdu / tangentLength;
    const Vec3 radial = dir - glm::dot(dir, axis) * axis;
    const float radialLength = glm::length(radial);
    if (!(radialLength > 1e-6f * glm::length(dir))) return false;  // along the axis: leave where it hit
    normal = radial / radialLength;
    p = si.fibreAxis + si.fibreRadius * normal;
    return true;
}

}  // namespace

Ray ShadingContext::spawn(const Vec3& wi) const {
    Vec3 p, normal;
    Ray ray = fibreExit(*this, wi, p, normal) ? spawnRay(p, si->pError, normal, wi) : spawnRay(si->p, si->pError, ng, wi);
    ray.time = time;
    return ray;
}

Ray ShadingContext::spawnTo(const Vec3& target) const {
    Vec3 p, normal;
    Ray ray = fibreExit(*this, target - si->p, p, normal) ? spawnRayTo(p, si->pError, normal, target)
                                                          : spawnRayTo(si->p, si->pError, ng, target);
    ray.time = time;
    return ray;
}

ShadingContext makeShadingContext(const World& world, const SurfaceHit& hit, float footprint) {
    ShadingContext ctx;
    const SurfaceInteraction& si = hit.interaction();
    ctx.si = &si;
    ctx.material = &hit.material();
    ctx.wo = -glm::normalize(hit.ray().dir);
    ctx.time = hit.ray().time;

    ShadingPoint& sp = ctx.point;
    sp = shadingPointAt(si, footprint);
    const TextureSystem* textures = world.textures.get();
    const Vec3 ns = shadingNormal(*ctx.material, sp, textures);
    ctx.bsdf = makeBsdf(*ctx.material, sp, textures);

    Vec3 ng = si.Ng, n = ns;
    if (glm::dot(n, ng) < 0.0f) n = -n;  // a normal map must not flip the side
    if (ctx.bsdf.isOpaque()) {
        if (glm::dot(ng, ctx.wo) < 0.0f) {
            ng = -ng;
            n = -n;
        }
        // Interpolated or mapped normals can face away from the viewer near
        // silhouettes; fall back to the geometric normal there.
        if (glm::dot(n, ctx.wo) <= 0.0f) n = ng;
    }
    ctx.ng = ng;
    ctx.n = n;
    if (ctx.material->terminatorShadowing && ctx.material->mapsNormals()) {
        // The tilt the map gives the normal acts as a microfacet roughness:
        // alpha^2 = tan^2(tilt) / 8, at most 1 (Chiang et al. 2019).
        Vec3 unmapped = si.Ns;  // unit
        if (glm::dot(unmapped, ng) < 0.0f) unmapped = -unmapped;
        const float c = std::clamp(glm::dot(unmapped, n), -1.0f, 1.0f);
        const float tan2 = (1.0f - c * c) / std::max(c * c, 1e-12f);
        ctx.unmappedNormal = unmapped;
        ctx.terminatorAlpha2 = std::min(0.125f * tan2, 1.0f);
    }
    // The frame's first axis follows dpdu (anisotropy, consistent texture
    // frames); Gram-Schmidt against n, any basis if dpdu is missing.
    const Vec3 tangent = si.dpdu - glm::dot(si.dpdu, n) * n;
    const float len = glm::length(tangent);
    if (len > 1e-6f * glm::length(si.dpdu) && len > 0.0f) {
        ctx.s = tangent / len;
        ctx.t = glm::cross(n, ctx.s);
    } else {
        orthonormalBasis(n, ctx.s, ctx.t);
    }
    return ctx;
}

Color emittedTowards(const World& world, const ShadingContext& ctx, uint32_t areaLight) {
    const Material& material = *ctx.material;
    if (!material.emits()) return Color(0.0f);
    if (areaLight != kInvalidId) {
        // The light's own front (its winding), as light sampling sees it.
        const Color front = triangleLe(world.lightSet.lights()[areaLight], ctx.wo);
        if (material.hasUniformEmission() || maxComponent(front) <= 0.0f) return front;
        // Read as light sampling reads it: at the point, footprint 0.
        ShadingPoint point = ctx.point;
        point.footprint = 0.0f;
        return emittedRadiance(material, point, world.textures.get());
    }
    // A user shape or an emission mapped triplanar: the front is the
    // surface's own Ng.
    if (!material.twoSidedEmission && glm::dot(ctx.si->Ng, ctx.wo) <= 0.0f) return Color(0.0f);
    return emittedRadiance(material, ctx.point, world.textures.get());
}

Color estimateLight(const World& world, const ShadingContext& ctx, const Light& light,
                    const Vec2& u, float selectPdf, LightSampling sampling, ShadingStats& stats) {
    LightSampleContext lightContext = ctx.lightContext();
    lightContext.textures = world.textures.get();
    const std::optional<LightLiSample> ls = sampleLi(light, lightContext, u);
    if (!ls || !(ls->pdf > 0.0f) || maxComponent(ls->L) <= 0.0f) return Color(0.0f);
    const Color f = ctx.fCos(ls->wi);
    if (maxComponent(f) <= 0.0f) return Color(0.0f);
    const Ray shadow = ls->atInfinity ? ctx.spawn(ls->wi) : ctx.spawnTo(ls->pLight);
    ++stats.shadowRays;
    if (world.accel->occluded(shadow)) return Color(0.0f);
    if (light.isDelta()) return f * ls->L / selectPdf;
    const float lightPdf = ls->pdf * selectPdf;
    const float weight =
        sampling == LightSampling::Mis ? powerHeuristic(1, lightPdf, 1, ctx.pdf(ls->wi)) : 1.0f;
    return f * ls->L * (weight / lightPdf);
}

Color sampleDirectLight(const World& world, const ShadingContext& ctx, Sampler& sampler,
                        LightSampling sampling, ShadingStats& stats) {
    const float uLight = sampler.get1D();
    const Vec2 u = sampler.get2D();
    const auto choice = world.lightSet.choose(uLight, ctx.lightContext());
    if (!choice) return Color(0.0f);
    return estimateLight(world, ctx, world.lightSet.lights()[choice->first], u, choice->second,
                         sampling, stats);
}

}  // namespace strahl
