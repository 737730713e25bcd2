#pragma once
// Image textures through OpenImageIO's TextureSystem: mip-mapped, tiled and
// cached on demand, filtered by the footprint of the ray at the hit. The OIIO
// types stay in texture_system.cpp; the rest of strahl sees handles.
//
// Colour: 8-bit and 16-bit integer images registered as Color are taken as
// sRGB-encoded and decoded to linear; float images (EXR, HDR) and everything
// registered as Data (roughness, metallic, normal maps) are returned as
// stored. Details, and the approximation in the sRGB decoding: docs/textures.md.
//
// Channels: every lookup is RGBA. Grey images replicate their one channel into
// RGB, grey + alpha images likewise; images without alpha have alpha 1.
//
// Texture coordinates st follow OpenImageIO: s runs right and t runs DOWN the
// image ((0, 0) is the top-left corner of the top-left texel). Mesh UVs with v
// up must be passed as (u, 1 - v).
//
// Sampling (TextureSampling): outside [0, 1] the image repeats (default), is
// mirrored, or its edge texels extend. The default filter follows the ray's
// footprint through MIP levels (trilinear; sRGB decoded after filtering, the
// approximation docs/textures.md measures). "bilinear" and "nearest" read the
// full-resolution image at the point, without prefiltering, as Mitsuba's
// bitmap does: texel values decoded first, then interpolated between texel
// centres, exactly.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>

#include "strahl/core/math.h"
#include "strahl/texture/normal_map.h"  // applyNormalMap, for the materials

namespace strahl {

// GCC 12's -Wshadow takes the scoped enumerator Color for a shadow of the
// type strahl::Color (math.h); it is not one, as it is only ever named
// TextureEncoding::Color.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
enum class TextureEncoding { Color, Data };
#pragma GCC diagnostic pop

enum class TextureWrap { Repeat, Mirror, Clamp };
enum class TextureFilter { Footprint, Bilinear, Nearest };
struct TextureSampling {
    TextureWrap wrap = TextureWrap::Repeat;
    TextureFilter filter = TextureFilter::Footprint;
    bool operator==(const TextureSampling&) const = default;
};

struct TextureHandle {
    uint32_t index = 0xFFFFFFFFu;
    bool valid() const { return index != 0xFFFFFFFFu; }
};

class TextureSystem {
public:
    // cacheMegabytes bounds the tile cache (OIIO's max_memory_MB); it must be
    // positive and finite.
    explicit TextureSystem(float cacheMegabytes = 512.0f);
    ~TextureSystem();
    TextureSystem(const TextureSystem&) = delete;
    TextureSystem& operator=(const TextureSystem&) = delete;

    // Registers an image file, once per (file, encoding): the same file with
    // the same encoding, however spelled, returns the same handle. Throws
    // strahl::Error naming the file if it is missing, not a regular file, or
    // not an image OpenImageIO can read, so that the error comes before
    // rendering. Not thread-safe: register every texture before rendering.
    TextureHandle add(const std::filesystem::path& file, TextureEncoding encoding);

    // Filtered RGBA lookup at st (s right, t down; see above). footprint is
    // the width of the ray's footprint in st units: 0 is the finest level
    // (bilinear between texel centres, so a texel centre gives the texel's
    // exact value); 1 or more covers the whole image and gives its mean. The
    // bilinear and nearest filters ignore it. Thread-safe; throws
    // strahl::Error for an invalid handle or if OpenImageIO fails to read the
    // file.
    Vec4 lookup(TextureHandle texture, const Vec2& st, float footprint,
                const TextureSampling& sampling = {}) const;

    // The RGB of lookup(), from one lookup of at most three channels.
    Color lookupColor(TextureHandle texture, const Vec2& st, float footprint,
                      const TextureSampling& sampling = {}) const;

    // Channel `channel` (0 R, 1 G, 2 B, 3 A) of lookup(), from a one-channel
    // lookup: e.g. roughness from the G of a glTF metallic-roughness map.
    float lookupChannel(TextureHandle texture, int channel, const Vec2& st, float footprint,
                        const TextureSampling& sampling = {}) const;

    // A height field's value and slope at st: the luminance (Rec. 709; the
    // grey of a grey image) of the full-resolution image interpolated
    // bilinearly between texel centres, and its exact derivatives along s and
    // t, as (value, d/ds, d/dt). The nearest filter gives slope 0; the
    // footprint filter reads as bilinear. Bump maps read this.
    Vec3 lookupSlope(TextureHandle texture, const Vec2& st, const TextureSampling& sampling = {}) const;

    // Triplanar projection for surfaces without UVs (implicit surfaces): the
    // lookups at st = (p.y, p.z), (p.x, p.z) and (p.x, p.y), each times scale,
    // blended by |n.x|^sharpness, |n.y|^sharpness, |n.z|^sharpness normalised
    // to sum 1. footprint is in the projected st units (world width * scale).
    // The projections are not mirrored per side: on faces looking down -x,
    // -y or -z the image appears mirrored.
    Vec4 triplanar(TextureHandle texture, const Vec3& p, const Vec3& n, float scale,
                   float sharpness, float footprint, const TextureSampling& sampling = {}) const;

    // Width and height of the full-resolution image, in texels.
    glm::ivec2 resolution(TextureHandle texture) const;

    size_t textureCount() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace strahl
