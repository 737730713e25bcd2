// Lambertian reflection and the Phong family: modified Phong (Lafortune &
// Willems 1994) and Blinn-Phong with the Ashikhmin-Shirley (2000) normalisation.
// Derivations in docs/materials.md, "Lambert" and "Phong and Blinn-Phong".

#include <cmath>

#include "lobe_sampling.h"
#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/local_frame.h"
#include "strahl/core/sampling.h"

namespace strahl::bsdf_models {

namespace {

// The unit vector at polar angle acos(cosTheta) and azimuth 2 pi v around axis.
Vec3 aroundAxis(const Vec3& axis, float cosTheta, float v) {
    Vec3 b1, b2;
    orthonormalBasis(axis, b1, b2);
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const float phi = 2.0f * kPi * v;
    return glm::normalize(sinTheta * (std::cos(phi) * b1 + std::sin(phi) * b2) + cosTheta * axis);
}

}  // namespace

// ---- Lambert -------------------------------------------------------------------

Color LambertModel::f(const Vec3& wo, const Vec3& wi) const {
    return (wo.z > 0.0f && wi.z > 0.0f) ? reflectance * kInvPi : Color(0.0f);
}

float LambertModel::pdf(const Vec3& wo, const Vec3& wi) const {
    return wo.z > 0.0f ? cosineHemispherePdf(wi.z) : 0.0f;
}

std::optional<BsdfSample> LambertModel::sample(const Vec3& wo, float, const Vec2& u) const {
    if (wo.z <= 0.0f || maxComponent(reflectance) <= 0.0f) return std::nullopt;
    BsdfSample s;
    s.wi = sampleCosineHemisphere(u);
    s.pdf = cosineHemispherePdf(s.wi.z);
    if (s.pdf <= 0.0f) return std::nullopt;  // the disk's rim maps onto the horizon
    s.f = reflectance * kInvPi;
    return s;
}

// ---- Diffuse transmission ------------------------------------------------------

float DiffuseTransmissionModel::reflectProbability() const {
    const float r = mean(reflectance), t = mean(transmittance);
    return r + t > 0.0f ? r / (r + t) : 0.5f;
}

Color DiffuseTransmissionModel::f(const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0.0f || wi.z == 0.0f) return Color(0.0f);
    return (wo.z > 0.0f) == (wi.z > 0.0f) ? reflectance * kInvPi : transmittance * kInvPi;
}

float DiffuseTransmissionModel::pdf(const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0.0f) return 0.0f;
    const float pr = reflectProbability();
    const bool sameSide = (wo.z > 0.0f) == (wi.z > 0.0f);
    return (sameSide ? pr : 1.0f - pr) * cosineHemispherePdf(std::abs(wi.z));
}

std::optional<BsdfSample> DiffuseTransmissionModel::sample(const Vec3& wo, float uLobe, const Vec2& u) const {
    if (wo.z == 0.0f || maxComponent(reflectance + transmittance) <= 0.0f) return std::nullopt;
    const float pr = reflectProbability();
    const bool reflect = uLobe < pr;
    BsdfSample s;
    s.wi = sampleCosineHemisphere(u);
    // The cosine lobe on wo's side to reflect, on the other to transmit.
    if ((wo.z < 0.0f) == reflect) s.wi.z = -s.wi.z;
    s.pdf = (reflect ? pr : 1.0f - pr) * cosineHemispherePdf(std::abs(s.wi.z));
    if (!(s.pdf > 0.0f)) return std::nullopt;
    s.f = (reflect ? reflectance : transmittance) * kInvPi;
    s.transmission = !reflect;
    return s;
}

// ---- Phong and Blinn-Phong -----------------------------------------------------

float PhongModel::specularProbability() const {
    const float d = mean(kd), s = mean(ks);
    return d + s > 0.0f ? s / (d + s) : 0.0f;
}

Color PhongModel::specularF(const Vec3& wo, const Vec3& wi) const {
    if (blinn) {
        // ks (n + 1) / (8 pi) cos^n theta_h / ((wo.h) max(cos theta_o, cos theta_i)):
        // the half-vector density (n + 1) / (2 pi) cos^n theta_h mapped to wi
        // (Jacobian 1 / (4 wo.h)) and divided by max(cos) instead of cos theta_i,
        // which bounds the albedo by ks for every wo.
        const Vec3 sum = wo + wi;
        if (glm::dot(sum, sum) == 0.0f) return Color(0.0f);
        const Vec3 h = glm::normalize(sum);
        const float woDotH = glm::dot(wo, h);
        if (h.z <= 0.0f || woDotH <= 0.0f) return Color(0.0f);
        const float lobe = (exponent + 1.0f) / (8.0f * kPi) * std::pow(h.z, exponent);
        return ks * (lobe / (woDotH * std::max(wo.z, wi.z)));
    }
    // ks (n + 2) / (2 pi) cos^n alpha, alpha the angle between wi and the mirror of wo.
    const float cosAlpha = glm::dot(wi, reflectZ(wo));
    if (cosAlpha <= 0.0f) return Color(0.0f);
    return ks * ((exponent + 2.0f) / (2.0f * kPi) * std::pow(cosAlpha, exponent));
}

float PhongModel::specularPdf(const Vec3& wo, const Vec3& wi) const {
    if (blinn) {
        const Vec3 sum = wo + wi;
        if (glm::dot(sum, sum) == 0.0f) return 0.0f;
        const Vec3 h = glm::normalize(sum);
        const float woDotH = glm::dot(wo, h);
        if (h.z <= 0.0f || woDotH <= 0.0f) return 0.0f;
        return (exponent + 1.0f) / (2.0f * kPi) * std::pow(h.z, exponent) / (4.0f * woDotH);
    }
    const float cosAlpha = glm::dot(wi, reflectZ(wo));
    if (cosAlpha <= 0.0f) return 0.0f;
    return (exponent + 1.0f) / (2.0f * kPi) * std::pow(cosAlpha, exponent);
}

Color PhongModel::f(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return Color(0.0f);
    return kd * kInvPi + specularF(wo, wi);
}

float PhongModel::pdf(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    const float ps = specularProbability();
    return (1.0f - ps) * cosineHemispherePdf(wi.z) + ps * specularPdf(wo, wi);
}

std::optional<BsdfSample> PhongModel::sample(const Vec3& wo, float uLobe, const Vec2& u) const {
    if (wo.z <= 0.0f || maxComponent(kd) + maxComponent(ks) <= 0.0f) return std::nullopt;
    Vec3 wi;
    if (uLobe < specularProbability()) {
        // Both lobes invert cos^n: the CDF of cos theta under (n + 1) cos^n theta
        // sin theta is cos^(n+1) theta, so cos theta = u^(1 / (n + 1)).
        const float cosTheta = std::pow(u.x, 1.0f / (exponent + 1.0f));
        if (blinn) {
            const Vec3 h = aroundAxis(Vec3(0.0f, 0.0f, 1.0f), cosTheta, u.y);
            if (glm::dot(wo, h) <= 0.0f) return std::nullopt;
            wi = reflectDir(wo, h);
        } else {
            wi = aroundAxis(reflectZ(wo), cosTheta, u.y);
        }
    } else {
        wi = sampleCosineHemisphere(u);
    }
    return completeSample(*this, wo, wi);
}

}  // namespace strahl::bsdf_models
