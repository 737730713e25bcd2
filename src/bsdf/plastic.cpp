// Plastic: a Lambertian base under a dielectric coat, smooth (delta specular)
// or rough (microfacets). The diffuse term accounts for the two coat crossings and the
// light bouncing between base and coat (Mitsuba's "plastic"); derivation in
// docs/materials.md, "Plastic".

#include "lobe_sampling.h"
#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/fresnel.h"

namespace strahl::bsdf_models {

float PlasticModel::coatTransmittance(float cosTheta) const {
    if (roughCoat && !microfacets.smooth())
        return roughCoat->transmittance(microfacets.alphaX(), cosTheta);
    return 1.0f - fresnelDielectric(cosTheta, eta);
}

float PlasticModel::specularProbability(float coatTransmittanceO) const {
    // Lobe weights: what the coat reflects, about 1 - T(wo), against the
    // diffuse albedo T(wo) kd (1 - Fbar_int) / (1 - kd Fbar_int) (see diffuseF).
    const Color diffuseAlbedo = kd * (1.0f - internalReflectance) / interreflection();
    const float r = 1.0f - coatTransmittanceO;
    const float d = coatTransmittanceO * mean(diffuseAlbedo);
    return r + d > 0.0f ? r / (r + d) : 1.0f;
}

Color PlasticModel::diffuseF(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return Color(0.0f);
    // T(wi) T(wo) kd / (pi eta^2 (1 - kd Fbar_int)): transmission in and out
    // of the coat, the radiance compression 1 / eta^2 of the way out, and the
    // geometric series of base-coat inter-reflections (Mitsuba's "linear"
    // variant leaves kd out of the series: 1 - Fbar_int).
    const float tIn = coatTransmittance(wi.z), tOut = coatTransmittance(wo.z);
    return tIn * tOut * kd / (kPi * eta * eta * interreflection());
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
    return microfacetOrDiffusePdf(microfacets, specularProbability(coatTransmittance(wo.z)), wo, wi);
}

std::optional<BsdfSample> PlasticModel::sample(const Vec3& wo, float uLobe, const Vec2& u) const {
    if (wo.z <= 0.0f) return std::nullopt;
    const float transmittanceO = coatTransmittance(wo.z);
    return sampleMicrofacetOrDiffuse(
        *this, microfacets, specularProbability(transmittanceO),
        [&] { return 1.0f - transmittanceO; }, wo, uLobe, u);
}

}  // namespace strahl::bsdf_models
