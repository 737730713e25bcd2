#pragma once
// "diffuse": Lambert, f = R / pi (docs/materials.md).
//
//   key       value                               default
//   color     reflectance: colour or texture       0.8
//   diffuse   older name of color

#include <array>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct DiffuseMaterial {
    static constexpr std::string_view kName = "diffuse";
    static constexpr std::array<std::string_view, 2> kKeys = {"color", "diffuse"};

    TexturedColor color{Color(0.8f), {}};

    template <typename Reader>
    static DiffuseMaterial parse(const Reader& r) {
        DiffuseMaterial m;
        material_parsing::colorOrDiffuse(r, m.color);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const { return Bsdf::diffuse(p.reflectance(color)); }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        visitTextures(color, TextureEncoding::Color, fn);
    }
};

}  // namespace strahl
