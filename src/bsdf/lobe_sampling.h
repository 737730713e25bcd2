#pragma once
// Internal to the bsdf module: the sampling steps the opaque two-lobe models
// (Phong, plastic, metallic-roughness) and the conductor share, and the delta
// reflection of the dielectrics. All work in the local frame; the opaque
// models' with wo in the upper hemisphere (see bsdf_models.h).

#include <optional>

#include "strahl/bsdf/bsdf.h"
#include "strahl/bsdf/local_frame.h"
#include "strahl/bsdf/microfacet.h"
#include "strahl/core/sampling.h"

namespace strahl::bsdf_models {

inline float mean(const Color& c) {
    return (c.r + c.g + c.b) / 3.0f;
}

// The delta mirror reflection about +z chosen with probability `probability`
// (its pdf), carrying `weight` (f |cos| / pdf): f = weight probability / |cos|.
inline BsdfSample deltaReflection(const Vec3& wo, const Color& weight, float probability) {
    BsdfSample s;
    s.wi = reflectZ(wo);
    s.f = weight * (probability / std::abs(s.wi.z));
    s.pdf = probability;
    s.specular = true;
    return s;
}

// The sample of a non-delta lobe once its direction wi is drawn: nullopt when
// wi is at or below the horizon or model.pdf(wo, wi) is not positive (or NaN),
// else wi with the model's own pdf() and f(). Taking both from the model, not
// from the lobe that drew wi, keeps a sample of a lobe mixture consistent with
// what pdf() and f() return for the same pair (one-sample MIS over the lobes).
template <typename Model>
std::optional<BsdfSample> completeSample(const Model& model, const Vec3& wo, const Vec3& wi) {
    if (wi.z <= 0.0f) return std::nullopt;
    BsdfSample s;
    s.wi = wi;
    s.pdf = model.pdf(wo, wi);
    if (!(s.pdf > 0.0f)) return std::nullopt;
    s.f = model.f(wo, wi);
    return s;
}

// Samples a microfacet specular lobe, chosen with probability specularProbability, or
// else the cosine-weighted diffuse lobe (PlasticModel, MetallicRoughnessModel).
// A smooth distribution makes the specular lobe the delta mirror reflectZ(wo), weighted
// by mirrorFresnel() (called only then: the Fresnel reflectance at wo.z) with
// the lobe probability as its pdf; a rough one reflects wo about a visible
// normal. The non-delta samples are finished by completeSample.
template <typename Model, typename MirrorFresnel>
std::optional<BsdfSample> sampleMicrofacetOrDiffuse(const Model& model, const MicrofacetDistribution& microfacets,
                                             float specularProbability,
                                             const MirrorFresnel& mirrorFresnel, const Vec3& wo,
                                             float uLobe, const Vec2& u) {
    Vec3 wi;
    if (uLobe < specularProbability) {
        if (microfacets.smooth()) {
            BsdfSample s;
            s.wi = reflectZ(wo);
            s.f = Color(mirrorFresnel()) / s.wi.z;
            s.pdf = specularProbability;
            s.specular = true;
            return s;
        }
        const Vec3 m = microfacets.sampleNormal(wo, u);
        if (glm::dot(wo, m) <= 0.0f) return std::nullopt;
        wi = reflectDir(wo, m);
    } else {
        wi = sampleCosineHemisphere(u);
    }
    return completeSample(model, wo, wi);
}

// The pdf of that mixture: (1 - ps) times the cosine density, plus ps times
// the visible-normal density of the reflection (pdf 0 for a delta mirror).
// wo and wi must both be in the upper hemisphere.
inline float microfacetOrDiffusePdf(const MicrofacetDistribution& microfacets, float specularProbability, const Vec3& wo,
                             const Vec3& wi) {
    float result = (1.0f - specularProbability) * cosineHemispherePdf(wi.z);
    if (!microfacets.smooth()) {
        const Vec3 m = glm::normalize(wo + wi);
        result += specularProbability * microfacets.normalPdf(wo, m) / (4.0f * glm::dot(wo, m));
    }
    return result;
}

}  // namespace strahl::bsdf_models
