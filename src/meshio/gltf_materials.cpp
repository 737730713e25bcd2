// Materials: glTF's metallic-roughness materials and the material extensions
// strahl reads, as MeshMaterials (their textures: gltf_images.cpp).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "gltf_reader.h"

namespace strahl::meshio::gltf {

MeshMaterial GltfReader::gltfDefaults() {
    MeshMaterial m;
    m.source = MeshMaterial::Source::Gltf;
    m.diffuse = Color(1.0f);  // baseColorFactor defaults to white
    return m;
}

// A number from a material extension object, or `fallback` when absent.
double GltfReader::extensionNumber(const tinygltf::ExtensionMap& extensions, const char* extension,
                                   const char* key, double fallback,
                                   const std::string& place) const {
    const auto it = extensions.find(extension);
    if (it == extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return fallback;
    const tinygltf::Value& v = it->second.Get(key);
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble()))
        error(place, extension, ".", key, " is not a finite number");
    return v.GetNumberAsDouble();
}

float GltfReader::factor(double value, const std::string& place, const char* what) {
    if (!std::isfinite(value)) error(place, what, " is not a finite number");
    if (value < 0.0 || value > 1.0)
        meshio::warn(concat(name_, ": ", place, what, " ", value, " is outside [0, 1]; clamped"));
    return static_cast<float>(std::clamp(value, 0.0, 1.0));
}

Color GltfReader::color(const std::vector<double>& values, size_t expected,
                        const std::string& place, const char* what) const {
    if (values.size() != expected)
        error(place, what, " has ", values.size(), " numbers, expected ", expected);
    for (double v : values) {
        if (!std::isfinite(v)) error(place, what, " is not finite");
    }
    return Color(float(values[0]), float(values[1]), float(values[2]));
}

void GltfReader::convertMaterials(std::vector<MeshMaterial>& out) {
    out.reserve(model_.materials.size() + 1);  // +1: the default material, if used
    for (size_t i = 0; i < model_.materials.size(); ++i) {
        const tinygltf::Material& g = model_.materials[i];
        const std::string place = concat("materials[", i, "].");
        const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
        MeshMaterial m = gltfDefaults();
        m.name = g.name;
        m.diffuse = color(pbr.baseColorFactor, 4, place, "pbrMetallicRoughness.baseColorFactor");
        // Alpha (glTF 2.0 3.9.4): OPAQUE ignores it; MASK cuts out where the
        // base colour's alpha (factor times texture) is below alphaCutoff;
        // BLEND is rendered as a stochastic opacity.
        if (g.alphaMode == "MASK" || g.alphaMode == "BLEND") {
            m.dissolve = factor(pbr.baseColorFactor[3], place, "baseColorFactor alpha");
            m.opacityTexture = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                       place + "pbrMetallicRoughness.baseColorTexture");
        }
        if (g.alphaMode == "MASK") {
            if (!(g.alphaCutoff >= 0.0 && g.alphaCutoff <= 1.0))
                error(place, "alphaCutoff ", g.alphaCutoff, " is not in [0, 1]");
            m.opacityCutoff = float(g.alphaCutoff);
        }
        m.metallic = factor(pbr.metallicFactor, place, "pbrMetallicRoughness.metallicFactor");
        m.roughness = factor(pbr.roughnessFactor, place, "pbrMetallicRoughness.roughnessFactor");
        const double strength = extensionNumber(g.extensions, "KHR_materials_emissive_strength",
                                                "emissiveStrength", 1.0, place + "extensions.");
        if (strength < 0.0)
            error(place, "extensions.KHR_materials_emissive_strength.emissiveStrength ", strength,
                  " is negative");
        m.emission = color(g.emissiveFactor, 3, place, "emissiveFactor") * float(strength);
        const double ior =
            extensionNumber(g.extensions, "KHR_materials_ior", "ior", 1.5, place + "extensions.");
        if (ior >= 1.0)
            m.ior = float(ior);
        else
            meshio::warn(concat(name_, ": ", place, "extensions.KHR_materials_ior.ior ", ior,
                                " is less than 1; using 1.5"));
        m.transmission =
            Color(factor(extensionNumber(g.extensions, "KHR_materials_transmission",
                                         "transmissionFactor", 0.0, place + "extensions."),
                         place, "extensions.KHR_materials_transmission.transmissionFactor"));

        m.diffuseTexture = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                   place + "pbrMetallicRoughness.baseColorTexture");
        m.metallicRoughnessTexture =
            texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                    place + "pbrMetallicRoughness.metallicRoughnessTexture");
        m.normalTexture =
            texture(g.normalTexture.index, g.normalTexture.texCoord, place + "normalTexture");
        if (!m.normalTexture.empty() && g.normalTexture.scale != 1.0)
            warnOnce("normal scale", "normalTexture.scale is ignored (taken as 1)");
        m.emissionTexture =
            texture(g.emissiveTexture.index, g.emissiveTexture.texCoord, place + "emissiveTexture");
        const auto transmission = g.extensions.find("KHR_materials_transmission");
        if (transmission != g.extensions.end() && transmission->second.Has("transmissionTexture"))
            warnOnce("transmission texture", "transmissionTexture is ignored");
        if (g.alphaMode != "OPAQUE" && (maxComponent(m.emission) > 0.0f || !m.emissionTexture.empty())) {
            warnOnce("emissive alpha", "the alpha of emitting materials is ignored (cut-out "
                                       "emitters are not supported)");
            m.dissolve = 1.0f;
            m.opacityTexture.clear();
            m.opacityCutoff = -1.0f;
        }
        out.push_back(std::move(m));
    }
}

}  // namespace strahl::meshio::gltf
