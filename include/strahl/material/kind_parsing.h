#pragma once
// Parsing steps several material kinds share. Like the kinds' parse(), they
// are templates over the scene module's reader (scene/material_parser.cpp
// instantiates them), so the material headers need no JSON library. The
// reader offers has(key), find(key) (an optional JSON value with color(),
// numberIn(lo, hi), string(), oneOf({...}), fail(...)), texturedColor(key, out),
// texturedFloat(key, lo, hi, out) and fail(...).

#include <string>

#include "strahl/bsdf/bsdf.h"
#include "strahl/bsdf/microfacet.h"
#include "strahl/material/textured.h"

namespace strahl::material_parsing {

// "color", or "diffuse", its older name (diffuse, phong and blinn accept both).
template <typename Reader>
void colorOrDiffuse(const Reader& r, TexturedColor& color) {
    if (r.has("color") && r.has("diffuse")) r.fail("give either 'color' or 'diffuse', not both");
    r.texturedColor("color", color);
    r.texturedColor("diffuse", color);
}

// The index of refraction: below 1.0001 the interface vanishes; above 4 no
// common material.
template <typename Reader>
void ior(const Reader& r, float& ior) {
    if (auto value = r.find("ior")) ior = value->numberIn(1.0001f, 4.0f);
}

// Perceptual roughness in [0, 1] (alpha = r^2), constant or textured.
template <typename Reader>
void roughness(const Reader& r, TexturedFloat& roughness) {
    r.texturedFloat("roughness", 0.0f, 1.0f, roughness);
}

// A metal's complex index: "metal" (a preset name, metalPresets()) or "eta"
// and "k" (colours; either may be left at its default), not both.
template <typename Reader>
void metal(const Reader& r, Color& eta, Color& k) {
    const bool preset = r.has("metal");
    if (preset && (r.has("eta") || r.has("k"))) r.fail("give either 'metal' or 'eta' and 'k', not both");
    if (preset) {
        const auto metal = r.find("metal");
        const std::optional<MetalPreset> found = findMetalPreset(metal->string());
        if (!found) {
            std::string names;
            for (const MetalPreset& p : metalPresets()) names += (names.empty() ? "" : ", ") + std::string(p.name);
            metal->fail("unknown metal '", metal->string(), "' (known: ", names, ")");
        }
        eta = found->eta;
        k = found->k;
    } else {
        if (auto value = r.find("eta")) eta = value->color();
        if (auto value = r.find("k")) k = value->color();
    }
}

// "distribution": "ggx" (default) | "beckmann", and "masking":
// "height_correlated" (default) | "separable" (Mitsuba's G1(wo) G1(wi)).
template <typename Reader>
void microfacetModel(const Reader& r, MicrofacetModel& model) {
    if (auto value = r.find("distribution")) {
        model.type = value->oneOf({"ggx", "beckmann"}) == "ggx" ? MicrofacetType::Ggx
                                                                : MicrofacetType::Beckmann;
    }
    if (auto value = r.find("masking")) {
        model.masking = value->oneOf({"height_correlated", "separable"}) == "separable"
                            ? MicrofacetMasking::Separable
                            : MicrofacetMasking::HeightCorrelated;
    }
}

}  // namespace strahl::material_parsing
