#pragma once
// Fresnel reflectance of smooth interfaces for unpolarised light: exact
// dielectric and complex-conductor equations, Schlick's approximation, and the
// hemispherical average a diffuse layer under a coat needs (docs/materials.md).

#include "strahl/core/math.h"

namespace strahl {

// Dielectric interface with eta = n_inside / n_outside. cosThetaI is the cosine
// between the incident direction and the outward normal: negative means the
// light arrives from inside (the relative index is then 1 / eta). Returns 1
// under total internal reflection.
float fresnelDielectric(float cosThetaI, float eta);

// Conductor with complex index eta + i k seen from a dielectric of index 1;
// cosThetaI is clamped to [0, 1]. eta = 0 with k > 0 reflects everything (a
// lossless mirror), k = 0 falls back to the dielectric equation.
float fresnelConductor(float cosThetaI, float eta, float k);
Color fresnelConductor(float cosThetaI, const Color& eta, const Color& k);

// Schlick (1994): F0 + (1 - F0) (1 - cos)^5.
inline float schlickWeight(float cosTheta) {
    const float m = glm::clamp(1.0f - cosTheta, 0.0f, 1.0f);
    const float m2 = m * m;
    return m2 * m2 * m;
}
inline Color fresnelSchlick(const Color& f0, float cosTheta) {
    return f0 + (Color(1.0f) - f0) * schlickWeight(cosTheta);
}
inline float fresnelSchlick(float f0, float cosTheta) {
    return f0 + (1.0f - f0) * schlickWeight(cosTheta);
}

// Normal-incidence reflectance of a dielectric, ((eta - 1) / (eta + 1))^2.
inline float dielectricF0(float eta) {
    const float r = (eta - 1.0f) / (eta + 1.0f);
    return r * r;
}

// Cosine-weighted hemispherical average 2 * integral_0^1 F(mu, eta) mu dmu of
// the reflectance for light arriving from the outside of an interface with
// relative index eta. The average seen from inside is fresnelDiffuseReflectance
// (1 / eta) = 1 - (1 - fresnelDiffuseReflectance(eta)) / eta^2.
float fresnelDiffuseReflectance(float eta);

}  // namespace strahl
