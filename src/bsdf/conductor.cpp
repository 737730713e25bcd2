// GGX microfacet conductor (Walter et al. 2007, Heitz 2014/2018) with exact
// complex Fresnel; a perfect mirror below MicrofacetDistribution::kSmoothAlpha.
// Derivations in docs/materials.md, "Conductor".

#include "lobe_sampling.h"
#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/local_frame.h"

namespace strahl::bsdf_models {

Color ConductorModel::f(const Vec3& wo, const Vec3& wi) const {
    if (microfacets.smooth() || wo.z <= 0.0f || wi.z <= 0.0f) return Color(0.0f);
    const Vec3 m = glm::normalize(wo + wi);  // wo + wi != 0: both are above the horizon
    // Torrance-Sparrow: F(wo.m) D(m) G2(wo, wi) / (4 cos theta_o cos theta_i).
    const Color fresnel = fresnelConductor(glm::dot(wo, m), eta, k);
    return fresnel * (microfacets.d(m) * microfacets.g(wo, wi) / (4.0f * wo.z * wi.z));
}

float ConductorModel::pdf(const Vec3& wo, const Vec3& wi) const {
    if (microfacets.smooth() || wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    const Vec3 m = glm::normalize(wo + wi);
    // Visible-normal density times the reflection Jacobian dm/dwi = 1 / (4 wo.m).
    return microfacets.normalPdf(wo, m) / (4.0f * glm::dot(wo, m));
}

std::optional<BsdfSample> ConductorModel::sample(const Vec3& wo, float, const Vec2& u) const {
    if (wo.z <= 0.0f) return std::nullopt;
    if (microfacets.smooth()) {
        BsdfSample s;
        s.wi = reflectZ(wo);
        s.f = fresnelConductor(wo.z, eta, k) / s.wi.z;
        s.pdf = 1.0f;
        s.specular = true;
        return s;
    }
    const Vec3 m = microfacets.sampleNormal(wo, u);
    if (glm::dot(wo, m) <= 0.0f) return std::nullopt;
    return completeSample(*this, wo, reflectDir(wo, m));  // none below the macro surface
}

}  // namespace strahl::bsdf_models
