#pragma once
// "phong" and "blinn": energy-conserving modified Phong (Lafortune & Willems
// 1994) and normalised Blinn-Phong — kd / pi plus a normalised cos^n lobe
// (docs/materials.md).
//
//   key        value                                          default
//   color      diffuse colour kd: colour or texture            0.8
//   diffuse    older name of color
//   specular   specular colour ks (color + specular <= 1)      0.2
//   exponent   lobe exponent n in [0, 10^4]                    32

#include <array>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

// The parameters and parsing both lobes share; Blinn selects the lobe.
template <bool Blinn>
struct PhongLikeMaterial {
    static constexpr std::string_view kName = Blinn ? "blinn" : "phong";
    static constexpr std::array<std::string_view, 4> kKeys = {"color", "diffuse", "specular",
                                                              "exponent"};

    TexturedColor color{Color(0.8f), {}};
    Color specular{0.2f};
    float exponent = 32.0f;

    template <typename Reader>
    static PhongLikeMaterial parse(const Reader& r) {
        PhongLikeMaterial m;
        material_parsing::colorOrDiffuse(r, m.color);
        if (auto specular = r.find("specular")) m.specular = specular->color();
        // Energy conservation of the sum needs kd + ks <= 1.
        const Color sum = m.color.value + m.specular;
        if (maxComponent(sum) > 1.0f)
            r.fail("color + specular must not exceed 1 in any channel (energy conservation), got (",
                   sum.x, ", ", sum.y, ", ", sum.z, ")");
        // 10^4 is a mirror-like lobe; beyond it use a conductor.
        if (auto exponent = r.find("exponent")) m.exponent = exponent->numberIn(0.0f, 1e4f);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        // The parser keeps color + specular <= 1; a texture may not.
        const Color kd = glm::min(p.reflectance(color), Color(1.0f) - specular);
        return Blinn ? Bsdf::blinnPhong(kd, specular, exponent) : Bsdf::phong(kd, specular, exponent);
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        visitTextures(color, TextureEncoding::Color, fn);
    }
};

using PhongMaterial = PhongLikeMaterial<false>;
using BlinnMaterial = PhongLikeMaterial<true>;

}  // namespace strahl
