#pragma once
// BSDFs of the physically based materials, evaluated and sampled in the local
// shading frame: the shading normal is +z, wo (towards the viewer) and wi
// (towards the light) are unit vectors pointing away from the surface.
//
// Conventions (pbrt-v4, radiance transport):
//  - f(wo, wi) excludes the cosine; the estimator weight is f |cos wi| / pdf.
//  - Opaque BSDFs (diffuse, Phong, conductor, plastic, metallic-roughness) are
//    two-sided: for wo.z < 0 they act on the lower hemisphere as a mirror image
//    of the upper one. The dielectric is not: wo.z < 0 means wo is inside.
//  - Transmission through a dielectric scales f by 1/eta^2 (radiance
//    compression), so a glass sphere in a white furnace stays white.
//  - Specular (delta) lobes: sample() returns f and pdf such that
//    f |cos wi| / pdf is the throughput weight, with pdf the discrete
//    probability of the lobe; f() and pdf() return 0 for them.
// Derivations and references: docs/materials.md.

#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/principled.h"
#include "strahl/core/math.h"

namespace strahl {

// Complex index of refraction of a metal at the R, G, B wavelengths.
struct MetalPreset {
    std::string_view name;  // "gold", "silver", "copper", "aluminium", ...
    Color eta;
    Color k;
};
std::span<const MetalPreset> metalPresets();
std::optional<MetalPreset> findMetalPreset(std::string_view name);

// One scattering model (bsdf_models.h) with validated parameters, made by the
// factories below, or a weighted sum of them (blend()).
class Bsdf {
public:
    Bsdf() = default;  // black()
    // Absorbs everything (purely emissive surfaces).
    static Bsdf black();
    // Lambert: f = R / pi.
    static Bsdf diffuse(const Color& reflectance);
    // Lambertian reflection R / pi and transmission T / pi (a thin leaf);
    // R + T <= 1 per channel conserves energy.
    static Bsdf diffuseTransmission(const Color& reflectance, const Color& transmittance);
    // Energy-conserving modified Phong (Lafortune & Willems 1994) and
    // normalised Blinn-Phong: kd / pi + ks-weighted normalised lobe; kd + ks <= 1
    // per channel keeps the albedo at or below 1.
    static Bsdf phong(const Color& kd, const Color& ks, float exponent);
    static Bsdf blinnPhong(const Color& kd, const Color& ks, float exponent);
    // Microfacet conductor (GGX by default, or Beckmann; microfacet.h) with
    // complex Fresnel. alpha 0 (both) is a smooth mirror.
    static Bsdf conductor(const Color& eta, const Color& k, float alphaX, float alphaY,
                          MicrofacetModel microfacets = {});
    // Smooth (alpha 0) or rough (Walter et al. 2007) dielectric interface.
    // eta = n_inside / n_outside, inside being the -z side. `tint` multiplies
    // both reflection and transmission (1 for clear glass).
    static Bsdf dielectric(float eta, float alpha, const Color& tint = Color(1.0f),
                           MicrofacetModel microfacets = {});
    // A thin sheet of dielectric of index eta: light reflects with the sheet's
    // summed reflectance or passes straight through (bsdf_models.h).
    static Bsdf thinDielectric(float eta, const Color& tint = Color(1.0f));
    // Lambertian base under a smooth or rough dielectric coat (plastic); kd is
    // clamped to [0, 1] (the base-coat inter-reflection series needs kd < 1/F).
    // A rough coat lets through what `coat.rough` tabulates (made for the same
    // eta and microfacet model); without tables, 1 - F of the smooth coat.
    struct PlasticCoat {
        MicrofacetModel microfacets;
        bool nonlinear = true;  // kd inside the inter-reflection series (Mitsuba's "nonlinear")
        const RoughCoat* rough = nullptr;
    };
    static Bsdf plastic(const Color& kd, float eta, float alpha, const PlasticCoat& coat);
    static Bsdf plastic(const Color& kd, float eta, float alpha) {
        return plastic(kd, eta, alpha, PlasticCoat{});
    }
    // A conductor under a dielectric coat (coated_base.h: the metal, the
    // coat's index, the layer between them, computed once per material; it
    // must outlive the Bsdf) with GGX alphas for the metal and the coat, 0
    // smooth. bsdf_models.h, CoatedConductorModel.
    static Bsdf coatedConductor(const CoatedBase& layers, float metalAlpha, float coatAlpha);
    // glTF 2.0 metallic-roughness: metallic blends a Schlick conductor with
    // F0 = base colour against a dielectric-coated diffuse with diffuse base
    // colour and Schlick F0 = ((eta - 1) / (eta + 1))^2. base, metallic and
    // alpha are clamped to [0, 1].
    static Bsdf metallicRoughness(const Color& base, float metallic, float alpha,
                                  float eta = 1.5f);
    // Burley's principled BSDF as Mitsuba 3 defines it (principled.h);
    // parameters are clamped to their ranges, NaN is refused.
    static Bsdf principled(const PrincipledParameters& parameters);
    // A hair fibre (bsdf_models.h, HairModel): absorption sigma_a per unit
    // of the fibre's radius, longitudinal and azimuthal roughness beta_m and beta_n
    // in [0, 1], the scales' tilt alpha in degrees and the index eta. The
    // entry offset h follows from wo (h outside [−1, 1]) or is fixed.
    static Bsdf hair(const Color& sigmaA, float betaM, float betaN, float alphaDegrees, float eta = 1.55f,
                     float h = 2.0f);
    // The absorption that gives a fibre (with beta_n) the colour c in a
    // white furnace of many scattering events (Chiang et al. 2016, eq. 9),
    // and its inverse, used as the hair's albedo.
    static Color hairSigmaAFromColor(const Color& c, float betaN);
    static Color hairColorFromSigmaA(const Color& sigmaA, float betaN);
    // (1 - weight) a + weight b (Mitsuba's blendbsdf, pbrt's mix): f and pdf
    // are the weighted sums, a sample picks a or b with probability 1 - weight
    // or weight. weight is clamped to [0, 1]; at 0 or 1 the result is a or b.
    // A blend of blends is one flat sum.
    static Bsdf blend(const Bsdf& a, const Bsdf& b, float weight);

    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    // uLobe picks the lobe, u the direction within it; nullopt if no direction
    // was produced (absorbed, or below the surface for an opaque BSDF).
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
    // True if every lobe is a delta (light sampling cannot contribute).
    bool isSpecular() const;
    // True if it never transmits (the integrator may then flip the frame).
    bool isOpaque() const;
    // True for a hair fibre: a far-field model of light that enters and
    // leaves a fibre anywhere around it, so rays leave a round curve from
    // the side facing their direction (ShadingContext::spawn).
    bool isFibre() const;
    // A reflectance-like colour for the albedo AOV (denoisers).
    Color albedo() const;
    // This BSDF with every glossy or specular lobe at least `alpha` rough
    // (Cycles' "filter glossy", which the path tracer applies after rough
    // bounces; biased): microfacet lobes (conductor, dielectric, plastic
    // without a rough coat's tables, both layers of the coated conductor,
    // metallic-roughness) get alpha =
    // max(alpha, own), Phong and Blinn the exponent 2 / alpha^2 - 2 of that
    // width if it is smaller. Lambert, the thin dielectric and the principled
    // BSDF stay as they are. alpha <= 0: unchanged.
    Bsdf roughened(float alpha) const;

    // Perceptual roughness r in [0, 1] to GGX alpha = r^2 (Burley 2012).
    static float roughnessToAlpha(float roughness) { return roughness * roughness; }

private:
    struct WeightedModel {
        BsdfModel model;
        float weight;
    };
    using Sum = std::vector<WeightedModel>;

    Bsdf(BsdfModel model, const Color& albedo) : model_(std::move(model)), albedo_(albedo) {}
    // The models of this BSDF with their weights (one of weight 1 unless blended).
    Sum terms() const;

    // One model, built at every path vertex and so kept small; a blend (rare)
    // holds its weighted models on the heap instead, shared by copies.
    BsdfModel model_;
    std::shared_ptr<const Sum> sum_;  // non-null: a blend, and model_ unused
    Color albedo_{0.0f};  // albedo(), computed by the factory
};

}  // namespace strahl
