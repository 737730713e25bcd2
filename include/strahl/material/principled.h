#pragma once
// "principled": Burley's principled BSDF as Mitsuba 3 defines it (its
// "principled", and with "thin" its "principledthin"); docs/materials.md,
// "Principled". Every number below may be a texture, a checkerboard or a
// mesh attribute; the defaults are Mitsuba's.
//
//   key                   value                                       default
//   color                 base colour                                  0.5
//   roughness             perceptual roughness, alpha = r^2            0.5
//   anisotropic           [0, 1]: stretches the lobe along dp/du       0
//   metallic              [0, 1] (not thin)                            0
//   specular              [0, 1]: the dielectric's reflectance,        0.5
//                         eta = 2 / (1 - sqrt(0.08 specular)) - 1
//   ior                   the index instead of specular, (1, 4]        (1.5)
//   specular_tint         [0, 1]: tints the dielectric reflection      0
//   sheen, sheen_tint     [0, 1]                                       0
//   clearcoat, clearcoat_gloss  [0, 1] (not thin)                      0
//   transmission          [0, 1]: rough refraction (thin: straight)    0
//   flatness              [0, 1]: diffuse towards fake subsurface      0
//   thin                  a thin sheet (a leaf, paper)                 false
//   diffuse_transmission  [0, 2], thin only: the diffuse lobe's        0
//                         share that passes through, times 2

#include <array>
#include <cmath>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct PrincipledMaterial {
    static constexpr std::string_view kName = "principled";
    static constexpr std::array<std::string_view, 15> kKeys = {
        "color",     "roughness",       "anisotropic",  "metallic",    "specular",
        "ior",       "specular_tint",   "sheen",        "sheen_tint",  "clearcoat",
        "clearcoat_gloss", "transmission", "flatness",  "thin",        "diffuse_transmission"};

    TexturedColor color{Color(0.5f), {}};
    TexturedFloat roughness{0.5f, {}, 0};
    TexturedFloat anisotropic{0.0f, {}, 0};
    TexturedFloat metallic{0.0f, {}, 0};
    TexturedFloat specularTint{0.0f, {}, 0};
    TexturedFloat sheen{0.0f, {}, 0};
    TexturedFloat sheenTint{0.0f, {}, 0};
    TexturedFloat clearcoat{0.0f, {}, 0};
    TexturedFloat clearcoatGloss{0.0f, {}, 0};
    TexturedFloat transmission{0.0f, {}, 0};
    TexturedFloat flatness{0.0f, {}, 0};
    TexturedFloat diffuseTransmission{0.0f, {}, 0};
    float eta = 1.5f;
    bool thin = false;

    // Mitsuba's map from "specular" to the index: specular = 0.08 F0-like
    // units, F0 = ((eta - 1) / (eta + 1))^2 = 0.08 specular solved for eta.
    // Below 1e-3 the index would be 1, where refraction is degenerate.
    static float etaOfSpecular(float specular) {
        return 2.0f / (1.0f - std::sqrt(0.08f * std::max(specular, 1e-3f))) - 1.0f;
    }

    template <typename Reader>
    static PrincipledMaterial parse(const Reader& r) {
        PrincipledMaterial m;
        if (r.has("specular") && r.has("ior")) r.fail("give either 'specular' or 'ior', not both");
        m.eta = etaOfSpecular(0.5f);
        if (auto v = r.find("specular")) m.eta = etaOfSpecular(v->numberIn(0.0f, 1.0f));
        material_parsing::ior(r, m.eta);
        if (auto v = r.find("thin")) m.thin = v->boolean();
        for (const char* key : {"metallic", "clearcoat", "clearcoat_gloss"})
            if (m.thin && r.has(key)) r.fail("'", key, "' does not apply to a thin principled material");
        if (!m.thin && r.has("diffuse_transmission"))
            r.fail("'diffuse_transmission' applies to a thin principled material only (\"thin\": true)");
        r.texturedColor("color", m.color);
        r.texturedFloat("roughness", 0.0f, 1.0f, m.roughness);
        r.texturedFloat("anisotropic", 0.0f, 1.0f, m.anisotropic);
        r.texturedFloat("metallic", 0.0f, 1.0f, m.metallic);
        r.texturedFloat("specular_tint", 0.0f, 1.0f, m.specularTint);
        r.texturedFloat("sheen", 0.0f, 1.0f, m.sheen);
        r.texturedFloat("sheen_tint", 0.0f, 1.0f, m.sheenTint);
        r.texturedFloat("clearcoat", 0.0f, 1.0f, m.clearcoat);
        r.texturedFloat("clearcoat_gloss", 0.0f, 1.0f, m.clearcoatGloss);
        r.texturedFloat("transmission", 0.0f, 1.0f, m.transmission);
        r.texturedFloat("flatness", 0.0f, 1.0f, m.flatness);
        r.texturedFloat("diffuse_transmission", 0.0f, 2.0f, m.diffuseTransmission);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const {
        PrincipledParameters q;
        q.base = p.reflectance(color);
        q.roughness = p.unit(roughness);
        q.anisotropic = p.unit(anisotropic);
        q.metallic = p.unit(metallic);
        q.eta = eta;
        q.specularTint = p.unit(specularTint);
        q.sheen = p.unit(sheen);
        q.sheenTint = p.unit(sheenTint);
        q.clearcoat = p.unit(clearcoat);
        q.clearcoatGloss = p.unit(clearcoatGloss);
        q.transmission = p.unit(transmission);
        q.flatness = p.unit(flatness);
        q.thin = thin;
        const float dt = p.scalar(diffuseTransmission);
        q.diffuseTransmission = std::isnan(dt) ? 0.0f : dt;  // clamped to [0, 2] by the BSDF
        return Bsdf::principled(q);
    }
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        visitTextures(color, TextureEncoding::Color, fn);
        for (TexturedFloat* f : {&roughness, &anisotropic, &metallic, &specularTint, &sheen,
                                 &sheenTint, &clearcoat, &clearcoatGloss, &transmission,
                                 &flatness, &diffuseTransmission})
            visitTextures(*f, TextureEncoding::Data, fn);
    }
};

}  // namespace strahl
