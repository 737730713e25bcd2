#pragma once
// "plastic": a Lambertian base under a smooth or rough dielectric coat
// (docs/materials.md).
//
//   key           value                                   default
//   color         base colour: colour or texture           0.8
//   ior           index of refraction of the coat           1.5
//   roughness     perceptual roughness of the coat          0
//   distribution, masking: the coat's microfacet model, as for "conductor"
//   nonlinear     the base colour enters the series of      true
//                 base-coat inter-reflections (false:
//                 Mitsuba's default, linear in the colour)
//   coat_transmittance  "fresnel": a rough coat lets through   "fresnel"
//                 1 - F of the mean surface (nearly energy
//                 conserving); "microfacet": what the rough
//                 interface transmits in single scattering,
//                 tabulated (Mitsuba's roughplastic)

#include <array>
#include <memory>
#include <string_view>
#include <vector>

#include "strahl/bsdf/bsdf.h"
#include "strahl/bsdf/rough_coat.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct PlasticMaterial {
    static constexpr std::string_view kName = "plastic";
    static constexpr std::array<std::string_view, 7> kKeys = {
        "color",   "ior",      "roughness",         "distribution",
        "masking", "nonlinear", "coat_transmittance"};

    TexturedColor color{Color(0.8f), {}};
    float ior = 1.5f;
    TexturedFloat roughness{0.0f, {}, 1};
    MicrofacetModel microfacets;
    bool nonlinear = true;
    bool microfacetCoat = false;  // coat_transmittance "microfacet"
    // A rough microfacet coat's tables (shared by the copies of the material).
    std::shared_ptr<const RoughCoat> roughCoat;

    template <typename Reader>
    static PlasticMaterial parse(const Reader& r) {
        PlasticMaterial m;
        r.texturedColor("color", m.color);
        material_parsing::ior(r, m.ior);
        material_parsing::roughness(r, m.roughness);
        material_parsing::microfacetModel(r, m.microfacets);
        if (auto value = r.find("nonlinear")) m.nonlinear = value->boolean();
        if (auto value = r.find("coat_transmittance"))
            m.microfacetCoat = value->oneOf({"fresnel", "microfacet"}) == "microfacet";
        m.tabulateRoughCoat();
        return m;
    }
    // Builds roughCoat for a microfacet coat of the current roughness, ior and
    // microfacet model: exact at a constant roughness; for a textured one, at
    // perceptual roughness 0, 1/8, ..., 1 (interpolated between).
    void tabulateRoughCoat() {
        roughCoat = nullptr;
        if (!microfacetCoat) return;  // the fresnel coat needs no tables
        std::vector<float> alphas;
        if (!roughness.varies()) {
            const float alpha = Bsdf::roughnessToAlpha(roughness.value);
            if (alpha >= MicrofacetDistribution::kSmoothAlpha) alphas.push_back(alpha);
        } else {
            for (int i = 0; i <= 8; ++i) alphas.push_back(Bsdf::roughnessToAlpha(float(i) / 8.0f));
        }
        if (!alphas.empty()) roughCoat = std::make_shared<const RoughCoat>(microfacets, ior, alphas);
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        return Bsdf::plastic(p.reflectance(color), ior, p.alpha(roughness),
                             Bsdf::PlasticCoat{microfacets, nonlinear, roughCoat.get()});
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        visitTextures(color, TextureEncoding::Color, fn);
        visitTextures(roughness, TextureEncoding::Data, fn);
    }
};

}  // namespace strahl
