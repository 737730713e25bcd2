#pragma once
// The inputs of a material that may vary over the surface: a constant,
// optionally multiplied by a texture; and MaterialPoint, which evaluates them
// at one shading point. The material kinds (material_kinds.h) build their BSDF
// from these.

#include <filesystem>
#include <memory>
#include <optional>

#include "strahl/core/math.h"
#include "strahl/geometry/surface_interaction.h"
#include "strahl/texture/texture_system.h"

namespace strahl {

// A texture a material uses: the file the scene names (set when the scene is
// parsed) and its handle in the texture system (set when the world is built),
// with how it is sampled and where it is placed. Colour and scalar inputs may
// instead read a mesh attribute by name (no file; the world checks that every
// mesh with the material has it).
struct TextureRef {
    std::filesystem::path file;
    std::string meshAttribute;
    TextureHandle handle;
    TextureSampling sampling;  // wrap and filter (texture_system.h)
    // An affine map of the image coordinates (s, t) = (u, 1 − v) applied
    // before the lookup (uv mapping only): (s', t', 1) = stTransform (s, t, 1).
    Mat3 stTransform{1.0f};
    // Whether an 8-bit image is read as stored (true) or sRGB-decoded
    // (false); unset, the input decides: colours are decoded, scalars and
    // maps are data.
    std::optional<bool> raw;

    bool valid() const { return handle.valid(); }
    // Whether the value varies over the surface (an image or an attribute).
    bool varies() const { return valid() || !file.empty() || !meshAttribute.empty(); }
};

// A procedural checkerboard (Mitsuba's `checkerboard`): in the texture
// coordinates of image textures, (s, t) = (u, 1 − v) scaled by `scale`, a
// point is color0 where frac(s) and frac(t) are both above 1/2 or both not,
// color1 elsewhere; so `scale` (n, n) gives n × n squares over [0, 1]².
// Evaluated at the point, unfiltered.
struct Checkerboard {
    Color color0{0.4f}, color1{0.2f};
    Vec2 scale{1.0f};
    Color at(Vec2 uv) const;
};

// Owns one node of a texture graph (a mix) and copies it deeply, so that
// copies of a material never share the nodes whose texture handles the world
// sets. Empty by default.
template <typename Node>
class NodeBox {
public:
    NodeBox() = default;
    explicit NodeBox(Node node) : node_(std::make_unique<Node>(std::move(node))) {}
    NodeBox(const NodeBox& other) : node_(other.node_ ? std::make_unique<Node>(*other.node_) : nullptr) {}
    NodeBox& operator=(const NodeBox& other) {
        if (this != &other) node_ = other.node_ ? std::make_unique<Node>(*other.node_) : nullptr;
        return *this;
    }
    NodeBox(NodeBox&&) noexcept = default;
    NodeBox& operator=(NodeBox&&) noexcept = default;
    ~NodeBox() = default;

    explicit operator bool() const { return node_ != nullptr; }
    Node& operator*() { return *node_; }
    const Node& operator*() const { return *node_; }
    Node* operator->() { return node_.get(); }
    const Node* operator->() const { return node_.get(); }

private:
    std::unique_ptr<Node> node_;
};

struct ColorMix;
struct FloatMix;

// A colour, optionally multiplied by a texture's RGB (an image's or a mesh
// attribute's), a checkerboard, or a mix of two colour inputs; one of the three.
struct TexturedColor {
    Color value{1.0f};
    TextureRef texture;
    std::optional<Checkerboard> checkerboard = std::nullopt;  // exclusive with texture
    NodeBox<ColorMix> mix = {};                               // exclusive with both

    // Whether the value varies over the surface.
    bool varies() const;
};

// A scalar, optionally multiplied by one channel of a texture (an image's or
// a mesh attribute's), by a checkerboard of numbers or by a mix of two scalar
// inputs.
struct TexturedFloat {
    float value = 0.0f;
    TextureRef texture;
    int channel = 0;  // 0 R, 1 G, 2 B, 3 A
    // Exclusive with texture: a checkerboard of two numbers (its colours grey).
    std::optional<Checkerboard> checkerboard = std::nullopt;
    NodeBox<FloatMix> mix = {};  // exclusive with texture and checkerboard

    // Whether the value varies over the surface.
    bool varies() const;
};

// (1 − amount) a + amount b at each point (pbrt's "mix" texture): two inputs
// blended by a third, each constant or textured, mixes included.
struct ColorMix {
    TexturedColor a, b;
    TexturedFloat amount{0.5f, {}, 0};
};
struct FloatMix {
    TexturedFloat a, b;
    TexturedFloat amount{0.5f, {}, 0};
};

inline bool TexturedColor::varies() const {
    return texture.varies() || checkerboard.has_value() ||
           (mix && (mix->a.varies() || mix->b.varies() || mix->amount.varies()));
}
inline bool TexturedFloat::varies() const {
    return texture.varies() || checkerboard.has_value() ||
           (mix && (mix->a.varies() || mix->b.varies() || mix->amount.varies()));
}

// Calls fn(TextureRef&, encoding) for the texture of `input` (a
// TexturedColor or TexturedFloat, const or not) and for every texture of its
// mix, depth first; a mix's amount is data.
template <typename Input, typename Fn>
void visitTextures(Input& input, TextureEncoding encoding, Fn&& fn) {
    fn(input.texture, encoding);
    if (!input.mix) return;
    visitTextures(input.mix->a, encoding, fn);
    visitTextures(input.mix->b, encoding, fn);
    visitTextures(input.mix->amount, TextureEncoding::Data, fn);
}

// How a texture is placed on the surface.
struct TextureMapping {
    enum class Kind { UV, Triplanar };
    Kind kind = Kind::UV;
    float scale = 1.0f;      // triplanar: texture repeats per world unit
    float sharpness = 4.0f;  // triplanar: blend exponent on |n|
};

// What a material needs to know about the shading point.
struct ShadingPoint {
    Vec3 p{0.0f};      // world space (triplanar)
    Vec3 n{0.0f};      // shading normal (triplanar blend, normal-map frame)
    Vec3 dpdu{0.0f};   // tangent along u (normal maps, anisotropy); zero if unknown
    Vec3 dpdv{0.0f};   // tangent along v (bump maps); zero if unknown
    Vec2 uv{0.0f};     // texture coordinates, v up
    float footprint = 0.0f;  // ray footprint width in uv units (texture filtering)
    // The hit mesh's attributes (mesh_attribute.h), owned by the interaction; null without.
    const MeshAttributePoint* attributes = nullptr;
};

// The shading point of an interaction, with a footprint in world units
// (converted to uv units by the interaction's uv density); it refers to the
// interaction's attributes, so the interaction must outlive it.
ShadingPoint shadingPointAt(const SurfaceInteraction& si, float footprint = 0.0f);

// `texture` at image coordinates st = (u, 1 − v), before its stTransform,
// through its sampling; footprint in st units (scaled by the transform).
Vec4 lookupTexture(const TextureRef& texture, Vec2 st, float footprint,
                   const TextureSystem& textures);

// Texture lookups of one material at one point. `textures` may be null when
// the material has no textures.
Color evaluateColor(const TexturedColor& c, const TextureMapping& mapping,
                    const ShadingPoint& sp, const TextureSystem* textures);
float evaluateFloat(const TexturedFloat& f, const TextureMapping& mapping,
                    const ShadingPoint& sp, const TextureSystem* textures);
// The encoded normal of a normal map at sp (RGB in [0, 1]).
Vec3 lookupNormalMap(const TextureRef& normalMap, const TextureMapping& mapping,
                     const ShadingPoint& sp, const TextureSystem& textures);

// One shading point of one material: what a material kind's bsdf() reads its
// textured inputs through.
struct MaterialPoint {
    const ShadingPoint& sp;
    const TextureMapping& mapping;
    const TextureSystem* textures;

    Color color(const TexturedColor& c) const { return evaluateColor(c, mapping, sp, textures); }
    float scalar(const TexturedFloat& f) const { return evaluateFloat(f, mapping, sp, textures); }
    // A reflectance for a BSDF factory: texture values may be HDR or corrupt,
    // and a render must not stop on one texel, so each channel is clamped to
    // [0, 1] and NaN becomes 0.
    Color reflectance(const TexturedColor& c) const;
    // A scalar clamped to [0, 1]; NaN becomes 0.
    float unit(const TexturedFloat& f) const;
    // GGX alpha from a perceptual roughness (clamped like unit(); a NaN texel
    // means smooth).
    float alpha(const TexturedFloat& roughness) const;
};

}  // namespace strahl
