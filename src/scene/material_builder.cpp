#include "material_builder.h"

#include <algorithm>

#include "strahl/core/error.h"

namespace strahl::scene_detail {

namespace fs = std::filesystem;

TextureHandle addTexture(World& world, const fs::path& file, TextureEncoding encoding,
                         const std::string& where) {
    if (file.empty()) return {};
    if (!world.textures) world.textures = std::make_unique<TextureSystem>();
    try {
        return world.textures->add(file, encoding);
    } catch (const Error& e) {
        fail(where, ": ", e.what());
    }
}

namespace {

// Registers `file` (if any) and points `ref` at it.
void bindTexture(World& world, const fs::path& file, TextureEncoding encoding,
                 const std::string& where, TextureRef& ref) {
    ref.file = file;
    ref.handle = addTexture(world, file, encoding, where);
}

// What OBJ and glTF materials map alike: the emission (clamped at 0) with its
// texture, and the normal map; both call it after adding their other textures.
void setEmissionAndNormalMap(const MeshMaterial& m, const std::string& name, World& world,
                             Material& mat) {
    mat.emission.value = glm::max(m.emission, Color(0.0f));
    bindTexture(world, m.emissionTexture, TextureEncoding::Color, name, mat.emission.texture);
    bindTexture(world, m.normalTexture, TextureEncoding::Data, name, mat.normalMap);
}

// OBJ's Phong exponent Ns runs 0..1000; the (Blinn-)Phong lobes need >= 0.
constexpr float kMaxObjExponent = 1e4f;

Material fromObj(const MeshMaterial& m, const std::string& name, World& world) {
    Material mat;
    mat.name = name;
    // Tf is not a test for glass: exporters write "Tf 1 1 1" on opaque
    // materials (McGuire's Cornell box lamp), so only illum and d decide.
    const bool glass = m.illum == 4 || m.illum == 6 || m.illum == 7 || m.illum == 9 ||
                       m.dissolve < 1.0f;
    const bool mirror = m.illum == 3 || m.illum == 5;
    if (glass) {
        DielectricMaterial dielectric;
        // Ni <= 1 (often 1 or absent in exported files) has no interface: 1.5.
        dielectric.ior = m.ior > 1.0001f ? std::min(m.ior, 4.0f) : 1.5f;
        // Clear glass: Tf is as unreliable a tint as a test (McGuire's glass
        // sphere has Tf 0.1, which would make it nearly black).
        dielectric.tint.value = Color(1.0f);
        mat.kind = dielectric;
    } else if (mirror) {
        // A mirror whose colour is Ks: a smooth conductor with eta = 1 and
        // the k that gives normal-incidence reflectance Ks,
        // F0 = k^2 / (4 + k^2)  =>  k = 2 sqrt(F0 / (1 - F0)).
        ConductorMaterial conductor;
        const Color f0 = glm::clamp(maxComponent(m.specular) > 0.0f ? m.specular : Color(0.9f),
                                    Color(0.0f), Color(0.999f));
        conductor.eta = Color(1.0f);
        conductor.k = 2.0f * glm::sqrt(f0 / (Color(1.0f) - f0));
        mat.kind = conductor;
    } else if (maxComponent(m.specular) > 0.0f && m.shininess > 0.0f) {
        PhongMaterial phong;
        Color kd = glm::max(m.diffuse, Color(0.0f)), ks = glm::max(m.specular, Color(0.0f));
        // Many .mtl files have Kd + Ks > 1; scale both down to conserve energy.
        const float sum = maxComponent(kd + ks);
        if (sum > 1.0f) {
            kd /= sum;
            ks /= sum;
        }
        phong.color.value = kd;
        phong.specular = ks;
        phong.exponent = std::min(m.shininess, kMaxObjExponent);
        if (!m.diffuseTexture.empty()) {
            // map_Kd replaces Kd in most exporters' files (Sponza's Kd are grey
            // placeholders), so the texture is used unscaled, up to 1 - Ks.
            bindTexture(world, m.diffuseTexture, TextureEncoding::Color, name, phong.color.texture);
            phong.color.value = Color(1.0f) - phong.specular;
        }
        mat.kind = phong;
    } else {
        DiffuseMaterial diffuse;
        diffuse.color.value = glm::clamp(m.diffuse, Color(0.0f), Color(1.0f));
        if (!m.diffuseTexture.empty()) {
            bindTexture(world, m.diffuseTexture, TextureEncoding::Color, name, diffuse.color.texture);
            diffuse.color.value = Color(1.0f);  // as for Phong: map_Kd replaces Kd
        }
        mat.kind = diffuse;
    }
    setEmissionAndNormalMap(m, name, world, mat);
    return mat;
}

Material fromGltf(const MeshMaterial& m, const std::string& name, World& world) {
    Material mat;
    mat.name = name;
    const float transmission = maxComponent(m.transmission);
    const float ior = m.ior > 1.0001f ? std::min(m.ior, 4.0f) : 1.5f;
    const float roughness = std::clamp(m.roughness, 0.0f, 1.0f);
    if (transmission > 0.5f) {
        // KHR_materials_transmission: a mostly transmissive surface is glass
        // tinted by the base colour (the mix of both lobes is not modelled).
        DielectricMaterial dielectric;
        dielectric.ior = ior;
        dielectric.roughness.value = roughness;
        dielectric.tint.value = glm::clamp(m.diffuse, Color(0.0f), Color(1.0f));
        mat.kind = dielectric;
    } else {
        MetallicRoughnessMaterial mr;
        mr.ior = ior;
        mr.roughness.value = roughness;  // channel G, as glTF stores it
        mr.color.value = glm::clamp(m.diffuse, Color(0.0f), Color(1.0f));
        mr.metallic.value = std::clamp(m.metallic, 0.0f, 1.0f);  // channel B
        bindTexture(world, m.diffuseTexture, TextureEncoding::Color, name, mr.color.texture);
        bindTexture(world, m.metallicRoughnessTexture, TextureEncoding::Data, name,
                    mr.metallic.texture);
        mr.roughness.texture = mr.metallic.texture;  // one texture, two channels
        mat.kind = mr;
    }
    setEmissionAndNormalMap(m, name, world, mat);
    // glTF alpha (the reader drops it on emitting materials).
    if (!m.opacityTexture.empty() || m.dissolve < 1.0f || m.opacityCutoff >= 0.0f) {
        mat.opacity.value = m.dissolve;
        mat.opacity.channel = 3;  // the base colour's alpha (1 where the image has none)
        bindTexture(world, m.opacityTexture, TextureEncoding::Data, name, mat.opacity.texture);
        mat.opacityCutoff = m.opacityCutoff;
    }
    return mat;
}

}  // namespace

Material buildMaterial(const MaterialDesc& desc, const SceneDesc& scene, World& world) {
    Material mat = desc.material;
    mat.name = desc.name;
    const std::string where = scene.file.filename().string() + ": " + desc.where;
    mat.forEachTexture([&](TextureRef& texture, TextureEncoding encoding) {
        if (texture.raw) encoding = *texture.raw ? TextureEncoding::Data : TextureEncoding::Color;
        texture.handle = addTexture(world, texture.file, encoding, where);
    });
    return mat;
}

Material buildMeshMaterial(const MeshMaterial& mesh, const std::string& name, World& world) {
    return mesh.source == MeshMaterial::Source::Gltf ? fromGltf(mesh, name, world)
                                                     : fromObj(mesh, name, world);
}

}  // namespace strahl::scene_detail
