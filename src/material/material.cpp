#include "strahl/material/material.h"

#include <algorithm>
#include <cmath>

#include "strahl/texture/bump_map.h"
#include "strahl/texture/normal_map.h"

namespace strahl {

namespace {

// One texture lookup at sp in the material's mapping. Mesh UVs have v up;
// OIIO's t runs down the image, hence t = 1 - v.
Vec4 lookup(const TextureRef& texture, const TextureMapping& mapping, const ShadingPoint& sp,
            const TextureSystem& textures) {
    if (mapping.kind == TextureMapping::Kind::Triplanar)
        return textures.triplanar(texture.handle, sp.p, sp.n, mapping.scale, mapping.sharpness,
                                  sp.footprint * mapping.scale, texture.sampling);
    return lookupTexture(texture, Vec2(sp.uv.x, 1.0f - sp.uv.y), sp.footprint, textures);
}

}  // namespace

Vec4 lookupTexture(const TextureRef& texture, Vec2 st, float footprint,
                   const TextureSystem& textures) {
    if (texture.stTransform != Mat3(1.0f)) {
        const Mat3& m = texture.stTransform;
        st = Vec2(m * Vec3(st, 1.0f));
        // A width scales by the square root of the area ratio.
        footprint *= std::sqrt(std::abs(m[0][0] * m[1][1] - m[1][0] * m[0][1]));
    }
    return textures.lookup(texture.handle, st, footprint, texture.sampling);
}

Color Checkerboard::at(Vec2 uv) const {
    const float s = scale.x * uv.x, t = scale.y * (1.0f - uv.y);
    const bool upperS = s - std::floor(s) > 0.5f, upperT = t - std::floor(t) > 0.5f;
    return upperS == upperT ? color0 : color1;
}

ShadingPoint shadingPointAt(const SurfaceInteraction& si, float footprint) {
    ShadingPoint sp;
    sp.p = si.p;
    sp.n = si.Ns;
    sp.dpdu = si.dpdu;
    sp.dpdv = si.dpdv;
    sp.uv = si.uv;
    sp.footprint = footprint * si.uvDensity;
    if (si.attributes.mesh) sp.attributes = &si.attributes;
    return sp;
}

// (1 − t) a + t b of a mix (ColorMix or FloatMix) at sp, each input through
// `evaluate`; the input whose weight is 0 is not looked up (pbrt does the same).
template <typename Mix, typename Evaluate>
auto evaluateMix(const Mix& mix, const TextureMapping& mapping, const ShadingPoint& sp,
                 const TextureSystem* textures, Evaluate evaluate) {
    const float t = evaluateFloat(mix.amount, mapping, sp, textures);
    if (t == 0.0f) return evaluate(mix.a, mapping, sp, textures);
    if (t == 1.0f) return evaluate(mix.b, mapping, sp, textures);
    return (1.0f - t) * evaluate(mix.a, mapping, sp, textures) + t * evaluate(mix.b, mapping, sp, textures);
}

Color evaluateColor(const TexturedColor& c, const TextureMapping& mapping, const ShadingPoint& sp,
                    const TextureSystem* textures) {
    if (c.mix) return c.value * evaluateMix(*c.mix, mapping, sp, textures, &evaluateColor);
    if (c.checkerboard) return c.value * c.checkerboard->at(sp.uv);
    if (!c.texture.meshAttribute.empty())
        return sp.attributes ? c.value * Color(sp.attributes->value(c.texture.meshAttribute)) : Color(0.0f);
    if (!c.texture.valid() || !textures) return c.value;
    return c.value * Color(lookup(c.texture, mapping, sp, *textures));
}

float evaluateFloat(const TexturedFloat& f, const TextureMapping& mapping, const ShadingPoint& sp,
                    const TextureSystem* textures) {
    if (f.mix) return f.value * evaluateMix(*f.mix, mapping, sp, textures, &evaluateFloat);
    if (f.checkerboard) return f.value * f.checkerboard->at(sp.uv).r;
    if (!f.texture.meshAttribute.empty())
        return sp.attributes ? f.value * sp.attributes->value(f.texture.meshAttribute)[f.channel] : 0.0f;
    if (!f.texture.valid() || !textures) return f.value;
    return f.value * lookup(f.texture, mapping, sp, *textures)[f.channel];
}

Vec3 lookupNormalMap(const TextureRef& normalMap, const TextureMapping& mapping,
                     const ShadingPoint& sp, const TextureSystem& textures) {
    return Vec3(lookup(normalMap, mapping, sp, textures));
}

float opacityAt(const Material& material, Vec2 uv, const TextureSystem* textures) {
    ShadingPoint sp;
    sp.uv = uv;
    return evaluateFloat(material.opacity, material.mapping, sp, textures);
}

Color MaterialPoint::reflectance(const TexturedColor& c) const {
    const Color value = color(c);
    Color r;
    for (int i = 0; i < 3; ++i) r[i] = value[i] > 0.0f ? std::min(value[i], 1.0f) : 0.0f;
    return r;
}

float MaterialPoint::unit(const TexturedFloat& f) const {
    const float x = std::clamp(scalar(f), 0.0f, 1.0f);
    return std::isnan(x) ? 0.0f : x;  // std::clamp passes NaN through
}

float MaterialPoint::alpha(const TexturedFloat& roughness) const {
    return Bsdf::roughnessToAlpha(unit(roughness));
}

Material Material::diffuse(std::string name, const Color& reflectance, const Color& emitted) {
    Material m;
    m.name = std::move(name);
    m.kind = DiffuseMaterial{TexturedColor{reflectance, {}}};
    m.emission.value = emitted;
    return m;
}

Bsdf makeBsdf(const Material& m, const ShadingPoint& sp, const TextureSystem* textures) {
    const MaterialPoint point{sp, m.mapping, textures};
    return std::visit([&](const auto& kind) { return kind.bsdf(point); }, m.kind);
}

Color emittedRadiance(const Material& m, const ShadingPoint& sp, const TextureSystem* textures) {
    if (!m.emits()) return Color(0.0f);
    return evaluateColor(m.emission, m.mapping, sp, textures);
}

Vec3 shadingNormal(const Material& m, const ShadingPoint& sp, const TextureSystem* textures) {
    if (!textures) return sp.n;
    if (m.bumpMap.valid()) {
        // The slope in the texture's own coordinates st' = M st, back to st
        // by the chain rule: dh/ds = M00 dh/ds' + M10 dh/dt', and so on.
        const Mat3& M = m.bumpMap.stTransform;
        const Vec2 st(sp.uv.x, 1.0f - sp.uv.y);
        const Vec3 h = textures->lookupSlope(m.bumpMap.handle, Vec2(M * Vec3(st, 1.0f)),
                                             m.bumpMap.sampling);
        const Vec2 slope(M[0][0] * h.y + M[0][1] * h.z, M[1][0] * h.y + M[1][1] * h.z);
        return applyBumpMap(m.bumpScale * slope, sp.n, sp.dpdu, sp.dpdv);
    }
    if (!m.normalMap.valid()) return sp.n;
    return applyNormalMap(lookupNormalMap(m.normalMap, m.mapping, sp, *textures), sp.n, sp.dpdu);
}

}  // namespace strahl
