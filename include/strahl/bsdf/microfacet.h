#pragma once
// Anisotropic microfacet distributions: GGX / Trowbridge-Reitz (Walter et al.
// 2007; Heitz 2014) and Beckmann, with the Smith masking-shadowing term either
// height-correlated (strahl's default, pbrt-v4's) or separable (Mitsuba's).
// GGX samples the normals visible from the viewer (Heitz 2018); Beckmann
// samples D(m) cos(theta_m). Directions are in the local frame; microfacet
// normals m always lie in the upper hemisphere. Derivations in
// docs/materials.md, "Microfacet distributions".

#include <cstdint>

#include "strahl/core/math.h"

namespace strahl {

enum class MicrofacetType : std::uint8_t { Ggx, Beckmann };
enum class MicrofacetMasking : std::uint8_t { HeightCorrelated, Separable };

// Which distribution and which masking-shadowing term a rough surface uses.
struct MicrofacetModel {
    MicrofacetType type = MicrofacetType::Ggx;
    MicrofacetMasking masking = MicrofacetMasking::HeightCorrelated;
};

class MicrofacetDistribution {
public:
    // Below this alpha (both axes) the surface is treated as perfectly smooth:
    // D then peaks above 3e5 and single-precision half vectors cannot resolve
    // the lobe, while a delta lobe renders it exactly.
    static constexpr float kSmoothAlpha = 1e-3f;

    MicrofacetDistribution() = default;
    MicrofacetDistribution(float alphaX, float alphaY, MicrofacetModel model = {});

    float alphaX() const { return alphaX_; }
    float alphaY() const { return alphaY_; }
    MicrofacetModel model() const { return model_; }
    bool smooth() const { return smooth_; }

    // Normal distribution D(m), normalised so that integral D(m) cos(theta_m) dm = 1.
    float d(const Vec3& m) const;
    // Smith auxiliary function Lambda(w); infinite for grazing w.
    float lambda(const Vec3& w) const;
    // Masking G1(w) = 1 / (1 + Lambda(w)).
    float g1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
    // Masking-shadowing: height-correlated 1 / (1 + Lambda(wo) + Lambda(wi)),
    // or separable G1(wo) G1(wi).
    float g(const Vec3& wo, const Vec3& wi) const;
    // Density (over m) of the normals sampleNormal draws seen from w (w on
    // either side; it is flipped into the upper hemisphere). GGX: the visible
    // normals D_w(m) = G1(w) max(0, w.m) D(m) / |cos(theta_w)|; Beckmann:
    // D(m) cos(theta_m), whatever w. Either integrates to 1 over m.
    float normalPdf(const Vec3& w, const Vec3& m) const;
    // Draws m with density normalPdf(w, m). w must not be grazing (|w.z| > 0).
    // A Beckmann normal may face away from w; callers reject those.
    Vec3 sampleNormal(const Vec3& w, const Vec2& u) const;

private:
    float ggxD(const Vec3& m) const;
    float beckmannD(const Vec3& m) const;
    Vec3 sampleGgxVisibleNormal(const Vec3& w, const Vec2& u) const;
    Vec3 sampleBeckmannNormal(const Vec2& u) const;

    float alphaX_ = 0.0f, alphaY_ = 0.0f;
    MicrofacetModel model_;
    bool smooth_ = true;
};

}  // namespace strahl
