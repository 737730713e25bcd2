#include "strahl/integrator/material.h"

#include <algorithm>
#include <cmath>

namespace strahl {

namespace {

// One texture lookup at sp in the material's mapping. Mesh UVs have v up;
// OIIO's t runs down the image, hence t = 1 - v.
Vec4 lookup(TextureHandle texture, const TextureMapping& mapping, const ShadingPoint& sp,
            const TextureSystem& textures) {
    if (mapping.kind == TextureMapping::Kind::Triplanar)
        return textures.triplanar(texture, sp.p, sp.n, mapping.scale, mapping.sharpness,
                                  sp.footprint * mapping.scale);
    return textures.lookup(texture, Vec2(sp.uv.x, 1.0f - sp.uv.y), sp.footprint);
}

// Texture values feed BSDF factories that reject NaN and negative input; an
// HDR or corrupt texel must not stop a render, so reflectances are clamped to
// [0, 1] and NaN becomes 0.
Color reflectance(const Color& c) {
    Color r;
    for (int i = 0; i < 3; ++i) r[i] = c[i] > 0.0f ? std::min(c[i], 1.0f) : 0.0f;
    return r;
}

}  // namespace

Color evaluateColor(const TexturedColor& c, const TextureMapping& mapping, const ShadingPoint& sp,
                    const TextureSystem* textures) {
    if (!c.texture.valid() || !textures) return c.value;
    return c.value * Color(lookup(c.texture, mapping, sp, *textures));
}

float evaluateFloat(const TexturedFloat& f, const TextureMapping& mapping, const ShadingPoint& sp,
                    const TextureSystem* textures) {
    if (!f.texture.valid() || !textures) return f.value;
    return f.value * lookup(f.texture, mapping, sp, *textures)[f.channel];
}

Bsdf makeBsdf(const Material& m, const ShadingPoint& sp, const TextureSystem* textures) {
    const auto color = [&] { return reflectance(evaluateColor(m.color, m.mapping, sp, textures)); };
    const auto alpha = [&] {
        const float r = std::clamp(evaluateFloat(m.roughness, m.mapping, sp, textures), 0.0f, 1.0f);
        // std::clamp passes NaN through; a NaN texel means smooth.
        if (std::isnan(r)) return 0.0f;
        return Bsdf::roughnessToAlpha(r);
    };
    switch (m.type) {
        case Material::Type::Diffuse: return Bsdf::diffuse(color());
        // The parser keeps color + specular <= 1; a texture may not.
        case Material::Type::Phong:
            return Bsdf::phong(glm::min(color(), Color(1.0f) - m.specular), m.specular, m.exponent);
        case Material::Type::BlinnPhong:
            return Bsdf::blinnPhong(glm::min(color(), Color(1.0f) - m.specular), m.specular,
                                    m.exponent);
        case Material::Type::Conductor: {
            const float a = alpha();
            return Bsdf::conductor(m.eta, m.k, a, a);
        }
        case Material::Type::Dielectric: return Bsdf::dielectric(m.ior, alpha(), color());
        case Material::Type::Plastic: return Bsdf::plastic(color(), m.ior, alpha());
        case Material::Type::MetallicRoughness: {
            float metallic =
                std::clamp(evaluateFloat(m.metallic, m.mapping, sp, textures), 0.0f, 1.0f);
            if (std::isnan(metallic)) metallic = 0.0f;
            return Bsdf::metallicRoughness(color(), metallic, alpha(), m.ior);
        }
        case Material::Type::Emissive: return Bsdf::black();
    }
    return Bsdf::black();
}

Color emittedRadiance(const Material& m, const ShadingPoint& sp, const TextureSystem* textures) {
    if (!m.emits()) return Color(0.0f);
    return evaluateColor(m.emission, m.mapping, sp, textures);
}

Vec3 shadingNormal(const Material& m, const ShadingPoint& sp, const TextureSystem* textures) {
    if (!m.normalMap.valid() || !textures) return sp.n;
    const Vec3 encoded(lookup(m.normalMap, m.mapping, sp, *textures));
    return applyNormalMap(encoded, sp.n, sp.dpdu);
}

}  // namespace strahl
