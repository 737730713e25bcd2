// Dielectric interface: smooth (delta reflection and refraction chosen by
// Fresnel) and rough (Walter et al. 2007 with visible-normal sampling), in
// radiance transport (transmission scaled by 1 / etap^2). Derivations in
// docs/materials.md, "Dielectric".

#include <cmath>

#include "lobe_sampling.h"
#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/local_frame.h"

namespace strahl::bsdf_models {

namespace {

// The generalised half vector of a pair (wo, wi) (Walter et al. 2007, eq. 16),
// facing +z, with the relative index etap of the crossing (1 for reflection);
// false if the pair cannot be connected by a front-facing microfacet.
bool halfVector(const Vec3& wo, const Vec3& wi, float eta, Vec3& wm, float& etap) {
    const float cosO = wo.z, cosI = wi.z;
    if (cosO == 0.0f || cosI == 0.0f) return false;
    const bool reflect = cosO * cosI > 0.0f;
    etap = reflect ? 1.0f : (cosO > 0.0f ? eta : 1.0f / eta);
    wm = wi * etap + wo;
    if (glm::dot(wm, wm) == 0.0f) return false;
    wm = glm::normalize(wm);
    if (wm.z < 0.0f) wm = -wm;
    // Microfacets seen from behind by either direction carry no light.
    return glm::dot(wm, wi) * cosI > 0.0f && glm::dot(wm, wo) * cosO > 0.0f;
}

}  // namespace

Color DielectricModel::f(const Vec3& wo, const Vec3& wi) const {
    if (smooth()) return Color(0.0f);
    Vec3 wm;
    float etap;
    if (!halfVector(wo, wi, eta, wm, etap)) return Color(0.0f);
    const float fresnel = fresnelDielectric(glm::dot(wo, wm), eta);
    const float dg = microfacets.d(wm) * microfacets.g(wo, wi);
    if (etap == 1.0f) return tint * (dg * fresnel / std::abs(4.0f * wi.z * wo.z));
    // Walter et al. eq. 21: D G (1 - F) |wi.m| |wo.m| / (|cos_i cos_o| (wi.m + wo.m / etap)^2),
    // then / etap^2 for radiance.
    const float cosIm = glm::dot(wi, wm), cosOm = glm::dot(wo, wm);
    const float sqrtDenom = cosIm + cosOm / etap;
    const float denom = sqrtDenom * sqrtDenom * wi.z * wo.z;
    if (denom == 0.0f) return Color(0.0f);
    const float ft = dg * (1.0f - fresnel) * std::abs(cosIm * cosOm / denom);
    return tint * (ft / (etap * etap));
}

float DielectricModel::pdf(const Vec3& wo, const Vec3& wi) const {
    if (smooth()) return 0.0f;
    Vec3 wm;
    float etap;
    if (!halfVector(wo, wi, eta, wm, etap)) return 0.0f;
    // The lobe is chosen with probability R (reflection) or T = 1 - R.
    const float r = fresnelDielectric(glm::dot(wo, wm), eta);
    const float cosOm = glm::dot(wo, wm), cosIm = glm::dot(wi, wm);
    if (etap == 1.0f) return microfacets.normalPdf(wo, wm) / (4.0f * std::abs(cosOm)) * r;
    // Refraction Jacobian dm/dwi = |wi.m| / (wi.m + wo.m / etap)^2.
    const float sqrtDenom = cosIm + cosOm / etap;
    if (sqrtDenom == 0.0f) return 0.0f;
    const float dwmDwi = std::abs(cosIm) / (sqrtDenom * sqrtDenom);
    return microfacets.normalPdf(wo, wm) * dwmDwi * (1.0f - r);
}

std::optional<BsdfSample> DielectricModel::sample(const Vec3& wo, float uLobe,
                                                  const Vec2& u) const {
    if (wo.z == 0.0f) return std::nullopt;
    BsdfSample s;
    if (smooth()) {
        const float r = fresnelDielectric(wo.z, eta), t = 1.0f - r;
        s.specular = true;
        if (uLobe < r) return deltaReflection(wo, tint, r);
        float etap;
        if (t <= 0.0f || !refractDir(wo, Vec3(0.0f, 0.0f, 1.0f), eta, s.wi, etap) ||
            s.wi.z == 0.0f) {
            return std::nullopt;
        }
        s.f = tint * (t / (std::abs(s.wi.z) * etap * etap));
        s.pdf = t;
        s.transmission = true;
        s.eta = etap;
        return s;
    }
    const Vec3 wm = microfacets.sampleNormal(wo, u);
    const float r = fresnelDielectric(glm::dot(wo, wm), eta);
    if (uLobe < r) {
        s.wi = reflectDir(wo, wm);
        if (!sameHemisphere(wo, s.wi)) return std::nullopt;
    } else {
        float etap;
        if (!refractDir(wo, wm, eta, s.wi, etap)) return std::nullopt;
        if (sameHemisphere(wo, s.wi) || s.wi.z == 0.0f) return std::nullopt;
        s.transmission = true;
        s.eta = etap;
    }
    s.pdf = pdf(wo, s.wi);
    if (!(s.pdf > 0.0f)) return std::nullopt;
    s.f = f(wo, s.wi);
    return s;
}

}  // namespace strahl::bsdf_models
