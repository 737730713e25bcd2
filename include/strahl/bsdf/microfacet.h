#pragma once
// The anisotropic GGX / Trowbridge-Reitz microfacet distribution (Walter et al.
// 2007; Heitz 2014) with the height-correlated Smith masking-shadowing term and
// visible-normal sampling (Heitz 2018). Directions are in the local frame;
// microfacet normals m always lie in the upper hemisphere. Derivations in
// docs/materials.md, "GGX microfacet distribution".

#include "strahl/core/math.h"

namespace strahl {

class GgxDistribution {
public:
    // Below this alpha (both axes) the surface is treated as perfectly smooth:
    // D then peaks above 3e5 and single-precision half vectors cannot resolve
    // the lobe, while a delta lobe renders it exactly.
    static constexpr float kSmoothAlpha = 1e-3f;

    GgxDistribution() = default;
    GgxDistribution(float alphaX, float alphaY);

    float alphaX() const { return alphaX_; }
    float alphaY() const { return alphaY_; }
    bool smooth() const { return smooth_; }

    // Normal distribution D(m), normalised so that integral D(m) cos(theta_m) dm = 1.
    float d(const Vec3& m) const;
    // Smith auxiliary function Lambda(w); infinite for grazing w.
    float lambda(const Vec3& w) const;
    // Masking G1(w) = 1 / (1 + Lambda(w)).
    float g1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
    // Height-correlated masking-shadowing G2 = 1 / (1 + Lambda(wo) + Lambda(wi)).
    float g(const Vec3& wo, const Vec3& wi) const {
        return 1.0f / (1.0f + lambda(wo) + lambda(wi));
    }
    // Distribution of normals visible from w (w on either side; the visible
    // side is the one facing w flipped into the upper hemisphere):
    // D_w(m) = G1(w) max(0, w.m) D(m) / |cos(theta_w)|; integrates to 1 over m.
    float visibleD(const Vec3& w, const Vec3& m) const;
    // Samples m from D_w (Heitz 2018, with the concentric disk map); the density
    // is visibleD(w, m). w must not be grazing (|w.z| > 0).
    Vec3 sampleVisibleNormal(const Vec3& w, const Vec2& u) const;

private:
    float alphaX_ = 0.0f, alphaY_ = 0.0f;
    bool smooth_ = true;
};

}  // namespace strahl
