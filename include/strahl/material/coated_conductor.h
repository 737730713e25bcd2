#pragma once
// "coated_conductor": a metal under a clear dielectric coat, with an optional
// absorbing layer between them: lacquered brass, car paint's clear coat over
// metal flakes (pbrt-v4's coatedconductor). docs/materials.md, "Coated
// conductor".
//
//   key             value                                          default
//   metal           the base metal, a preset name (as "conductor")  aluminium
//   eta, k          its complex index in vacuum (not with metal)
//   roughness       the base's perceptual roughness: number or texture  0
//   ior             index of refraction of the coat                 1.5
//   coat_roughness  the coat's perceptual roughness: number or texture  0
//   thickness       optical thickness of the layer under the coat    0
//                   (unit extinction: exp(-thickness / cos) per crossing)
//   distribution, masking: both layers' microfacet model, as for "conductor"

#include <array>
#include <memory>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/bsdf/coated_base.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct CoatedConductorMaterial {
    static constexpr std::string_view kName = "coated_conductor";
    static constexpr std::array<std::string_view, 9> kKeys = {
        "metal", "eta", "k", "roughness", "ior", "coat_roughness", "thickness", "distribution", "masking"};

    Color eta = findMetalPreset("aluminium")->eta;
    Color k = findMetalPreset("aluminium")->k;
    TexturedFloat roughness{0.0f, {}, 1};
    float ior = 1.5f;
    TexturedFloat coatRoughness{0.0f, {}, 1};
    float thickness = 0.0f;
    MicrofacetModel microfacets;
    // What the BSDF needs once per material (shared by the copies).
    std::shared_ptr<const CoatedBase> layers = makeLayers();

    std::shared_ptr<const CoatedBase> makeLayers() const {
        return std::make_shared<const CoatedBase>(CoatedLayers{eta, k, ior, thickness, microfacets});
    }

    template <typename Reader>
    static CoatedConductorMaterial parse(const Reader& r) {
        CoatedConductorMaterial m;
        material_parsing::metal(r, m.eta, m.k);
        material_parsing::roughness(r, m.roughness);
        material_parsing::ior(r, m.ior);
        r.texturedFloat("coat_roughness", 0.0f, 1.0f, m.coatRoughness);
        // Beyond 100 the layer lets through less than e^-100: black.
        if (auto value = r.find("thickness")) m.thickness = value->numberIn(0.0f, 100.0f);
        material_parsing::microfacetModel(r, m.microfacets);
        m.layers = m.makeLayers();
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        return Bsdf::coatedConductor(*layers, p.alpha(roughness), p.alpha(coatRoughness));
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        visitTextures(roughness, TextureEncoding::Data, fn);
        visitTextures(coatRoughness, TextureEncoding::Data, fn);
    }
};

}  // namespace strahl
