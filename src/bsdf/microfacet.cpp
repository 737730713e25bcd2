// GGX distribution, height-correlated Smith masking and visible-normal sampling.
// Derivations in docs/materials.md, "GGX microfacet distribution".

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

GgxDistribution::GgxDistribution(float alphaX, float alphaY)
    : smooth_(std::max(alphaX, alphaY) < kSmoothAlpha) {
    alphaX_ = smooth_ ? alphaX : std::max(alphaX, kMinRoughAlpha);
    alphaY_ = smooth_ ? alphaY : std::max(alphaY, kMinRoughAlpha);
}

float GgxDistribution::d(const Vec3& m) const {
    if (m.z <= 0.0f) return 0.0f;
    // D = 1 / (pi ax ay cos^4 (1 + tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2))^2)
    //   = 1 / (pi ax ay (mx^2 / ax^2 + my^2 / ay^2 + mz^2)^2), free of tan and phi.
    const float sx = m.x / alphaX_, sy = m.y / alphaY_;
    const float s = sx * sx + sy * sy + m.z * m.z;
    return 1.0f / (kPi * alphaX_ * alphaY_ * s * s);
}

float GgxDistribution::lambda(const Vec3& w) const {
    // Lambda = (sqrt(1 + alpha(phi)^2 tan^2 theta) - 1) / 2 with
    // alpha(phi)^2 tan^2 theta = (ax^2 wx^2 + ay^2 wy^2) / wz^2.
    const float z2 = w.z * w.z;
    const float a2t2Num = alphaX_ * alphaX_ * w.x * w.x + alphaY_ * alphaY_ * w.y * w.y;
    if (z2 == 0.0f) return a2t2Num > 0.0f ? kInfinity : 0.0f;
    return 0.5f * (std::sqrt(1.0f + a2t2Num / z2) - 1.0f);
}

float GgxDistribution::visibleD(const Vec3& w, const Vec3& m) const {
    const Vec3 wv = w.z < 0.0f ? -w : w;
    if (wv.z == 0.0f) return 0.0f;
    const float cosWm = glm::dot(wv, m);
    if (cosWm <= 0.0f) return 0.0f;
    return g1(wv) * cosWm * d(m) / wv.z;
}

Vec3 GgxDistribution::sampleVisibleNormal(const Vec3& w, const Vec2& u) const {
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

}  // namespace strahl
