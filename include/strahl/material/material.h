#pragma once
// Materials: what the scene file and mesh files describe, with textures bound,
// turned into a BSDF at each shading point (bsdf/bsdf.h has the models).
// A material is one kind from material_kinds.h (diffuse, phong, blinn,
// conductor, dielectric, thin_dielectric, plastic, metallic_roughness,
// principled, blend, emissive) plus what every kind may have: an emission, a
// normal or bump map, an opacity and a texture mapping. Keys,
// defaults and the mapping from OBJ/glTF materials: docs/materials.md.

#include <string>

#include "strahl/bsdf/bsdf.h"
#include "strahl/core/math.h"
#include "strahl/material/material_kinds.h"
#include "strahl/material/textured.h"

namespace strahl {

struct Material {
    std::string name;
    MaterialKind kind;  // a grey (0.8) diffuse unless set
    TexturedColor emission{Color(0.0f), {}};
    bool twoSidedEmission = false;  // otherwise only the front (Ng) side emits
    TextureRef normalMap;
    // A height map (its luminance; exclusive with normalMap) times bumpScale.
    TextureRef bumpMap;
    float bumpScale = 1.0f;
    // Chiang et al.'s shadowing of the light a normal or bump map tilts
    // towards grazing (docs/textures.md, "Normal maps"); Mitsuba's normalmap
    // and bumpmap have it.
    bool terminatorShadowing = false;
    TextureMapping mapping;
    // Alpha cut-out: 1 solid, 0 a hole, between a stochastic opacity, read
    // through the uvs at footprint 0 (docs/materials.md, "Opacity").
    TexturedFloat opacity{1.0f, {}, 0};
    // When in [0, 1]: the opacity is a threshold instead, solid where it is
    // at least this and a hole elsewhere (glTF's alphaMode MASK).
    float opacityCutoff = -1.0f;

    // A Lambertian material (what tests and benchmarks mostly need).
    static Material diffuse(std::string name, const Color& reflectance,
                            const Color& emitted = Color(0.0f));

    bool emits() const { return maxComponent(emission.value) > 0.0f; }
    // Emission that is its `value` everywhere (no texture, no mix — even a
    // mix of constants is evaluated, not folded into the value): such
    // triangles become area lights of that radiance.
    bool hasUniformEmission() const {
        return emits() && !emission.varies() && !emission.mix;
    }
    // Whether some of the surface may be a hole.
    bool cutsOut() const { return opacity.value < 1.0f || !opacity.texture.file.empty(); }

    // Calls fn(TextureRef&, TextureEncoding) for every texture the material
    // can use, bound or not: the kind's, the opacity's, then the emission's,
    // the normal map and the bump map.
    template <typename Fn>
    void forEachTexture(Fn&& fn) {
        std::visit([&](auto& k) { k.forEachTexture(fn); }, kind);
        visitTextures(opacity, TextureEncoding::Data, fn);
        visitTextures(emission, TextureEncoding::Color, fn);
        fn(normalMap, TextureEncoding::Data);
        fn(bumpMap, TextureEncoding::Data);
    }
    // Whether a normal or bump map perturbs the shading normal.
    bool mapsNormals() const { return normalMap.valid() || bumpMap.valid(); }
};

// The BSDF of `material` at sp. `textures` may be null when no texture is bound.
Bsdf makeBsdf(const Material& material, const ShadingPoint& sp, const TextureSystem* textures);
// The emitted radiance at sp (before the one-sided test).
Color emittedRadiance(const Material& material, const ShadingPoint& sp,
                      const TextureSystem* textures);
// The opacity at texture coordinates uv (footprint 0), not clamped.
float opacityAt(const Material& material, Vec2 uv, const TextureSystem* textures);
// The shading normal after the material's normal or bump map (sp.n without).
Vec3 shadingNormal(const Material& material, const ShadingPoint& sp,
                   const TextureSystem* textures);

}  // namespace strahl
