#pragma once
// "hair": a hair or fur fibre (Chiang et al. 2016; Bsdf::hair,
// docs/materials.md, "Hair"), for curves. Its pigment is given one of three
// ways — a colour, an absorption, or melanin concentrations:
//
//   key          value                                                  default
//   color        the fibre's colour in light scattered many times:      —
//                colour or texture (absorption by Chiang's fit)
//   sigma_a      absorption per unit of the fibre's radius, colour >= 0 —
//   eumelanin    brown-black pigment concentration, >= 0 (0.3 blond,    1.3
//                1.3 brown, 8 black)
//   pheomelanin  red-yellow pigment concentration, >= 0                  0
//   beta_m       longitudinal roughness, [0, 1]                         0.3
//   beta_n       azimuthal roughness, [0, 1]                            0.3
//   alpha        tilt of the cuticle scales, degrees, [-45, 45]          2
//   ior          index of the fibre, (1, 4]                              1.55
//
// The melanin absorptions per unit concentration are those of Donner and
// Jensen as used by pbrt-v4: eumelanin (0.419, 0.697, 1.37), pheomelanin
// (0.187, 0.4, 1.05).

#include <array>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct HairMaterial {
    static constexpr std::string_view kName = "hair";
    static constexpr std::array<std::string_view, 8> kKeys = {"color",  "sigma_a", "eumelanin", "pheomelanin",
                                                              "beta_m", "beta_n",  "alpha",     "ior"};

    bool byColor = false;
    TexturedColor color{Color(0.5f), {}};
    Color sigmaA = 1.3f * Color(0.419f, 0.697f, 1.37f);
    float betaM = 0.3f, betaN = 0.3f, alpha = 2.0f, ior = 1.55f;

    template <typename Reader>
    static HairMaterial parse(const Reader& r) {
        HairMaterial m;
        const bool melanin = r.has("eumelanin") || r.has("pheomelanin");
        if (int(r.has("color")) + int(r.has("sigma_a")) + int(melanin) > 1)
            r.fail("give one of 'color', 'sigma_a' or 'eumelanin'/'pheomelanin'");
        if (r.has("color")) {
            m.byColor = true;
            r.texturedColor("color", m.color);
        }
        if (auto s = r.find("sigma_a")) {
            m.sigmaA = s->color();
            if (!(m.sigmaA.r >= 0.0f && m.sigmaA.g >= 0.0f && m.sigmaA.b >= 0.0f)) s->fail("must be >= 0");
        }
        if (melanin) {
            float eu = 0.0f, pheo = 0.0f;
            if (auto e = r.find("eumelanin")) eu = e->numberIn(0.0f, 1e4f);
            if (auto p = r.find("pheomelanin")) pheo = p->numberIn(0.0f, 1e4f);
            m.sigmaA = eu * Color(0.419f, 0.697f, 1.37f) + pheo * Color(0.187f, 0.4f, 1.05f);
        }
        if (auto v = r.find("beta_m")) m.betaM = v->numberIn(0.0f, 1.0f);
        if (auto v = r.find("beta_n")) m.betaN = v->numberIn(0.0f, 1.0f);
        if (auto v = r.find("alpha")) m.alpha = v->numberIn(-45.0f, 45.0f);
        material_parsing::ior(r, m.ior);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        const Color sigma = byColor ? Bsdf::hairSigmaAFromColor(p.reflectance(color), betaN) : sigmaA;
        return Bsdf::hair(sigma, betaM, betaN, alpha, ior);
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        visitTextures(color, TextureEncoding::Color, fn);
    }
};

}  // namespace strahl
