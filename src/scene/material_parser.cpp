#include "material_parser.h"

#include <algorithm>
#include <array>
#include <memory>
#include <optional>
#include <span>

#include "strahl/core/closed_family.h"
#include "texture_parser.h"

namespace strahl::scene_detail {

namespace fs = std::filesystem;

namespace {

// The keys every material accepts; each kind adds its own (Kind::kKeys).
constexpr std::array<std::string_view, 9> kCommonKeys = {
    "name",    "type",    "emission",       "two_sided", "normal_map",
    "bump_map", "mapping", "opacity", "opacity_cutoff"};

// A material inside a blend has only its kind: what every material may have
// belongs on the blend.
constexpr std::array<std::string_view, 1> kNestedKeys = {"type"};

MaterialKind parseKind(const JsonValue& m, const fs::path& folder,
                       std::span<const std::string_view> commonKeys);

fs::path textureFile(const JsonValue& v, const fs::path& folder) {
    return resolveExistingFile(folder, v, "texture file");
}

// {"color0": c, "color1": c, "scale": s or [su, sv]} (textured.h, Checkerboard).
Checkerboard parseCheckerboard(const JsonValue& v) {
    v.requireKeys({"color0", "color1", "scale"});
    Checkerboard c;
    if (auto c0 = v.find("color0")) c.color0 = c0->color();
    if (auto c1 = v.find("color1")) c.color1 = c1->color();
    if (auto scale = v.find("scale")) {
        c.scale = scale->raw().is_array() ? scale->vec2() : Vec2(scale->number());
        if (!(c.scale.x > 0.0f && c.scale.y > 0.0f)) scale->fail("must be positive");
    }
    return c;
}

// {"attribute": name, ...}: a mesh attribute read as a texture (mesh_attribute.h).
// Its keys are `own` besides "attribute"; the name must not be empty.
void parseMeshAttribute(const JsonValue& v, std::initializer_list<std::string_view> own,
                        TextureRef& out) {
    for (const auto& item : v.raw().items()) {
        if (item.key() == "attribute" ||
            std::find(own.begin(), own.end(), item.key()) != own.end())
            continue;
        std::string allowed = "attribute";
        for (std::string_view k : own) allowed += ", " + std::string(k);
        v.get(item.key()).fail("not a key of a mesh attribute texture (allowed: ", allowed, ")");
    }
    out.meshAttribute = v.get("attribute").string();
    if (out.meshAttribute.empty()) v.get("attribute").fail("must name an attribute");
}

// Mixes nest (a mix of mixes); deeper than this is refused, so a hostile
// file cannot exhaust the stack of the recursive parse and evaluation.
constexpr int kMaxMixDepth = 16;

// The [a, b] of {"mix": [a, b], "amount": t, "scale": s}, whose keys it
// checks; `depth` counts the mixes around it.
JsonValue mixPair(const JsonValue& v, int depth) {
    for (const auto& item : v.raw().items())
        if (item.key() != "mix" && item.key() != "amount" && item.key() != "scale")
            v.get(item.key()).fail("not a key of a mix (allowed: mix, amount, scale)");
    if (depth >= kMaxMixDepth) v.fail("mixes nested deeper than ", kMaxMixDepth, " are not supported");
    const JsonValue pair = v.get("mix");
    if (!pair.raw().is_array() || pair.size() != 2)
        pair.fail("expected [a, b], the two inputs the amount blends, got ",
                  pair.raw().is_array() ? std::to_string(pair.size()) + " values" : pair.describe());
    return pair;
}

void parseTexturedFloat(const JsonValue& v, const fs::path& folder, float lo, float hi,
                        TexturedFloat& out, int depth = 0);

// A colour given as a number, [r, g, b], {"texture": file, "scale": colour,
// "raw": false, sampling keys}, {"attribute": name, "scale": colour}, {"checkerboard":
// {...}, "scale": colour} or {"mix": [a, b], "amount": t, "scale": colour}
// (a and b colours of any of these forms, t a scalar in [0, 1] of any form).
void parseTexturedColor(const JsonValue& v, const fs::path& folder, TexturedColor& out,
                        int depth = 0) {
    if (v.raw().is_object() && v.has("mix")) {
        const JsonValue pair = mixPair(v, depth);
        ColorMix mix;
        parseTexturedColor(pair.at(0), folder, mix.a, depth + 1);
        parseTexturedColor(pair.at(1), folder, mix.b, depth + 1);
        if (auto amount = v.find("amount")) parseTexturedFloat(*amount, folder, 0.0f, 1.0f, mix.amount, depth + 1);
        out.mix = NodeBox<ColorMix>(std::move(mix));
        out.value = Color(1.0f);
        if (auto scale = v.find("scale")) out.value = scale->color();
        return;
    }
    if (v.raw().is_object() && v.has("attribute")) {
        parseMeshAttribute(v, {"scale"}, out.texture);
        out.value = Color(1.0f);
        if (auto scale = v.find("scale")) out.value = scale->color();
        return;
    }
    if (v.raw().is_object()) {
        requireTextureKeys(v, {"texture", "checkerboard", "scale", "raw"});
        if (auto checker = v.find("checkerboard")) {
            if (v.has("texture")) v.fail("'texture' and 'checkerboard' are exclusive: give one");
            for (std::string_view key : kTextureSamplingKeys)
                if (v.has(key)) v.get(key).fail("applies to image textures, not to a checkerboard");
            if (v.has("raw")) v.get("raw").fail("applies to image textures, not to a checkerboard");
            out.checkerboard = parseCheckerboard(*checker);
            out.value = Color(1.0f);
            if (auto scale = v.find("scale")) out.value = scale->color();
            return;
        }
        out.texture.file = textureFile(v.get("texture"), folder);
        parseTextureSampling(v, out.texture);
        if (auto raw = v.find("raw")) out.texture.raw = raw->boolean();
        out.value = Color(1.0f);
        if (auto scale = v.find("scale")) out.value = scale->color();
        return;
    }
    out.value = v.color();
}

// A scalar in [lo, hi] given as a number, {"texture": file, "channel": "g",
// "scale": x, "raw": true, sampling keys}, {"attribute": name, "channel": "g", "scale": x},
// {"checkerboard": {"color0": x, "color1": y, "scale": s}, "scale": x} or
// {"mix": [a, b], "amount": t, "scale": x} (a and b scalars of any of these forms).
void parseTexturedFloat(const JsonValue& v, const fs::path& folder, float lo, float hi,
                        TexturedFloat& out, int depth) {
    if (v.raw().is_object() && v.has("mix")) {
        const JsonValue pair = mixPair(v, depth);
        FloatMix mix;
        parseTexturedFloat(pair.at(0), folder, lo, hi, mix.a, depth + 1);
        parseTexturedFloat(pair.at(1), folder, lo, hi, mix.b, depth + 1);
        if (auto amount = v.find("amount")) parseTexturedFloat(*amount, folder, 0.0f, 1.0f, mix.amount, depth + 1);
        out.mix = NodeBox<FloatMix>(std::move(mix));
        out.value = 1.0f;
        if (auto scale = v.find("scale")) out.value = scale->numberIn(lo, hi);
        return;
    }
    if (v.raw().is_object()) {
        if (v.has("attribute")) {
            parseMeshAttribute(v, {"channel", "scale"}, out.texture);
        } else if (auto checker = v.find("checkerboard")) {
            // Squares of two numbers: the scalar is the number, no channel.
            for (const auto& item : v.raw().items())
                if (item.key() != "checkerboard" && item.key() != "scale")
                    v.get(item.key()).fail("not a key of a checkerboard (allowed: checkerboard, scale)");
            for (const char* key : {"color0", "color1"})
                if (auto c = checker->find(key); c && !c->raw().is_number())
                    c->fail("a scalar checkerboard takes numbers, got ", c->describe());
            out.checkerboard = parseCheckerboard(*checker);
        } else {
            requireTextureKeys(v, {"texture", "channel", "scale", "raw"});
            out.texture.file = textureFile(v.get("texture"), folder);
            parseTextureSampling(v, out.texture);
            if (auto raw = v.find("raw")) out.texture.raw = raw->boolean();
        }
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

// What a material kind's parse() reads the material object through
// (strahl/material/kind_parsing.h lists the operations).
class MaterialReader {
public:
    MaterialReader(const JsonValue& material, const fs::path& folder)
        : material_(material), folder_(folder) {}

    bool has(std::string_view key) const { return material_.has(key); }
    std::optional<JsonValue> find(std::string_view key) const { return material_.find(key); }
    template <typename... Args>
    [[noreturn]] void fail(const Args&... args) const {
        material_.fail(args...);
    }
    // Sets `out` if the key is present.
    void texturedColor(std::string_view key, TexturedColor& out) const {
        if (auto v = material_.find(key)) parseTexturedColor(*v, folder_, out);
    }
    void texturedFloat(std::string_view key, float lo, float hi, TexturedFloat& out) const {
        if (auto v = material_.find(key)) parseTexturedFloat(*v, folder_, lo, hi, out);
    }
    // Two material objects of their kind's keys only (a blend's parts); required.
    void materialPair(std::string_view key, std::array<std::unique_ptr<MaterialKindBox>, 2>& out) const {
        const auto v = material_.find(key);
        if (!v) material_.fail("needs '", key, "': [first, second], two material objects");
        if (!v->raw().is_array())
            v->fail("expected [first, second], two material objects, got ", v->describe());
        if (v->size() != 2)
            v->fail("expected [first, second], two material objects, got ", v->size());
        for (size_t i = 0; i < 2; ++i)
            out[i] = std::make_unique<MaterialKindBox>(
                MaterialKindBox{parseKind(v->at(i), folder_, kNestedKeys)});
    }

private:
    const JsonValue& material_;
    const fs::path& folder_;
};

void requireKeys(const JsonValue& v, const std::string& type,
                 std::span<const std::string_view> commonKeys,
                 std::span<const std::string_view> kindKeys) {
    for (const auto& item : v.raw().items()) {
        const auto known = [&](std::span<const std::string_view> keys) {
            return std::find(keys.begin(), keys.end(), item.key()) != keys.end();
        };
        if (known(commonKeys) || known(kindKeys)) continue;
        std::string list;
        for (std::string_view k : commonKeys) list += (list.empty() ? "" : ", ") + std::string(k);
        for (std::string_view k : kindKeys) list += ", " + std::string(k);
        v.fail("unknown key '", item.key(), "' for a ", type, " material (allowed: ", list, ")");
    }
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

// The kind of material object m ("type", diffuse by default) with its keys;
// besides them m may have commonKeys.
MaterialKind parseKind(const JsonValue& m, const fs::path& folder,
                       std::span<const std::string_view> commonKeys) {
    if (!m.raw().is_object()) m.fail("expected an object, got ", m.describe());
    static constexpr auto kTypes = kindNames<MaterialKind>();
    const std::string typeName =
        m.has("type") ? m.get("type").oneOf(kTypes) : std::string(DiffuseMaterial::kName);
    const MaterialReader reader(m, folder);
    return *withKindNamed<MaterialKind>(typeName, [&](auto kind) -> MaterialKind {
        using Kind = typename decltype(kind)::type;
        requireKeys(m, typeName, commonKeys, Kind::kKeys);
        return Kind::parse(reader);
    });
}

MaterialDesc parseMaterial(const JsonValue& m, const fs::path& folder) {
    MaterialDesc desc;
    desc.where = m.pointer();
    Material& mat = desc.material;
    mat.kind = parseKind(m, folder, kCommonKeys);
    if (auto emission = m.find("emission")) parseTexturedColor(*emission, folder, mat.emission);
    if (auto twoSided = m.find("two_sided")) mat.twoSidedEmission = twoSided->boolean();
    if (auto normal = m.find("normal_map")) {
        // A file name, or {"texture": file, "shadowing": bool, sampling keys}.
        if (normal->raw().is_object()) {
            requireTextureKeys(*normal, {"texture", "shadowing"});
            mat.normalMap.file = textureFile(normal->get("texture"), folder);
            parseTextureSampling(*normal, mat.normalMap);
            if (auto shadowing = normal->find("shadowing"))
                mat.terminatorShadowing = shadowing->boolean();
        } else {
            mat.normalMap.file = textureFile(*normal, folder);
        }
    }
    if (auto bump = m.find("bump_map")) {
        // {"texture": file, "scale": 1, "shadowing": bool, sampling keys}.
        if (m.has("normal_map")) bump->fail("give either 'normal_map' or 'bump_map', not both");
        if (!bump->raw().is_object()) bump->fail("expected {\"texture\": file, \"scale\": ...}");
        requireTextureKeys(*bump, {"texture", "scale", "shadowing"});
        mat.bumpMap.file = textureFile(bump->get("texture"), folder);
        parseTextureSampling(*bump, mat.bumpMap);
        if (auto scale = bump->find("scale")) mat.bumpScale = scale->number();
        if (auto shadowing = bump->find("shadowing")) mat.terminatorShadowing = shadowing->boolean();
    }
    if (auto mapping = m.find("mapping")) mat.mapping = parseMapping(*mapping);
    if (mat.mapping.kind == TextureMapping::Kind::Triplanar && !mat.bumpMap.file.empty())
        m.get("bump_map").fail("a bump map is read through the uvs: it cannot be mapped triplanar");
    if (auto opacity = m.find("opacity")) {
        parseTexturedFloat(*opacity, folder, 0.0f, 1.0f, mat.opacity);
        if (mat.emits())
            opacity->fail("an emitting material cannot have an opacity (cut-out emitters are "
                          "not supported)");
        if (!mat.opacity.texture.meshAttribute.empty())
            opacity->fail("an opacity is read where rays are tested, through the uvs only: a "
                          "mesh attribute cannot be one");
        if (mat.opacity.mix)
            opacity->fail("an opacity is one image or a number: a mix cannot be one");
        if (mat.mapping.kind == TextureMapping::Kind::Triplanar && !mat.opacity.texture.file.empty())
            opacity->fail("an opacity texture is read through the uvs: it cannot be mapped "
                          "triplanar");
    }
    if (auto cutoff = m.find("opacity_cutoff")) {
        if (!m.has("opacity")) cutoff->fail("needs an 'opacity' to threshold");
        mat.opacityCutoff = cutoff->numberIn(0.0f, 1.0f);
    }
    if (mat.mapping.kind == TextureMapping::Kind::Triplanar)
        mat.forEachTexture([&](const TextureRef& texture, TextureEncoding) {
            if (texture.stTransform != Mat3(1.0f))
                m.get("mapping").fail("a triplanar mapping has no uv: a texture's uv_transform "
                                      "does not apply (remove it or map by uv)");
        });
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
