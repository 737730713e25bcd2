#pragma once
// Internal: everything the lighting integrators (direct, path) need at one
// surface hit — the interaction, the material's BSDF in a shading frame, the
// normals oriented for two-sided shading — and next-event estimation, which
// both integrators share.
//
// Orientation: for opaque BSDFs the geometric and shading normals are turned
// towards wo (two-sided surfaces), so wo is in the local upper hemisphere. A
// dielectric keeps its normals as the surface defines them (outward): the sign
// of wo.z tells the BSDF whether the ray arrives from inside.

#include "strahl/core/sampler.h"
#include "strahl/integrator/integrator.h"
#include "strahl/integrator/surface_hit.h"

namespace strahl {

struct ShadingContext {
    const SurfaceInteraction* si = nullptr;
    const Material* material = nullptr;
    ShadingPoint point;
    Vec3 wo{0.0f};  // unit, towards where the ray came from
    float time = 0.0f;  // the ray's: every ray spawned here is cast at it
    Vec3 ng{0.0f};  // unit geometric normal (oriented, see above)
    Vec3 s{0.0f}, t{0.0f}, n{0.0f};  // shading frame, n = shading normal
    Bsdf bsdf;
    // A normal or bump map's terminator shadowing (material.terminatorShadowing):
    // alpha^2 of the tilt, 0 for none, and the normal before the map.
    float terminatorAlpha2 = 0.0f;
    Vec3 unmappedNormal{0.0f};

    Vec3 toLocal(const Vec3& v) const { return Vec3(glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)); }
    Vec3 toWorld(const Vec3& v) const { return v.x * s + v.y * t + v.z * n; }
    // BSDF times |cos| for a world-space wi, zero where an opaque surface's
    // geometry puts wi on the other side than wo (light leaks through
    // interpolated normals).
    Color fCos(const Vec3& wi) const;
    // The factor the normal map's shadowing puts on light from wi (1 without):
    // the GGX Smith G1 of wi about the unmapped normal, with alpha^2 =
    // min(1, tan^2(tilt) / 8) (Chiang, Li & Burley 2019, "Taming the Shadow
    // Terminator"). fCos includes it; a BSDF sample's weight must take it too.
    float terminatorShadowing(const Vec3& wi) const;
    float pdf(const Vec3& wi) const { return bsdf.pdf(toLocal(wo), toLocal(wi)); }
    // A ray leaving the surface in direction wi, offset past the error bound;
    // and one towards a point (shadow rays). A fibre BSDF on a round curve
    // (Bsdf::isFibre, a far-field model of light entering and leaving the
    // fibre anywhere around it) lets rays leave from the side of the fibre
    // facing their direction, so that they never cross the fibre's inside.
    Ray spawn(const Vec3& wi) const;
    Ray spawnTo(const Vec3& target) const;
    LightSampleContext lightContext() const {
        // A transmissive surface receives light from both sides: no normal.
        return LightSampleContext{si->p, bsdf.isOpaque() ? ng : Vec3(0.0f)};
    }
};

// footprint: width of the ray's footprint at the hit, world units.
ShadingContext makeShadingContext(const World& world, const SurfaceHit& hit, float footprint);

// Emitted radiance towards ctx.wo (zero behind a one-sided emitter).
// `areaLight` is world.areaLightOf(hit): the caller looks it up once and
// also needs it for the MIS weight.
Color emittedTowards(const World& world, const ShadingContext& ctx, uint32_t areaLight);

// One next-event estimate: picks a light by power, samples it, traces the
// shadow ray. With MIS the result carries the power-heuristic weight against
// BSDF sampling (delta lights: weight 1). Always draws one 1D and one 2D value.
Color sampleDirectLight(const World& world, const ShadingContext& ctx, Sampler& sampler,
                        LightSampling sampling, ShadingStats& stats);
// The same for one given light, without light selection (the direct integrator
// estimates every light).
Color estimateLight(const World& world, const ShadingContext& ctx, const Light& light,
                    const Vec2& u, float selectPdf, LightSampling sampling, ShadingStats& stats);

}  // namespace strahl
