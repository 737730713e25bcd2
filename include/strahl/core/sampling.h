#pragma once
// Warps from the unit square to the shapes light transport samples, with their
// densities (pbrt-v4 A.5). Every function maps [0, 1)^2 onto its domain.

#include <algorithm>
#include <cmath>

#include "strahl/core/math.h"

namespace strahl {

// Shirley-Chiu concentric map onto the unit disk (area-preserving, low
// distortion, so stratification survives).
inline Vec2 sampleConcentricDisk(const Vec2& u) {
    const Vec2 o = 2.0f * u - Vec2(1.0f);
    if (o.x == 0.0f && o.y == 0.0f) return Vec2(0.0f);
    float r, theta;
    if (std::abs(o.x) > std::abs(o.y)) {
        r = o.x;
        theta = 0.25f * kPi * (o.y / o.x);
    } else {
        r = o.y;
        theta = 0.5f * kPi - 0.25f * kPi * (o.x / o.y);
    }
    return r * Vec2(std::cos(theta), std::sin(theta));
}

// Cosine-weighted upper hemisphere (Malley's method); pdf = cos(theta) / pi.
inline Vec3 sampleCosineHemisphere(const Vec2& u) {
    const Vec2 d = sampleConcentricDisk(u);
    const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
    return Vec3(d.x, d.y, z);
}
inline float cosineHemispherePdf(float cosTheta) { return std::max(cosTheta, 0.0f) * kInvPi; }

// Uniform over the sphere; pdf = 1 / (4 pi).
inline Vec3 sampleUniformSphere(const Vec2& u) {
    const float z = 1.0f - 2.0f * u.x;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPi * u.y;
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}
inline constexpr float kUniformSpherePdf = 0.25f * kInvPi;

// Uniform over the cone of directions within acos(cosMax) of +z;
// pdf = 1 / (2 pi (1 - cosMax)).
inline Vec3 sampleUniformCone(const Vec2& u, float cosMax) {
    const float cosTheta = (1.0f - u.x) + u.x * cosMax;
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const float phi = 2.0f * kPi * u.y;
    return Vec3(std::cos(phi) * sinTheta, std::sin(phi) * sinTheta, cosTheta);
}
inline float uniformConePdf(float cosMax) { return 1.0f / (2.0f * kPi * (1.0f - cosMax)); }

// The same cone given by h = 1 - cos(thetaMax), which the caller computes as
// 2 sin^2(thetaMax / 2): exact also for cones too narrow for cosMax in float
// (the sun's 4.65e-3 rad has 1 - cos = 1.08e-5, and cos in float would be off
// by 0.5%). Height hs = u.x h below the pole gives cos = 1 - hs and
// sin = sqrt(hs (2 - hs)) without cancellation. pdf = 1 / (2 pi h).
inline Vec3 sampleUniformConeHeight(const Vec2& u, float h) {
    const float hs = u.x * h;
    const float sinTheta = std::sqrt(std::max(0.0f, hs * (2.0f - hs)));
    const float phi = 2.0f * kPi * u.y;
    return Vec3(std::cos(phi) * sinTheta, std::sin(phi) * sinTheta, 1.0f - hs);
}
inline float uniformConeHeightPdf(float h) { return 1.0f / (2.0f * kPi * h); }

// Uniform over a triangle: barycentrics (b0, b1, b2) by the square-root-free
// warp of Heitz 2019 ("A Low-Distortion Map Between Triangle and Square").
inline Vec3 sampleUniformTriangle(const Vec2& u) {
    float b0, b1;
    if (u.x < u.y) {
        b0 = u.x / 2.0f;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2.0f;
        b0 = u.x - b1;
    }
    return Vec3(b0, b1, 1.0f - b0 - b1);
}

// Power heuristic with beta = 2 (Veach 1997) for two strategies with nf and ng
// samples and densities fPdf, gPdf.
inline float powerHeuristic(int nf, float fPdf, int ng, float gPdf) {
    const float f = static_cast<float>(nf) * fPdf, g = static_cast<float>(ng) * gPdf;
    if (std::isinf(f * f)) return 1.0f;
    const float denom = f * f + g * g;
    return denom > 0.0f ? (f * f) / denom : 0.0f;
}

}  // namespace strahl
