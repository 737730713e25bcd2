#pragma once
// The scattering models behind strahl::Bsdf, a closed family: one struct per
// model, each with f / pdf / sample in the local frame, specular() (every lobe
// a delta: light sampling cannot contribute) and kOpaque. Bsdf holds one of
// them in a std::variant (BsdfModel below) built by its factories, which
// validate the parameters; use the models directly only in tests.
//
// Opaque models (kOpaque, or opaque() where it varies with the parameters)
// see wo in the upper hemisphere only (Bsdf mirrors the lower one onto it) and
// return 0 / nullopt for wi below; the others see both sides as they are.
// Derivations and references: docs/materials.md.

#include <memory>
#include <optional>
#include <variant>

#include "strahl/bsdf/bsdf_sample.h"
#include "strahl/bsdf/coated_base.h"
#include "strahl/bsdf/microfacet.h"
#include "strahl/bsdf/rough_coat.h"

namespace strahl {
struct PrincipledLobes;  // principled.h
}  // namespace strahl

namespace strahl::bsdf_models {

// Absorbs everything (purely emissive surfaces): no lobe at all, so nothing
// for light sampling either.
struct BlackModel {
    static constexpr bool kOpaque = true;
    bool specular() const { return true; }
    Color f(const Vec3&, const Vec3&) const { return Color(0.0f); }
    float pdf(const Vec3&, const Vec3&) const { return 0.0f; }
    std::optional<BsdfSample> sample(const Vec3&, float, const Vec2&) const { return std::nullopt; }
};

// Lambert: f = R / pi, cosine-weighted sampling.
struct LambertModel {
    Color reflectance;

    static constexpr bool kOpaque = true;
    bool specular() const { return false; }
    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
};

// Lambertian reflection and transmission (pbrt's diffusetransmission, the
// thin leaves of foliage): f = R / pi with wo and wi on one side, T / pi on
// opposite sides. Sampling picks the side by the means of R and T, then
// a cosine-weighted direction there. Reciprocal; albedo R + T.
struct DiffuseTransmissionModel {
    Color reflectance, transmittance;

    static constexpr bool kOpaque = false;
    bool specular() const { return false; }
    float reflectProbability() const;
    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
};

// kd / pi plus a normalised cos^n lobe: around the mirror direction (modified
// Phong) or of the half vector (Blinn-Phong, Ashikhmin-Shirley normalisation).
struct PhongModel {
    Color kd, ks;
    float exponent = 1.0f;
    bool blinn = false;

    static constexpr bool kOpaque = true;
    bool specular() const { return false; }
    // Probability of sampling the specular lobe: mean(ks) / (mean(kd) + mean(ks)).
    float specularProbability() const;
    Color specularF(const Vec3& wo, const Vec3& wi) const;
    float specularPdf(const Vec3& wo, const Vec3& wi) const;
    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
};

// Microfacet conductor with exact complex Fresnel; a delta mirror when smooth.
struct ConductorModel {
    MicrofacetDistribution microfacets;
    Color eta, k;

    static constexpr bool kOpaque = true;
    bool specular() const { return microfacets.smooth(); }
    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
};

// Smooth or rough (Walter et al. 2007) dielectric interface, radiance transport.
struct DielectricModel {
    MicrofacetDistribution microfacets;
    float eta = 1.5f;  // n_inside / n_outside, inside = -z
    Color tint{1.0f};

    static constexpr bool kOpaque = false;
    bool smooth() const { return microfacets.smooth() || eta == 1.0f; }
    bool specular() const { return smooth(); }
    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
};

// A thin sheet of dielectric: delta reflection with the sheet's summed
// reflectance R' = 2R / (1 + R), delta transmission straight through (wi = -wo)
// with 1 - R'; both tinted. No radiance scaling: the light leaves in the
// medium it came from.
struct ThinDielectricModel {
    float eta = 1.5f;
    Color tint{1.0f};

    static constexpr bool kOpaque = false;
    bool specular() const { return true; }
    float reflectance(float cosTheta) const;
    Color f(const Vec3&, const Vec3&) const { return Color(0.0f); }
    float pdf(const Vec3&, const Vec3&) const { return 0.0f; }
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
};

// Lambertian base under a smooth (delta) or rough (microfacet) dielectric coat.
struct PlasticModel {
    MicrofacetDistribution microfacets;
    Color kd;
    float eta = 1.5f;
    float internalReflectance = 0.0f;  // what the coat reflects back down from inside
    bool nonlinear = true;             // the base's colour in the inter-reflection series
    const RoughCoat* roughCoat = nullptr;  // tables of a rough coat (else 1 - F)

    static constexpr bool kOpaque = true;
    // A black base leaves only the coat's delta lobe when it is smooth.
    bool specular() const { return microfacets.smooth() && maxComponent(kd) == 0.0f; }
    // The fraction of light at cos(theta) from outside that passes the coat.
    float coatTransmittance(float cosTheta) const;
    float specularProbability(float coatTransmittanceO) const;
    // 1 - kd Fbar_int (or 1 - Fbar_int, linear): what the base-coat
    // inter-reflection series divides by.
    Color interreflection() const {
        return Color(1.0f) - (nonlinear ? kd * internalReflectance : Color(internalReflectance));
    }
    Color diffuseF(const Vec3& wo, const Vec3& wi) const;
    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
};

// A conductor under a smooth or rough dielectric coat of index eta, with an
// optional absorbing layer between them (pbrt-v4's coatedconductor; car
// paint, lacquered brass). Three lobes: the coat's reflection; the metal seen
// through the coat's mean surface, both directions refracted into the coat
// (wo', wi'), f = T(wo) T(wi) a(wo') a(wi') f_metal(wo', wi') / eta^2 with
// T = 1 - F and a the layer's attenuation; and the light that stays in the
// coat after that bounce and leaves later, f = E A(wo) A(wi) / N with
// A(w) = T(w) trapped(w) a(w') (coated_base.h). A smooth metal is a delta
// mirror whose round trips between metal and coat are summed exactly.
// Derivation: docs/materials.md, "Coated conductor".
struct CoatedConductorModel {
    MicrofacetDistribution coat, metal;
    const CoatedBase* layers = nullptr;  // never null

    static constexpr bool kOpaque = true;
    bool specular() const { return coat.smooth() && metal.smooth(); }
    // w (outside, upper hemisphere) refracted into the coat, as the upward
    // direction it has there: same azimuth, sin theta' = sin theta / eta.
    Vec3 inside(const Vec3& w) const;
    float coatTransmittance(float cosTheta) const;
    // The weight of the smooth metal's delta mirror along reflectZ(wo): every
    // path through the coat, the metal, and back and forth between them.
    Color mirrorThroughCoat(const Vec3& wo) const;
    // The trapped light's lobe shape A(w) (0 for a smooth metal).
    float trappedLobe(const Vec3& w) const;
    struct LobeProbabilities {
        float coat, direct;  // the trapped lobe has the rest
    };
    LobeProbabilities lobeProbabilities(const Vec3& wo) const;
    Color directF(const Vec3& wo, const Vec3& wi) const;
    Color trappedF(const Vec3& wo, const Vec3& wi) const;
    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
};

// glTF 2.0 metallic-roughness: Schlick GGX specular with F0 = lerp(f0Dielectric,
// base, metallic), plus (1 - metallic) base-coloured diffuse coupled to the
// dielectric specular's albedo (Kelemen & Szirmay-Kalos 2001).
struct MetallicRoughnessModel {
    MicrofacetDistribution ggx;
    Color base;
    float metallic = 0.0f;
    float f0Dielectric = 0.04f;

    static constexpr bool kOpaque = true;
    // Smooth and without a diffuse part (all metal, or a black base).
    bool specular() const {
        return ggx.smooth() && (metallic >= 1.0f || maxComponent(base) == 0.0f);
    }
    Color specularFresnel(float cosThetaH) const;
    float specularProbability(const Vec3& wo) const;
    Color diffuseF(const Vec3& wo, const Vec3& wi) const;
    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
};

// Burley's principled BSDF as Mitsuba 3 defines it ("principled" and
// "principledthin"; docs/materials.md, "Principled"): a GGX specular lobe
// whose Fresnel term blends the dielectric, a metal of the base colour and a
// tinted dielectric, a rough transmission through it (or, thin, a straight
// rough transmission), a GTR1 clearcoat, Burley's diffuse with retro-
// reflection, flatness and sheen, and (thin) a Lambertian transmission.
struct PrincipledModel {
    // On the heap: the model has about twenty parameters, and every other
    // BSDF (kept in the same variant, built at each path vertex) would pay
    // for their size.
    std::shared_ptr<const PrincipledLobes> lobes;

    // A solid principled material that transmits nothing is opaque (two-sided
    // as strahl's opaque models are); with transmission, or thin, the model
    // sees both sides: the back of a solid one only reflects and refracts
    // through its specular lobe, a thin one is the same from either side.
    bool opaque() const;
    bool specular() const { return false; }
    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
};

// A hair fibre (Chiang et al. 2016, "A Practical and Controllable Hair and
// Fur Model for Production Path Tracing", with d'Eon et al. 2011's
// longitudinal term), in a frame whose x axis is the fibre and z the
// shading normal. Light reflects off the cuticle (p = 0, R), passes through
// (p = 1, TT), reflects once inside (p = 2, TRT) or more (p = 3, the rest,
// spread evenly in azimuth); each path p has a longitudinal lobe M_p (a
// von Mises–Fisher-like function of the inclinations, variance from beta_m,
// shifted by the scales' tilt alpha), an attenuation A_p (Fresnel at the
// entry offset h and the absorption sigma_a along the refracted path) and an
// azimuthal lobe N_p (a trimmed logistic of width beta_n around the
// deflection Φ(p, h) = 2p γt − 2γo + pπ). f = Σ M_p A_p N_p / |cos θ_i|
// (the cosine to the shading normal, which the integrator multiplies back).
// h, the offset across the fibre where the light enters, is h = −ŵ_y for the
// unit projection ŵ of wo onto the normal plane (docs/materials.md, "Hair"),
// unless fixed (tests). Energy conserving (a white furnace with sigma_a = 0
// returns 1); like every implementation of this model not reciprocal, as
// the attenuation depends on the entry angle.
struct HairModel {
    Color sigmaA{0.0f};  // absorption per unit of the fibre's radius (a ray through the axis crosses 2)
    float eta = 1.55f;
    float hFixed = 2.0f;  // outside [−1, 1]: h from wo
    // Precomputed from beta_m, beta_n, alpha by Bsdf::hair.
    float v[4]{};             // longitudinal variances of p = 0, 1, 2, 3
    float s = 0.0f;           // logistic scale
    float sin2kAlpha[3]{}, cos2kAlpha[3]{};  // the scale tilt alpha, 2 alpha, 4 alpha

    static constexpr bool kOpaque = false;
    bool specular() const { return false; }
    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
};

}  // namespace strahl::bsdf_models

namespace strahl {

// The closed set of scattering models a Bsdf can be.
using BsdfModel =
    std::variant<bsdf_models::BlackModel, bsdf_models::LambertModel, bsdf_models::DiffuseTransmissionModel,
                 bsdf_models::PhongModel,
                 bsdf_models::ConductorModel, bsdf_models::DielectricModel,
                 bsdf_models::ThinDielectricModel, bsdf_models::PlasticModel, bsdf_models::CoatedConductorModel,
                 bsdf_models::MetallicRoughnessModel, bsdf_models::PrincipledModel, bsdf_models::HairModel>;

}  // namespace strahl
