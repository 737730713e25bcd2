#pragma once
// "plastic": a Lambertian base under a smooth or rough dielectric coat
// (docs/materials.md).
//
//   key         value                                   default
//   color       base colour: colour or texture           0.8
//   ior         index of refraction of the coat           1.5
//   roughness   perceptual roughness of the coat          0

#include <array>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct PlasticMaterial {
    static constexpr std::string_view kName = "plastic";
    static constexpr std::array<std::string_view, 3> kKeys = {"color", "ior", "roughness"};

    TexturedColor color{Color(0.8f), {}};
    float ior = 1.5f;
    TexturedFloat roughness{0.0f, {}, 1};

    template <typename Reader>
    static PlasticMaterial parse(const Reader& r) {
        PlasticMaterial m;
        r.texturedColor("color", m.color);
        material_parsing::ior(r, m.ior);
        material_parsing::roughness(r, m.roughness);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        return Bsdf::plastic(p.reflectance(color), ior, p.alpha(roughness));
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        fn(color.texture, TextureEncoding::Color);
        fn(roughness.texture, TextureEncoding::Data);
    }
};

}  // namespace strahl
