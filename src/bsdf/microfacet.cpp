// GGX and Beckmann distributions, Smith masking (height-correlated or
// separable), and their normal sampling. Derivations in docs/materials.md,
// "Microfacet distributions".

#include "strahl/bsdf/microfacet.h"

#include <algorithm>
#include <cmath>

#include "strahl/core/sampling.h"

namespace strahl {

namespace {

// Rough surfaces keep each axis at least this large, so an anisotropic lobe
// with one zero axis stays finite (1e-4^-2 = 1e8 keeps D's denominator well
// inside float range).
constexpr float kMinRoughAlpha = 1e-4f;

}  // namespace

MicrofacetDistribution::MicrofacetDistribution(float alphaX, float alphaY, MicrofacetModel model)
    : model_(model), smooth_(std::max(alphaX, alphaY) < kSmoothAlpha) {
    alphaX_ = smooth_ ? alphaX : std::max(alphaX, kMinRoughAlpha);
    alphaY_ = smooth_ ? alphaY : std::max(alphaY, kMinRoughAlpha);
}

float MicrofacetDistribution::d(const Vec3& m) const {
    if (m.z <= 0.0f) return 0.0f;
    return model_.type == MicrofacetType::Ggx ? ggxD(m) : beckmannD(m);
}

float MicrofacetDistribution::ggxD(const Vec3& m) const {
    // D = 1 / (pi ax ay cos^4 (1 + tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2))^2)
    //   = 1 / (pi ax ay (mx^2 / ax^2 + my^2 / ay^2 + mz^2)^2), free of tan and phi.
    const float sx = m.x / alphaX_, sy = m.y / alphaY_;
    const float s = sx * sx + sy * sy + m.z * m.z;
    return 1.0f / (kPi * alphaX_ * alphaY_ * s * s);
}

float MicrofacetDistribution::beckmannD(const Vec3& m) const {
    // D = exp(-tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2)) / (pi ax ay cos^4)
    //   = exp(-(mx^2 / ax^2 + my^2 / ay^2) / mz^2) / (pi ax ay mz^4).
    const float sx = m.x / alphaX_, sy = m.y / alphaY_;
    const float z2 = m.z * m.z;
    return std::exp(-(sx * sx + sy * sy) / z2) / (kPi * alphaX_ * alphaY_ * z2 * z2);
}

float MicrofacetDistribution::lambda(const Vec3& w) const {
    // alpha(phi)^2 tan^2 theta = (ax^2 wx^2 + ay^2 wy^2) / wz^2.
    const float z2 = w.z * w.z;
    const float a2t2Num = alphaX_ * alphaX_ * w.x * w.x + alphaY_ * alphaY_ * w.y * w.y;
    if (a2t2Num == 0.0f) return 0.0f;  // normal view: nothing masked
    if (z2 == 0.0f) return kInfinity;
    if (model_.type == MicrofacetType::Ggx) {
        // Lambda = (sqrt(1 + alpha(phi)^2 tan^2 theta) - 1) / 2.
        return 0.5f * (std::sqrt(1.0f + a2t2Num / z2) - 1.0f);
    }
    // Beckmann, with a = 1 / (alpha(phi) tan theta):
    // Lambda = (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)); erfc keeps the
    // digits of erf(a) - 1 for large a.
    const float a = std::sqrt(z2 / a2t2Num);
    constexpr float kInvSqrtPi = 0.5641895835f;
    return 0.5f * (std::exp(-a * a) * kInvSqrtPi / a - std::erfc(a));
}

float MicrofacetDistribution::g(const Vec3& wo, const Vec3& wi) const {
    if (model_.masking == MicrofacetMasking::Separable) return g1(wo) * g1(wi);
    return 1.0f / (1.0f + lambda(wo) + lambda(wi));
}

float MicrofacetDistribution::normalPdf(const Vec3& w, const Vec3& m) const {
    if (model_.type == MicrofacetType::Beckmann) return d(m) * m.z;
    const Vec3 wv = w.z < 0.0f ? -w : w;
    if (wv.z == 0.0f) return 0.0f;
    const float cosWm = glm::dot(wv, m);
    if (cosWm <= 0.0f) return 0.0f;
    return g1(wv) * cosWm * d(m) / wv.z;
}

Vec3 MicrofacetDistribution::sampleNormal(const Vec3& w, const Vec2& u) const {
    return model_.type == MicrofacetType::Ggx ? sampleGgxVisibleNormal(w, u)
                                              : sampleBeckmannNormal(u);
}

Vec3 MicrofacetDistribution::sampleGgxVisibleNormal(const Vec3& w, const Vec2& u) const {
    const Vec3 wv = w.z < 0.0f ? -w : w;
    // Stretch the view direction to the hemisphere configuration (alpha = 1).
    const Vec3 wh = glm::normalize(Vec3(alphaX_ * wv.x, alphaY_ * wv.y, wv.z));
    // Orthonormal basis around wh; T1 is horizontal (undefined, so fixed, at normal view).
    const float lenSq = wh.x * wh.x + wh.y * wh.y;
    const Vec3 t1 = lenSq > 0.0f ? Vec3(-wh.y, wh.x, 0.0f) / std::sqrt(lenSq) : Vec3(1, 0, 0);
    const Vec3 t2 = glm::cross(wh, t1);
    // A uniform disk point, its t2 coordinate warped so the disk becomes the
    // projection of the visible half of the hemisphere (half disk + half ellipse).
    Vec2 p = sampleConcentricDisk(u);
    const float h = std::sqrt(std::max(0.0f, 1.0f - p.x * p.x));
    const float s = 0.5f * (1.0f + wh.z);
    p.y = (1.0f - s) * h + s * p.y;
    const float pz = std::sqrt(std::max(0.0f, 1.0f - p.x * p.x - p.y * p.y));
    const Vec3 nh = p.x * t1 + p.y * t2 + pz * wh;
    // Unstretch back to the ellipsoid configuration.
    return glm::normalize(Vec3(alphaX_ * nh.x, alphaY_ * nh.y, std::max(1e-6f, nh.z)));
}

Vec3 MicrofacetDistribution::sampleBeckmannNormal(const Vec2& u) const {
    // In slope space (x, y) = -(mx, my) / mz the Beckmann D(m) cos(theta_m) dm
    // is the Gaussian exp(-x^2/ax^2 - y^2/ay^2) / (pi ax ay) dx dy: two
    // independent normals of standard deviation a / sqrt(2), drawn by Box-Muller.
    const float r = std::sqrt(-std::log(std::max(1.0f - u.x, 1e-30f)));
    const float phi = 2.0f * kPi * u.y;
    const float slopeX = alphaX_ * r * std::cos(phi), slopeY = alphaY_ * r * std::sin(phi);
    return glm::normalize(Vec3(-slopeX, -slopeY, 1.0f));
}

}  // namespace strahl
