#pragma once
// "diffuse_transmission": Lambertian reflection and transmission, f = R / pi
// on the side light comes from and T / pi through to the other (thin leaves,
// paper, lamp shades; pbrt-v4's diffusetransmission). docs/materials.md.
//
//   key            value                                   default
//   color          reflectance R: colour or texture         0.25
//   transmittance  transmittance T: colour or texture       0.25
//
// R + T <= 1 per channel conserves energy (not enforced: textures may exceed
// it where they are brighter than their files say).

#include <array>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct DiffuseTransmissionMaterial {
    static constexpr std::string_view kName = "diffuse_transmission";
    static constexpr std::array<std::string_view, 2> kKeys = {"color", "transmittance"};

    TexturedColor color{Color(0.25f), {}};
    TexturedColor transmittance{Color(0.25f), {}};

    template <typename Reader>
    static DiffuseTransmissionMaterial parse(const Reader& r) {
        DiffuseTransmissionMaterial m;
        r.texturedColor("color", m.color);
        r.texturedColor("transmittance", m.transmittance);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        return Bsdf::diffuseTransmission(p.reflectance(color), p.reflectance(transmittance));
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        visitTextures(color, TextureEncoding::Color, fn);
        visitTextures(transmittance, TextureEncoding::Color, fn);
    }
};

}  // namespace strahl
