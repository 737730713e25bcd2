#pragma once
// "thin_dielectric": a thin sheet of glass (a window pane), both faces smooth
// and parallel, so light passes straight through undeviated; the reflections
// inside the sheet are summed (docs/materials.md, "Thin dielectric").
//
//   key         value                                           default
//   ior         index of refraction of the sheet, (1, 4]         1.5
//   color       tint of reflection and transmission               1

#include <array>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct ThinDielectricMaterial {
    static constexpr std::string_view kName = "thin_dielectric";
    static constexpr std::array<std::string_view, 2> kKeys = {"ior", "color"};

    float ior = 1.5f;
    TexturedColor tint{Color(1.0f), {}};

    template <typename Reader>
    static ThinDielectricMaterial parse(const Reader& r) {
        ThinDielectricMaterial m;
        material_parsing::ior(r, m.ior);
        r.texturedColor("color", m.tint);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        return Bsdf::thinDielectric(ior, p.reflectance(tint));
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        visitTextures(tint, TextureEncoding::Color, fn);
    }
};

}  // namespace strahl
