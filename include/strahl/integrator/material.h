#pragma once
// Materials: what the scene file and mesh files describe, with textures bound,
// turned into a BSDF at each shading point (bsdf/bsdf.h has the models).
//
//   diffuse             Lambert, colour
//   phong / blinn       energy-conserving (Blinn-)Phong: diffuse + specular colours, exponent
//   conductor           GGX metal: a preset ("gold") or eta/k, roughness
//   dielectric          glass: ior, roughness (0: smooth), tint colour
//   plastic             diffuse colour under a dielectric coat: ior, roughness
//   metallic_roughness  glTF 2.0: base colour, metallic, roughness, ior
//   emissive            emits, reflects nothing
// Any material may also emit (emission) and carry a normal map. Keys, defaults
// and the mapping from OBJ/glTF materials: docs/materials.md.

#include <string>

#include "strahl/bsdf/bsdf.h"
#include "strahl/core/math.h"
#include "strahl/geometry/surface_interaction.h"
#include "strahl/texture/texture_system.h"

namespace strahl {

// A colour, optionally multiplied by a texture's RGB.
struct TexturedColor {
    Color value{1.0f};
    TextureHandle texture;
};

// A scalar, optionally multiplied by one channel of a texture.
struct TexturedFloat {
    float value = 0.0f;
    TextureHandle texture;
    int channel = 0;  // 0 R, 1 G, 2 B, 3 A
};

// How a texture is placed on the surface.
struct TextureMapping {
    enum class Kind { UV, Triplanar };
    Kind kind = Kind::UV;
    float scale = 1.0f;      // triplanar: texture repeats per world unit
    float sharpness = 4.0f;  // triplanar: blend exponent on |n|
};

struct Material {
    enum class Type { Diffuse, Phong, BlinnPhong, Conductor, Dielectric, Plastic,
                      MetallicRoughness, Emissive };
    std::string name;
    Type type = Type::Diffuse;
    TexturedColor color{Color(0.8f), {}};  // diffuse / base colour / glass tint
    Color specular{0.0f};                  // phong: ks
    float exponent = 32.0f;                // phong: lobe exponent
    Color eta{1.5f}, k{0.0f};              // conductor: complex index of refraction
    float ior = 1.5f;                      // dielectric, plastic, metallic_roughness
    TexturedFloat roughness{0.0f, {}, 1};  // perceptual, alpha = r^2; glTF texture: G
    TexturedFloat metallic{0.0f, {}, 2};   // metallic_roughness; glTF texture: B
    TexturedColor emission{Color(0.0f), {}};
    bool twoSidedEmission = false;  // otherwise only the front (Ng) side emits
    TextureHandle normalMap;
    TextureMapping mapping;

    // A Lambertian material (what tests and benchmarks mostly need).
    static Material diffuse(std::string name, const Color& reflectance,
                            const Color& emitted = Color(0.0f)) {
        Material m;
        m.name = std::move(name);
        m.color.value = reflectance;
        m.emission.value = emitted;
        return m;
    }

    bool emits() const { return maxComponent(emission.value) > 0.0f; }
    // Emission that does not vary over the surface (no texture): such
    // triangles become area lights for next-event estimation.
    bool hasUniformEmission() const { return emits() && !emission.texture.valid(); }
};

// What the material needs to know about the shading point.
struct ShadingPoint {
    Vec3 p{0.0f};      // world space (triplanar)
    Vec3 n{0.0f};      // shading normal (triplanar blend, normal-map frame)
    Vec3 dpdu{0.0f};   // tangent along u (normal maps, anisotropy); zero if unknown
    Vec2 uv{0.0f};     // texture coordinates, v up
    float footprint = 0.0f;  // ray footprint width in uv units (texture filtering)
};

// Texture lookups of one material at one point. `textures` may be null when
// the material has no textures.
Color evaluateColor(const TexturedColor& c, const TextureMapping& mapping,
                    const ShadingPoint& sp, const TextureSystem* textures);
float evaluateFloat(const TexturedFloat& f, const TextureMapping& mapping,
                    const ShadingPoint& sp, const TextureSystem* textures);

// The BSDF of `material` at sp.
Bsdf makeBsdf(const Material& material, const ShadingPoint& sp, const TextureSystem* textures);
// The emitted radiance at sp (before the one-sided test).
Color emittedRadiance(const Material& material, const ShadingPoint& sp,
                      const TextureSystem* textures);
// The shading normal after the material's normal map (sp.n without one).
Vec3 shadingNormal(const Material& material, const ShadingPoint& sp,
                   const TextureSystem* textures);

}  // namespace strahl
