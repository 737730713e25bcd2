// Plastic: a Lambertian base under a dielectric coat, smooth (delta specular)
// or rough (GGX). The diffuse term accounts for the two coat crossings and the
// light bouncing between base and coat (Mitsuba's "plastic"); derivation in
// docs/materials.md, "Plastic".

#include "lobe_sampling.h"
#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/fresnel.h"

namespace strahl::bsdf_models {

float PlasticModel::specularProbability(float fresnelO) const {
    // Lobe weights: the coat's reflectance F(wo) against the diffuse albedo
    // (1 - F(wo)) kd (1 - Fbar_int) / (1 - kd Fbar_int) (see diffuseF).
    const Color multiple = (Color(1.0f) - kd * internalReflectance);
    const Color diffuseAlbedo = kd * (1.0f - internalReflectance) / multiple;
    const float d = (1.0f - fresnelO) * mean(diffuseAlbedo);
    return fresnelO + d > 0.0f ? fresnelO / (fresnelO + d) : 1.0f;
}

Color PlasticModel::diffuseF(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return Color(0.0f);
    // (1 - F(wi)) (1 - F(wo)) kd / (pi eta^2 (1 - kd Fbar_int)): transmission in
    // and out of the coat, the radiance compression 1 / eta^2 of the way out,
    // and the geometric series of base-coat inter-reflections.
    const float tIn = 1.0f - fresnelDielectric(wi.z, eta);
    const float tOut = 1.0f - fresnelDielectric(wo.z, eta);
    const Color denom = kPi * eta * eta * (Color(1.0f) - kd * internalReflectance);
    return tIn * tOut * kd / denom;
}

Color PlasticModel::f(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return Color(0.0f);
    Color result = diffuseF(wo, wi);
    if (!microfacets.smooth()) {
        const Vec3 m = glm::normalize(wo + wi);
        const float fresnel = fresnelDielectric(glm::dot(wo, m), eta);
        result += Color(fresnel * microfacets.d(m) * microfacets.g(wo, wi) / (4.0f * wo.z * wi.z));
    }
    return result;
}

float PlasticModel::pdf(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    return microfacetOrDiffusePdf(microfacets, specularProbability(fresnelDielectric(wo.z, eta)), wo, wi);
}

std::optional<BsdfSample> PlasticModel::sample(const Vec3& wo, float uLobe, const Vec2& u) const {
    if (wo.z <= 0.0f) return std::nullopt;
    const float fresnelO = fresnelDielectric(wo.z, eta);
    return sampleMicrofacetOrDiffuse(
        *this, microfacets, specularProbability(fresnelO), [&] { return fresnelO; }, wo, uLobe, u);
}

}  // namespace strahl::bsdf_models
