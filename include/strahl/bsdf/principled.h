#pragma once
// The parameters of the principled BSDF (PrincipledModel in bsdf_models.h)
// and what its lobes derive from them once per shading point. Definitions,
// ranges and the Mitsuba correspondence: docs/materials.md, "Principled".

#include "strahl/bsdf/microfacet.h"
#include "strahl/core/math.h"

namespace strahl {

// Burley's parameters, each in [0, 1] unless said otherwise.
struct PrincipledParameters {
    Color base{0.5f};            // base colour
    float roughness = 0.5f;      // perceptual: alpha = roughness^2 (at least 0.001)
    float anisotropic = 0.0f;    // alpha_x / alpha_y = 1 / (1 - 0.9 anisotropic)
    float metallic = 0.0f;
    float eta = 1.5f;            // relative index of the dielectric, > 1
    float specularTint = 0.0f;   // tints the dielectric reflection towards the base hue
    float sheen = 0.0f;
    float sheenTint = 0.0f;
    float clearcoat = 0.0f;
    float clearcoatGloss = 0.0f;
    float transmission = 0.0f;   // Mitsuba's spec_trans
    float flatness = 0.0f;       // blends the diffuse towards fake subsurface scattering
    // A thin sheet (Mitsuba's principledthin): no refraction, transmission
    // straight through; diffuseTransmission in [0, 2] (Mitsuba's diff_trans)
    // splits the diffuse lobe between reflection and Lambertian transmission.
    bool thin = false;
    float diffuseTransmission = 0.0f;
};

// Schlick's Fresnel with normal-incidence reflectance f0 at the microfacet
// cosine cosThetaM, as Mitsuba's principled models take it: through the
// incident angle when eta > 1, through the refracted angle inside a denser
// medium (eta < 1, where Schlick's curve is the transmitted side's).
Color principledSchlick(const Color& f0, float cosThetaM, float eta);

// The clearcoat's GTR1 distribution (Burley 2012, "generalized
// Trowbridge-Reitz" with gamma = 1): D(m) = (a^2 - 1) / (pi ln(a^2) (1 +
// (a^2 - 1) cos^2 theta_m)), normalised so that its integral of D cos = 1,
// and its sampling with that density.
float gtr1D(float cosThetaM, float alpha);
Vec3 sampleGtr1(float alpha, const Vec2& u);

struct PrincipledLobes {
    explicit PrincipledLobes(const PrincipledParameters& p);

    PrincipledParameters p;
    MicrofacetDistribution specular;      // GGX, separable masking (Mitsuba's)
    MicrofacetDistribution thinTransmission;  // thin: roughness scaled by (0.65 eta - 0.35)
    Color cTint{1.0f};        // base / luminance(base): the hue
    Color sheenColor{1.0f};   // lerp(1, cTint, sheenTint)
    float brdfWeight = 0.0f;  // (1 - metallic) (1 - transmission): diffuse
    float btdfWeight = 0.0f;  // (1 - metallic) transmission: refraction
    float clearcoatAlpha = 0.1f;  // lerp(0.1, 0.001, clearcoatGloss)
    float diffuseTransmission = 0.0f;  // thin: the parameter / 2, in [0, 1]
};

}  // namespace strahl
