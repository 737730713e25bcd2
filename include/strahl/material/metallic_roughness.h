#pragma once
// "metallic_roughness": the glTF 2.0 metallic-roughness model — metallic
// blends a Schlick GGX conductor with F0 = base colour against a
// dielectric-coated diffuse (docs/materials.md).
//
//   key         value                                                   default
//   color       base colour: colour or texture                           1
//   metallic    number in [0, 1] or texture (channel B by default)       1
//   roughness   perceptual roughness or texture (channel G by default)   1
//   ior         index of refraction of the dielectric part               1.5

#include <array>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct MetallicRoughnessMaterial {
    static constexpr std::string_view kName = "metallic_roughness";
    static constexpr std::array<std::string_view, 4> kKeys = {"color", "metallic", "roughness",
                                                              "ior"};

    TexturedColor color{Color(1.0f), {}};
    TexturedFloat metallic{1.0f, {}, 2};   // glTF: metallic in B
    TexturedFloat roughness{1.0f, {}, 1};  // glTF: roughness in G; glTF's default 1
    float ior = 1.5f;

    template <typename Reader>
    static MetallicRoughnessMaterial parse(const Reader& r) {
        MetallicRoughnessMaterial m;
        r.texturedColor("color", m.color);
        material_parsing::ior(r, m.ior);
        material_parsing::roughness(r, m.roughness);
        r.texturedFloat("metallic", 0.0f, 1.0f, m.metallic);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        return Bsdf::metallicRoughness(p.reflectance(color), p.unit(metallic), p.alpha(roughness),
                                       ior);
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        visitTextures(color, TextureEncoding::Color, fn);
        visitTextures(roughness, TextureEncoding::Data, fn);
        visitTextures(metallic, TextureEncoding::Data, fn);
    }
};

}  // namespace strahl
