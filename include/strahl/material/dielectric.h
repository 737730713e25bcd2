#pragma once
// "dielectric": glass, a smooth (roughness 0) or rough (GGX, Walter et al.
// 2007) dielectric interface (docs/materials.md).
//
//   key         value                                           default
//   color       tint of reflection and transmission              1
//   ior         index of refraction inside, in [1.0001, 4]       1.5
//   roughness   perceptual roughness: number or texture          0
//   distribution, masking: the microfacet model, as for "conductor"

#include <array>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct DielectricMaterial {
    static constexpr std::string_view kName = "dielectric";
    static constexpr std::array<std::string_view, 5> kKeys = {"color", "ior", "roughness",
                                                              "distribution", "masking"};

    TexturedColor tint{Color(1.0f), {}};
    float ior = 1.5f;
    TexturedFloat roughness{0.0f, {}, 1};
    MicrofacetModel microfacets;

    template <typename Reader>
    static DielectricMaterial parse(const Reader& r) {
        DielectricMaterial m;
        r.texturedColor("color", m.tint);
        material_parsing::ior(r, m.ior);
        material_parsing::roughness(r, m.roughness);
        material_parsing::microfacetModel(r, m.microfacets);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        return Bsdf::dielectric(ior, p.alpha(roughness), p.reflectance(tint), microfacets);
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        visitTextures(tint, TextureEncoding::Color, fn);
        visitTextures(roughness, TextureEncoding::Data, fn);
    }
};

}  // namespace strahl
