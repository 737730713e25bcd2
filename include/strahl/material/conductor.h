#pragma once
// "conductor": a GGX microfacet metal with the exact complex Fresnel term
// (docs/materials.md); roughness 0 is a smooth mirror.
//
//   key         value                                              default
//   metal       a preset name (bsdf/metal_presets.cpp): "gold", ...  aluminium
//   eta, k      complex index of refraction per channel (not with metal)
//   roughness   perceptual roughness, alpha = r^2: number or texture  0

#include <array>
#include <string>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct ConductorMaterial {
    static constexpr std::string_view kName = "conductor";
    static constexpr std::array<std::string_view, 4> kKeys = {"metal", "eta", "k", "roughness"};

    // Without a preset or eta/k: a near-perfect aluminium mirror.
    Color eta = findMetalPreset("aluminium")->eta;
    Color k = findMetalPreset("aluminium")->k;
    TexturedFloat roughness{0.0f, {}, 1};

    template <typename Reader>
    static ConductorMaterial parse(const Reader& r) {
        ConductorMaterial m;
        const bool preset = r.has("metal");
        if (preset && (r.has("eta") || r.has("k")))
            r.fail("give either 'metal' or 'eta' and 'k', not both");
        if (preset) {
            const auto metal = r.find("metal");
            const std::optional<MetalPreset> found = findMetalPreset(metal->string());
            if (!found) {
                std::string names;
                for (const MetalPreset& p : metalPresets())
                    names += (names.empty() ? "" : ", ") + std::string(p.name);
                metal->fail("unknown metal '", metal->string(), "' (known: ", names, ")");
            }
            m.eta = found->eta;
            m.k = found->k;
        } else {
            if (auto eta = r.find("eta")) m.eta = eta->color();
            if (auto k = r.find("k")) m.k = k->color();
        }
        material_parsing::roughness(r, m.roughness);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        const float a = p.alpha(roughness);
        return Bsdf::conductor(eta, k, a, a);
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        fn(roughness.texture, TextureEncoding::Data);
    }
};

}  // namespace strahl
