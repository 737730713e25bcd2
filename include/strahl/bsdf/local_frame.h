#pragma once
// Trigonometry of directions in the local shading frame (normal = +z) and the
// two ideal-specular direction maps, reflection and refraction (pbrt-v4 9.1,
// 9.3). Every BSDF of the module works in this frame.

#include <algorithm>
#include <cmath>

#include "strahl/core/math.h"

namespace strahl {

inline float cosTheta(const Vec3& w) {
    return w.z;
}
inline float absCosTheta(const Vec3& w) {
    return std::abs(w.z);
}
inline float sin2Theta(const Vec3& w) {
    return std::max(0.0f, 1.0f - w.z * w.z);
}
inline bool sameHemisphere(const Vec3& a, const Vec3& b) {
    return a.z * b.z > 0.0f;
}

// The mirror image of w about the unit normal n (both pointing away).
inline Vec3 reflectDir(const Vec3& w, const Vec3& n) {
    return 2.0f * glm::dot(w, n) * n - w;
}

// Mirror reflection about the shading normal +z.
inline Vec3 reflectZ(const Vec3& w) {
    return Vec3(-w.x, -w.y, w.z);
}

// Refracts w (pointing away) through the interface with unit normal n, where
// eta = n_inside / n_outside and n points to the outside. w may be on either
// side. On success wt is the transmitted direction (pointing away, unit) and
// etap = n_t / n_i the relative index of the crossing; false on total internal
// reflection.
inline bool refractDir(const Vec3& w, Vec3 n, float eta, Vec3& wt, float& etap) {
    float cosI = glm::dot(n, w);
    if (cosI < 0.0f) {  // w is inside: swap the media
        eta = 1.0f / eta;
        cosI = -cosI;
        n = -n;
    }
    const float sin2T = std::max(0.0f, 1.0f - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0f) return false;
    const float cosT = std::sqrt(1.0f - sin2T);
    wt = -w / eta + (cosI / eta - cosT) * n;
    etap = eta;
    return true;
}

}  // namespace strahl
