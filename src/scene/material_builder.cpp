#include "material_builder.h"

#include <algorithm>

#include "strahl/core/error.h"

namespace strahl::scene_detail {

namespace fs = std::filesystem;

namespace {

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

// What OBJ and glTF materials map alike: the emission (clamped at 0) with its
// texture, and the normal map; both call it after adding their other textures.
void setEmissionAndNormalMap(const MeshMaterial& m, const std::string& name, World& world,
                             Material& mat) {
    mat.emission.value = glm::max(m.emission, Color(0.0f));
    if (!m.emissionTexture.empty())
        mat.emission.texture = addTexture(world, m.emissionTexture, TextureEncoding::Color, name);
    if (!m.normalTexture.empty())
        mat.normalMap = addTexture(world, m.normalTexture, TextureEncoding::Data, name);
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
        // Ni <= 1 (often 1 or absent in exported files) has no interface: 1.5.
        mat.type = Material::Type::Dielectric;
        mat.ior = m.ior > 1.0001f ? std::min(m.ior, 4.0f) : 1.5f;
        // Clear glass: Tf is as unreliable a tint as a test (McGuire's glass
        // sphere has Tf 0.1, which would make it nearly black).
        mat.color.value = Color(1.0f);
    } else if (mirror) {
        // A mirror whose colour is Ks: a smooth conductor with eta = 1 and
        // the k that gives normal-incidence reflectance Ks,
        // F0 = k^2 / (4 + k^2)  =>  k = 2 sqrt(F0 / (1 - F0)).
        mat.type = Material::Type::Conductor;
        const Color f0 = glm::clamp(maxComponent(m.specular) > 0.0f ? m.specular : Color(0.9f),
                                    Color(0.0f), Color(0.999f));
        mat.eta = Color(1.0f);
        mat.k = 2.0f * glm::sqrt(f0 / (Color(1.0f) - f0));
        mat.roughness.value = 0.0f;
    } else if (maxComponent(m.specular) > 0.0f && m.shininess > 0.0f) {
        mat.type = Material::Type::Phong;
        Color kd = glm::max(m.diffuse, Color(0.0f)), ks = glm::max(m.specular, Color(0.0f));
        // Many .mtl files have Kd + Ks > 1; scale both down to conserve energy.
        const float sum = maxComponent(kd + ks);
        if (sum > 1.0f) {
            kd /= sum;
            ks /= sum;
        }
        mat.color.value = kd;
        mat.specular = ks;
        mat.exponent = std::min(m.shininess, kMaxObjExponent);
    } else {
        mat.type = Material::Type::Diffuse;
        mat.color.value = glm::clamp(m.diffuse, Color(0.0f), Color(1.0f));
    }
    if (!glass && !mirror && !m.diffuseTexture.empty()) {
        mat.color.texture = addTexture(world, m.diffuseTexture, TextureEncoding::Color, name);
        // map_Kd replaces Kd in most exporters' files (Sponza's Kd are grey
        // placeholders), so the texture is used unscaled.
        mat.color.value = Color(1.0f);
        if (mat.type == Material::Type::Phong) mat.color.value = Color(1.0f) - mat.specular;
    }
    setEmissionAndNormalMap(m, name, world, mat);
    return mat;
}

Material fromGltf(const MeshMaterial& m, const std::string& name, World& world) {
    Material mat;
    mat.name = name;
    const float transmission = maxComponent(m.transmission);
    mat.ior = m.ior > 1.0001f ? std::min(m.ior, 4.0f) : 1.5f;
    mat.roughness.value = std::clamp(m.roughness, 0.0f, 1.0f);
    mat.roughness.channel = 1;  // glTF: roughness in G
    if (transmission > 0.5f) {
        // KHR_materials_transmission: a mostly transmissive surface is glass
        // tinted by the base colour (the mix of both lobes is not modelled).
        mat.type = Material::Type::Dielectric;
        mat.color.value = glm::clamp(m.diffuse, Color(0.0f), Color(1.0f));
    } else {
        mat.type = Material::Type::MetallicRoughness;
        mat.color.value = glm::clamp(m.diffuse, Color(0.0f), Color(1.0f));
        mat.metallic.value = std::clamp(m.metallic, 0.0f, 1.0f);
        mat.metallic.channel = 2;  // glTF: metallic in B
        if (!m.diffuseTexture.empty())
            mat.color.texture = addTexture(world, m.diffuseTexture, TextureEncoding::Color, name);
        if (!m.metallicRoughnessTexture.empty()) {
            const TextureHandle mr =
                addTexture(world, m.metallicRoughnessTexture, TextureEncoding::Data, name);
            mat.metallic.texture = mr;
            mat.roughness.texture = mr;
        }
    }
    setEmissionAndNormalMap(m, name, world, mat);
    return mat;
}

}  // namespace

Material buildMaterial(const MaterialDesc& desc, const SceneDesc& scene, World& world) {
    Material mat = desc.material;
    mat.name = desc.name;
    const std::string where = scene.file.filename().string() + ": " + desc.where;
    mat.color.texture = addTexture(world, desc.textures.color, TextureEncoding::Color, where);
    mat.roughness.texture = addTexture(world, desc.textures.roughness, TextureEncoding::Data, where);
    mat.metallic.texture = addTexture(world, desc.textures.metallic, TextureEncoding::Data, where);
    mat.emission.texture = addTexture(world, desc.textures.emission, TextureEncoding::Color, where);
    mat.normalMap = addTexture(world, desc.textures.normal, TextureEncoding::Data, where);
    return mat;
}

Material buildMeshMaterial(const MeshMaterial& mesh, const std::string& name, World& world) {
    return mesh.source == MeshMaterial::Source::Gltf ? fromGltf(mesh, name, world)
                                                     : fromObj(mesh, name, world);
}

}  // namespace strahl::scene_detail
