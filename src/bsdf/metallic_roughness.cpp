// glTF 2.0 metallic-roughness (core specification, Appendix B): a GGX specular
// lobe with Schlick Fresnel, F0 = lerp(f0_dielectric, base, metallic), and a
// (1 - metallic) base-coloured diffuse lobe. Instead of glTF's per-direction
// (1 - F(v.h)) weight, the diffuse lobe is coupled to the dielectric specular's
// directional albedo E (Kelemen & Szirmay-Kalos 2001), which makes a white
// dielectric exactly lossless and the whole BSDF energy conserving. Derivation
// in docs/materials.md, "Metallic-roughness".

#include "lobe_sampling.h"
#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/ggx_albedo.h"

namespace strahl::bsdf_models {

Color MetallicRoughnessModel::specularFresnel(float cosThetaH) const {
    const Color f0 = glm::mix(Color(f0Dielectric), base, metallic);
    return fresnelSchlick(f0, cosThetaH);
}

float MetallicRoughnessModel::specularProbability(const Vec3& wo) const {
    // Lobe weights are the lobes' albedos at wo: the specular E with the mean
    // F0, the diffuse (1 - metallic) mean(base) (1 - E_dielectric(wo)).
    const float alpha = ggx.alphaX();
    const float f0 = mean(glm::mix(Color(f0Dielectric), base, metallic));
    const float s = ggxSchlickAlbedo(wo.z, alpha, f0);
    const float d =
        (1.0f - metallic) * mean(base) * (1.0f - ggxSchlickAlbedo(wo.z, alpha, f0Dielectric));
    return s + d > 0.0f ? s / (s + d) : 1.0f;
}

Color MetallicRoughnessModel::diffuseF(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f || metallic >= 1.0f) return Color(0.0f);
    // (1 - metallic) base / pi (1 - E(wo)) (1 - E(wi)) / (1 - Ebar): the light
    // the dielectric specular does not reflect at wo, redistributed over wi with
    // the reciprocal shape (1 - E(wi)) normalised by its cosine integral.
    const float alpha = ggx.alphaX();
    const float norm = 1.0f - ggxSchlickAverageAlbedo(alpha, f0Dielectric);
    if (norm <= 0.0f) return Color(0.0f);
    const float eo = ggxSchlickAlbedo(wo.z, alpha, f0Dielectric);
    const float ei = ggxSchlickAlbedo(wi.z, alpha, f0Dielectric);
    return base * ((1.0f - metallic) * kInvPi * (1.0f - eo) * (1.0f - ei) / norm);
}

Color MetallicRoughnessModel::f(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return Color(0.0f);
    Color result = diffuseF(wo, wi);
    if (!ggx.smooth()) {
        const Vec3 m = glm::normalize(wo + wi);
        result +=
            specularFresnel(glm::dot(wo, m)) * (ggx.d(m) * ggx.g(wo, wi) / (4.0f * wo.z * wi.z));
    }
    return result;
}

float MetallicRoughnessModel::pdf(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    return microfacetOrDiffusePdf(ggx, specularProbability(wo), wo, wi);
}

std::optional<BsdfSample> MetallicRoughnessModel::sample(const Vec3& wo, float uLobe,
                                                         const Vec2& u) const {
    if (wo.z <= 0.0f) return std::nullopt;
    return sampleMicrofacetOrDiffuse(
        *this, ggx, specularProbability(wo), [&] { return specularFresnel(wo.z); }, wo, uLobe, u);
}

}  // namespace strahl::bsdf_models
