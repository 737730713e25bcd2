#pragma once
// "conductor": a microfacet metal with the exact complex Fresnel term
// (docs/materials.md); roughness 0 is a smooth mirror.
//
//   key           value                                              default
//   metal         a preset name (bsdf/metal_presets.cpp): "gold", ...  aluminium
//   eta, k        complex index of refraction per channel (not with metal)
//   roughness     perceptual roughness, alpha = r^2: number or texture  0
//   roughness_u,  anisotropic roughness along the surface's dp/du and
//   roughness_v   across it (instead of roughness)
//   distribution  "ggx" | "beckmann"                                 ggx
//   masking       "height_correlated" | "separable"                  height_correlated

#include <array>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct ConductorMaterial {
    static constexpr std::string_view kName = "conductor";
    static constexpr std::array<std::string_view, 8> kKeys = {
        "metal",       "eta",          "k",           "roughness",
        "roughness_u", "roughness_v", "distribution", "masking"};

    // Without a preset or eta/k: a near-perfect aluminium mirror.
    Color eta = findMetalPreset("aluminium")->eta;
    Color k = findMetalPreset("aluminium")->k;
    TexturedFloat roughnessU{0.0f, {}, 1};
    TexturedFloat roughnessV{0.0f, {}, 1};
    bool anisotropic = false;  // roughness_u and roughness_v given (else V is U)
    MicrofacetModel microfacets;

    template <typename Reader>
    static ConductorMaterial parse(const Reader& r) {
        ConductorMaterial m;
        material_parsing::metal(r, m.eta, m.k);
        if (r.has("roughness") && (r.has("roughness_u") || r.has("roughness_v")))
            r.fail("give either 'roughness' or 'roughness_u' and 'roughness_v', not both");
        if (r.has("roughness_u") != r.has("roughness_v"))
            r.fail("'roughness_u' and 'roughness_v' go together");
        material_parsing::roughness(r, m.roughnessU);
        m.roughnessV = m.roughnessU;
        m.anisotropic = r.has("roughness_u");
        r.texturedFloat("roughness_u", 0.0f, 1.0f, m.roughnessU);
        r.texturedFloat("roughness_v", 0.0f, 1.0f, m.roughnessV);
        material_parsing::microfacetModel(r, m.microfacets);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        // An isotropic roughness is looked up once.
        const float alphaU = p.alpha(roughnessU);
        return Bsdf::conductor(eta, k, alphaU, anisotropic ? p.alpha(roughnessV) : alphaU,
                               microfacets);
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        visitTextures(roughnessU, TextureEncoding::Data, fn);
        visitTextures(roughnessV, TextureEncoding::Data, fn);
    }
};

}  // namespace strahl
