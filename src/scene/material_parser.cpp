#include "material_parser.h"

#include <algorithm>
#include <array>

#include "strahl/bsdf/bsdf.h"

namespace strahl::scene_detail {

namespace fs = std::filesystem;

namespace {

constexpr std::array<std::string_view, 8> kTypes = {
    "diffuse", "phong", "blinn", "conductor", "dielectric", "plastic", "metallic_roughness",
    "emissive"};

Material::Type typeFromName(const std::string& name) {
    static constexpr Material::Type kByIndex[] = {
        Material::Type::Diffuse,   Material::Type::Phong,      Material::Type::BlinnPhong,
        Material::Type::Conductor, Material::Type::Dielectric, Material::Type::Plastic,
        Material::Type::MetallicRoughness, Material::Type::Emissive};
    const auto it = std::find(kTypes.begin(), kTypes.end(), name);
    return kByIndex[it - kTypes.begin()];
}

// The keys each type accepts on top of the common ones.
std::vector<std::string_view> allowedKeys(Material::Type type) {
    std::vector<std::string_view> keys = {"name", "type", "emission", "two_sided", "normal_map",
                                          "mapping"};
    const auto add = [&](std::initializer_list<std::string_view> more) {
        keys.insert(keys.end(), more.begin(), more.end());
    };
    switch (type) {
        case Material::Type::Diffuse: add({"color", "diffuse"}); break;
        case Material::Type::Phong:
        case Material::Type::BlinnPhong: add({"color", "diffuse", "specular", "exponent"}); break;
        case Material::Type::Conductor: add({"metal", "eta", "k", "roughness"}); break;
        case Material::Type::Dielectric: add({"color", "ior", "roughness"}); break;
        case Material::Type::Plastic: add({"color", "ior", "roughness"}); break;
        case Material::Type::MetallicRoughness:
            add({"color", "metallic", "roughness", "ior"});
            break;
        case Material::Type::Emissive: break;
    }
    return keys;
}

void requireKeys(const JsonValue& v, const std::string& type,
                 const std::vector<std::string_view>& keys) {
    for (const auto& item : v.raw().items()) {
        if (std::find(keys.begin(), keys.end(), item.key()) == keys.end()) {
            std::string list;
            for (std::string_view k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
            v.fail("unknown key '", item.key(), "' for a ", type, " material (allowed: ", list, ")");
        }
    }
}

fs::path textureFile(const JsonValue& v, const fs::path& folder) {
    return resolveExistingFile(folder, v, "texture file");
}

// A colour given as a number, [r, g, b], or {"texture": file, "scale": colour}.
void parseTexturedColor(const JsonValue& v, const fs::path& folder, TexturedColor& out,
                        fs::path& texture) {
    if (v.raw().is_object()) {
        v.requireKeys({"texture", "scale"});
        texture = textureFile(v.get("texture"), folder);
        out.value = Color(1.0f);
        if (auto scale = v.find("scale")) out.value = scale->color();
        return;
    }
    out.value = v.color();
}

// A scalar in [lo, hi] given as a number or {"texture": file, "channel": "g", "scale": x}.
void parseTexturedFloat(const JsonValue& v, const fs::path& folder, float lo, float hi,
                        TexturedFloat& out, fs::path& texture) {
    if (v.raw().is_object()) {
        v.requireKeys({"texture", "channel", "scale"});
        texture = textureFile(v.get("texture"), folder);
        out.value = 1.0f;
        if (auto scale = v.find("scale")) out.value = scale->numberIn(lo, hi);
        if (auto channel = v.find("channel")) {
            const std::string c = channel->oneOf({"r", "g", "b", "a"});
            out.channel = c == "r" ? 0 : c == "g" ? 1 : c == "b" ? 2 : 3;
        }
        return;
    }
    out.value = v.numberIn(lo, hi);
}

TextureMapping parseMapping(const JsonValue& v) {
    TextureMapping mapping;
    if (!v.raw().is_object()) {
        mapping.kind = v.oneOf({"uv", "triplanar"}) == "uv" ? TextureMapping::Kind::UV
                                                            : TextureMapping::Kind::Triplanar;
        return mapping;
    }
    v.requireKeys({"type", "scale", "sharpness"});
    mapping.kind = v.get("type").oneOf({"uv", "triplanar"}) == "uv"
                       ? TextureMapping::Kind::UV
                       : TextureMapping::Kind::Triplanar;
    if (auto scale = v.find("scale")) {
        mapping.scale = scale->number();
        if (!(mapping.scale > 0.0f)) scale->fail("must be positive, got ", mapping.scale);
    }
    // Beyond 64 the blend is a hard switch between projections anyway.
    if (auto sharpness = v.find("sharpness")) mapping.sharpness = sharpness->numberIn(1.0f, 64.0f);
    return mapping;
}

MaterialDesc parseMaterial(const JsonValue& m, const fs::path& folder) {
    if (!m.raw().is_object()) m.fail("expected an object, got ", m.describe());
    MaterialDesc desc;
    desc.where = m.pointer();
    Material& mat = desc.material;
    const std::string typeName =
        m.has("type") ? m.get("type").oneOf(kTypes) : std::string("diffuse");
    mat.type = typeFromName(typeName);
    requireKeys(m, typeName, allowedKeys(mat.type));
    MaterialTextures& tex = desc.textures;

    // "diffuse" is the older name of a diffuse material's colour.
    if (m.has("color") && m.has("diffuse")) m.fail("give either 'color' or 'diffuse', not both");
    if (auto color = m.find("color")) parseTexturedColor(*color, folder, mat.color, tex.color);
    if (auto color = m.find("diffuse")) parseTexturedColor(*color, folder, mat.color, tex.color);
    if (mat.type == Material::Type::Dielectric && !m.has("color")) mat.color.value = Color(1.0f);
    if (mat.type == Material::Type::MetallicRoughness && !m.has("color"))
        mat.color.value = Color(1.0f);
    if (auto specular = m.find("specular")) mat.specular = specular->color();
    if (mat.type == Material::Type::Phong || mat.type == Material::Type::BlinnPhong) {
        if (!m.has("specular")) mat.specular = Color(0.2f);
        // Energy conservation of the (Blinn-)Phong sum needs kd + ks <= 1.
        const Color sum = mat.color.value + mat.specular;
        if (maxComponent(sum) > 1.0f)
            m.fail("color + specular must not exceed 1 in any channel (energy conservation), got (",
                   sum.x, ", ", sum.y, ", ", sum.z, ")");
        // 10^4 is a mirror-like lobe; beyond it use a conductor.
        if (auto exponent = m.find("exponent")) mat.exponent = exponent->numberIn(0.0f, 1e4f);
    }
    if (mat.type == Material::Type::Conductor) {
        const bool preset = m.has("metal");
        if (preset && (m.has("eta") || m.has("k")))
            m.fail("give either 'metal' or 'eta' and 'k', not both");
        if (preset) {
            const JsonValue metal = m.get("metal");
            const std::optional<MetalPreset> found = findMetalPreset(metal.string());
            if (!found) {
                std::string names;
                for (const MetalPreset& p : metalPresets())
                    names += (names.empty() ? "" : ", ") + std::string(p.name);
                metal.fail("unknown metal '", metal.string(), "' (known: ", names, ")");
            }
            mat.eta = found->eta;
            mat.k = found->k;
        } else {
            // Without a preset: a perfect-ish mirror of aluminium unless given.
            const MetalPreset aluminium = *findMetalPreset("aluminium");
            mat.eta = aluminium.eta;
            mat.k = aluminium.k;
            if (auto eta = m.find("eta")) mat.eta = eta->color();
            if (auto k = m.find("k")) mat.k = k->color();
        }
    }
    if (auto ior = m.find("ior")) {
        // Below 1.0001 the interface vanishes; above 4 no common material.
        mat.ior = ior->numberIn(1.0001f, 4.0f);
    }
    if (auto roughness = m.find("roughness"))
        parseTexturedFloat(*roughness, folder, 0.0f, 1.0f, mat.roughness, tex.roughness);
    if (mat.type == Material::Type::MetallicRoughness) {
        mat.metallic.value = 1.0f;
        if (auto metallic = m.find("metallic"))
            parseTexturedFloat(*metallic, folder, 0.0f, 1.0f, mat.metallic, tex.metallic);
        if (!m.has("roughness")) mat.roughness.value = 1.0f;  // glTF's default
    }
    if (auto emission = m.find("emission"))
        parseTexturedColor(*emission, folder, mat.emission, tex.emission);
    if (mat.type == Material::Type::Emissive && !m.has("emission"))
        m.fail("an emissive material needs 'emission'");
    if (auto twoSided = m.find("two_sided")) mat.twoSidedEmission = twoSided->boolean();
    if (auto normal = m.find("normal_map")) tex.normal = textureFile(*normal, folder);
    if (auto mapping = m.find("mapping")) mat.mapping = parseMapping(*mapping);
    return desc;
}

}  // namespace

std::vector<MaterialDesc> parseMaterials(const JsonValue& v, const fs::path& folder) {
    std::vector<MaterialDesc> materials;
    for (size_t i = 0; i < v.size(); ++i) {
        const JsonValue m = v.at(i);
        MaterialDesc desc = parseMaterial(m, folder);
        const JsonValue name = m.get("name");
        desc.name = name.string();
        if (desc.name.empty()) name.fail("must not be empty");
        if (desc.name == "default")
            name.fail("'default' is reserved for the built-in grey material");
        for (const MaterialDesc& earlier : materials) {
            if (earlier.name == desc.name)
                name.fail("material '", desc.name, "' is already defined at ", earlier.where);
        }
        desc.material.name = desc.name;
        materials.push_back(std::move(desc));
    }
    return materials;
}

}  // namespace strahl::scene_detail
