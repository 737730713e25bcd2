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

#include <optional>
#include <span>
#include <string_view>

#include "strahl/core/math.h"

namespace strahl {

struct BsdfSample {
    Color f{0.0f};
    Vec3 wi{0.0f};
    float pdf = 0.0f;  // solid-angle density, or the lobe probability for a specular sample
    bool specular = false;
    bool transmission = false;
    float eta = 1.0f;  // relative index of refraction crossed (1 for reflection)
};

// Complex index of refraction of a metal at the R, G, B wavelengths.
struct MetalPreset {
    std::string_view name;  // "gold", "silver", "copper", "aluminium", ...
    Color eta;
    Color k;
};
std::span<const MetalPreset> metalPresets();
std::optional<MetalPreset> findMetalPreset(std::string_view name);

class Bsdf {
public:
    enum class Kind { Black, Diffuse, Phong, BlinnPhong, Conductor, Dielectric, Plastic, MetallicRoughness };

    // Absorbs everything (purely emissive surfaces).
    static Bsdf black();
    // Lambert: f = R / pi.
    static Bsdf diffuse(const Color& reflectance);
    // Energy-conserving modified Phong (Lafortune & Willems 1994) and
    // normalised Blinn-Phong: kd / pi + ks-weighted normalised lobe; kd + ks <= 1
    // per channel keeps the albedo at or below 1.
    static Bsdf phong(const Color& kd, const Color& ks, float exponent);
    static Bsdf blinnPhong(const Color& kd, const Color& ks, float exponent);
    // GGX (Trowbridge-Reitz) microfacet conductor with complex Fresnel and
    // visible-normal sampling (Heitz 2018). alpha 0 (both) is a smooth mirror.
    static Bsdf conductor(const Color& eta, const Color& k, float alphaX, float alphaY);
    // Smooth (alpha 0) or rough (GGX, Walter et al. 2007) dielectric interface.
    // eta = n_inside / n_outside, inside being the -z side. `tint` multiplies
    // both reflection and transmission (1 for clear glass).
    static Bsdf dielectric(float eta, float alpha, const Color& tint = Color(1.0f));
    // Lambertian base under a smooth or rough dielectric coat (plastic); kd is
    // clamped to [0, 1] (the base-coat inter-reflection series needs kd < 1/F).
    static Bsdf plastic(const Color& kd, float eta, float alpha);
    // glTF 2.0 metallic-roughness: metallic blends a Schlick conductor with
    // F0 = base colour against a dielectric-coated diffuse with diffuse base
    // colour and Schlick F0 = ((eta - 1) / (eta + 1))^2. base, metallic and
    // alpha are clamped to [0, 1].
    static Bsdf metallicRoughness(const Color& base, float metallic, float alpha,
                                  float eta = 1.5f);

    Kind kind() const { return kind_; }
    Color f(const Vec3& wo, const Vec3& wi) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    // uLobe picks the lobe, u the direction within it; nullopt if no direction
    // was produced (absorbed, or below the surface for an opaque BSDF).
    std::optional<BsdfSample> sample(const Vec3& wo, float uLobe, const Vec2& u) const;
    // True if every lobe is a delta (light sampling cannot contribute).
    bool isSpecular() const;
    // True if it never transmits (the integrator may then flip the frame).
    bool isOpaque() const { return kind_ != Kind::Dielectric; }
    // A reflectance-like colour for the albedo AOV (denoisers).
    Color albedo() const;

    // Perceptual roughness r in [0, 1] to GGX alpha = r^2 (Burley 2012).
    static float roughnessToAlpha(float roughness) { return roughness * roughness; }

private:
    // Calls fn with the scattering model of this kind (bsdf_models.h); defined
    // and used in bsdf.cpp only.
    template <typename Fn>
    auto visit(Fn&& fn) const;

    Kind kind_ = Kind::Black;
    Color a_{0.0f}, b_{0.0f};  // kind-specific colours (see bsdf.cpp)
    Color c_{0.0f};            // albedo(), computed by the factory
    float alphaX_ = 0.0f, alphaY_ = 0.0f, eta_ = 1.0f, exponent_ = 0.0f, metallic_ = 0.0f;
    float internalReflectance_ = 0.0f;  // plastic: Fbar_dr inside the coat, cached per material
};

}  // namespace strahl
