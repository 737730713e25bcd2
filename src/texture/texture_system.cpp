// Image textures through a private OpenImageIO TextureSystem (see
// texture_system.h and docs/textures.md).

#include "strahl/core/srgb.h"
#include "strahl/texture/texture_system.h"

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>
#include <OpenImageIO/ustring.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "strahl/core/error.h"

namespace fs = std::filesystem;

namespace strahl {

namespace {

using OiioSystem = OIIO::TextureSystem;

// Emulated tile size for scanline images (PNG, JPEG, most TIFFs): OIIO's
// recommended 64 x 64, a few KiB to 64 KiB per tile, instead of caching each
// such image as one tile of its whole resolution.
constexpr int kAutotile = 64;

// A footprint of one period covers the whole image, which is the 1 x 1 top of
// the MIP pyramid; larger (or infinite) ones change nothing, so they are
// clamped before OIIO turns them into texel counts.
constexpr float kMaxFootprint = 1.0f;

// Triplanar projections whose normalised weight is below this are skipped and
// the others renormalised: at most 0.1% of the texture's range is lost, and an
// axis-aligned face costs one lookup instead of three.
constexpr float kMinTriplanarWeight = 1e-3f;

// OIIO's messages may span lines and end in a newline; keep them on one line.
std::string oneLine(std::string message) {
    for (char& c : message)
        if (c == '\n' || c == '\r') c = ' ';
    while (!message.empty() && message.back() == ' ') message.pop_back();
    return message.empty() ? std::string("unknown error") : message;
}

// Texture coordinates into [0, 1]: the same texels under periodic wrapping,
// and no float-to-int overflow inside OIIO for huge coordinates. Non-finite
// coordinates look up st = 0.
float wrapPeriodic(float x) { return std::isfinite(x) ? x - std::floor(x) : 0.0f; }

// NaN and negative footprints are 0 (the finest level).
float clampFootprint(float footprint) {
    return footprint > 0.0f ? std::min(footprint, kMaxFootprint) : 0.0f;
}

bool isSrgbFormat(OIIO::TypeDesc format) {
    switch (format.basetype) {
        case OIIO::TypeDesc::UINT8:
        case OIIO::TypeDesc::INT8:
        case OIIO::TypeDesc::UINT16:
        case OIIO::TypeDesc::INT16:
            return true;
        default:
            return false;
    }
}

void setAttribute(OiioSystem& system, const char* name, int value) {
    if (!system.attribute(name, value))
        fail("OpenImageIO rejected the texture option ", name, " = ", value);
}

void setAttribute(OiioSystem& system, const char* name, float value) {
    if (!system.attribute(name, value))
        fail("OpenImageIO rejected the texture option ", name, " = ", value);
}

}  // namespace

// Not in the anonymous namespace: TextureSystem::Impl, which has external
// linkage, holds Entry values (GCC's -Wsubobject-linkage flags that when the
// file is compiled as part of a unity source).
namespace texture_detail {

// One registered (file, encoding). Stored channels: 1 grey, 2 grey + alpha,
// 3 RGB, 4 or more RGBA followed by channels strahl does not use.
struct Entry {
    OiioSystem::TextureHandle* handle = nullptr;
    std::string file;  // as the caller spelled it, for messages
    int channels = 0;  // stored channels used, 1 to 4
    int width = 0, height = 0;  // full resolution, texels
    bool srgb = false;  // decode the colour channels from sRGB

    bool grey() const { return channels <= 2; }
    // Whether stored channel `stored` holds colour (decoded from sRGB) rather
    // than alpha.
    bool colourChannel(int stored) const { return grey() ? stored == 0 : stored < 3; }
    // The stored channel of RGBA channel c (0 to 3), or -1 for alpha without
    // an alpha channel.
    int storedChannel(int c) const {
        if (c < 3) return grey() ? 0 : c;
        return channels == 2 ? 1 : channels == 4 ? 3 : -1;
    }
};

}  // namespace texture_detail

using texture_detail::Entry;

struct TextureSystem::Impl {
    OiioSystem* system = nullptr;
    uint64_t id = 0;  // unique in the process, never reused
    std::vector<Entry> entries;
    std::map<std::pair<std::string, TextureEncoding>, uint32_t> index;

    Impl() {
        static std::atomic<uint64_t> counter{0};
        id = counter.fetch_add(1) + 1;
    }
    ~Impl() {
        // teardown_imagecache: without it OIIO 2.4 deletes the TextureSystem
        // but not the private ImageCache create(false) made for it, which
        // keeps its tiles, open files and per-thread records for ever.
        if (system) OiioSystem::destroy(system, /*teardown_imagecache=*/true);
    }

    // The calling thread's OIIO per-thread record for this system, fetched
    // once per thread and then kept in a thread-local slot. The slot names its
    // system by id, not address: a new system may reuse a destroyed one's.
    OiioSystem::Perthread* perthread() const {
        thread_local uint64_t owner = 0;
        thread_local OiioSystem::Perthread* info = nullptr;
        if (owner != id) {
            info = system->get_perthread_info();
            owner = id;
        }
        return info;
    }

    const Entry& entry(TextureHandle texture) const {
        if (texture.index >= entries.size())
            fail("invalid texture handle ", texture.index, " (", entries.size(),
                 " textures registered)");
        return entries[texture.index];
    }

    // `count` stored channels from `first` on, filtered as `sampling` says
    // and decoded (colour channels of sRGB images), into out[0..count-1].
    void filter(const Entry& e, int first, int count, const Vec2& st, float footprint,
                const TextureSampling& sampling, float* out) const {
        if (sampling.filter == TextureFilter::Footprint) {
            OIIO::TextureOpt opt = options(first, sampling.wrap);
            // Isotropic footprint: two MIP levels, bilinear within each.
            // Bilinear (not OIIO's default bicubic B-spline, which blurs) so a
            // texel centre at footprint 0 returns the texel.
            opt.mipmode = OIIO::TextureOpt::MipModeTrilinear;
            opt.interpmode = OIIO::TextureOpt::InterpBilinear;
            const float width = clampFootprint(footprint);
            read(e, opt, wrapToUnit(st, sampling.wrap), width, count, out);
            decode(e, first, count, out);
            return;
        }
        // Texel space: texel (i, j) covers [i, i + 1) x [j, j + 1), its value
        // at its centre. The coordinates are first brought near [0, 1] by a
        // whole number of the wrap's periods, so that indices stay exact.
        const float x = reduce(st.x, sampling.wrap) * static_cast<float>(e.width);
        const float y = reduce(st.y, sampling.wrap) * static_cast<float>(e.height);
        if (sampling.filter == TextureFilter::Nearest) {
            texel(e, first, count, wrapIndex(std::floor(x), e.width, sampling.wrap),
                  wrapIndex(std::floor(y), e.height, sampling.wrap), out);
            return;
        }
        const Quad q = quad(e, first, count, x, y, sampling.wrap);
        for (int c = 0; c < count; ++c)
            out[c] = (1.0f - q.fy) * ((1.0f - q.fx) * q.v00[c] + q.fx * q.v10[c]) +
                     q.fy * ((1.0f - q.fx) * q.v01[c] + q.fx * q.v11[c]);
    }

    // The four texels around texel-space point (x, y) (texel (i, j) centred
    // at (i + 1/2, j + 1/2)) and the bilinear weights fx, fy between them.
    struct Quad {
        float v00[4], v10[4], v01[4], v11[4];
        float fx, fy;
    };
    Quad quad(const Entry& e, int first, int count, float x, float y, TextureWrap wrap) const {
        Quad q;
        const float x0 = std::floor(x - 0.5f), y0 = std::floor(y - 0.5f);
        q.fx = x - 0.5f - x0;
        q.fy = y - 0.5f - y0;
        const int i0 = wrapIndex(x0, e.width, wrap), i1 = wrapIndex(x0 + 1.0f, e.width, wrap);
        const int j0 = wrapIndex(y0, e.height, wrap), j1 = wrapIndex(y0 + 1.0f, e.height, wrap);
        texel(e, first, count, i0, j0, q.v00);
        texel(e, first, count, i1, j0, q.v10);
        texel(e, first, count, i0, j1, q.v01);
        texel(e, first, count, i1, j1, q.v11);
        return q;
    }

    // lookupSlope: see texture_system.h. The bilinear interpolant's partial
    // derivatives are exact: d/dx = (1 - fy)(v10 - v00) + fy (v11 - v01) per
    // texel, times the resolution for d/ds (x = s * width; the wrap only
    // reindexes texels, so it does not change the sign).
    Vec3 slope(const Entry& e, const Vec2& st, const TextureSampling& sampling) const {
        const float x = reduce(st.x, sampling.wrap) * static_cast<float>(e.width);
        const float y = reduce(st.y, sampling.wrap) * static_cast<float>(e.height);
        const int count = e.grey() ? 1 : 3;
        const auto height = [&](const float* v) {
            return count == 1 ? v[0] : 0.2126f * v[0] + 0.7152f * v[1] + 0.0722f * v[2];
        };
        if (sampling.filter == TextureFilter::Nearest) {
            float v[4];
            texel(e, 0, count, wrapIndex(std::floor(x), e.width, sampling.wrap),
                  wrapIndex(std::floor(y), e.height, sampling.wrap), v);
            return Vec3(height(v), 0.0f, 0.0f);
        }
        const Quad q = quad(e, 0, count, x, y, sampling.wrap);
        const float h00 = height(q.v00), h10 = height(q.v10), h01 = height(q.v01), h11 = height(q.v11);
        const float value = (1.0f - q.fy) * ((1.0f - q.fx) * h00 + q.fx * h10) +
                            q.fy * ((1.0f - q.fx) * h01 + q.fx * h11);
        const float dx = (1.0f - q.fy) * (h10 - h00) + q.fy * (h11 - h01);
        const float dy = (1.0f - q.fx) * (h01 - h00) + q.fx * (h11 - h10);
        return Vec3(value, dx * static_cast<float>(e.width), dy * static_cast<float>(e.height));
    }

private:
    static OIIO::TextureOpt options(int first, TextureWrap wrap) {
        OIIO::TextureOpt opt;
        opt.firstchannel = first;
        // wrapToUnit first brings st within a period of [0, 1] (exact for
        // huge coordinates); OIIO wraps what is left.
        const auto mode = wrap == TextureWrap::Mirror  ? OIIO::TextureOpt::WrapMirror
                          : wrap == TextureWrap::Clamp ? OIIO::TextureOpt::WrapClamp
                                                       : OIIO::TextureOpt::WrapPeriodic;
        opt.swrap = opt.twrap = mode;
        return opt;
    }

    static float finiteOrZero(float x) { return std::isfinite(x) ? x : 0.0f; }

    // x moved by whole periods of the wrap (1 for repeat, 2 for mirror) into
    // [0, period), or clamped to [-1, 2] (clamp: beyond, nothing changes);
    // non-finite x is 0. Keeps texel-space values small for any resolution.
    static float reduce(float x, TextureWrap wrap) {
        x = finiteOrZero(x);
        switch (wrap) {
            case TextureWrap::Mirror: return x - 2.0f * std::floor(0.5f * x);
            case TextureWrap::Clamp: return std::clamp(x, -1.0f, 2.0f);
            case TextureWrap::Repeat:
            default: return wrapPeriodic(x);
        }
    }

    static Vec2 wrapToUnit(const Vec2& st, TextureWrap wrap) {
        return Vec2(reduce(st.x, wrap), reduce(st.y, wrap));
    }

    // The texel index along an axis of n texels for texel-space coordinate
    // floor value `i` (Mitsuba's wrap modes): repeat is i mod n; mirror
    // reflects every other copy (..., 1, 0 | 0, 1, ..., n-1 | n-1, ...);
    // clamp takes the edge texel.
    static int wrapIndex(float i, int n, TextureWrap wrap) {
        const int k = static_cast<int>(i);  // small: see reduce()
        int index = k;
        if (wrap == TextureWrap::Mirror) {
            const int m = ((k % (2 * n)) + 2 * n) % (2 * n);  // [0, 2n)
            index = m < n ? m : 2 * n - 1 - m;
        } else if (wrap == TextureWrap::Repeat) {
            index = ((k % n) + n) % n;
        }
        return std::clamp(index, 0, n - 1);  // clamp, and float rounding at the edges
    }

    // Texel (i, j) of the full-resolution image, decoded.
    void texel(const Entry& e, int first, int count, int i, int j, float* out) const {
        OIIO::TextureOpt opt = options(first, TextureWrap::Repeat);
        opt.mipmode = OIIO::TextureOpt::MipModeNoMIP;
        opt.interpmode = OIIO::TextureOpt::InterpClosest;
        const Vec2 centre((static_cast<float>(i) + 0.5f) / static_cast<float>(e.width),
                          (static_cast<float>(j) + 0.5f) / static_cast<float>(e.height));
        read(e, opt, centre, 0.0f, count, out);
        decode(e, first, count, out);
    }

    void read(const Entry& e, OIIO::TextureOpt& opt, const Vec2& st, float width, int count,
              float* out) const {
        if (!system->texture(e.handle, perthread(), opt, st.x, st.y, width, 0.0f, 0.0f, width,
                             count, out))
            fail(e.file, ": texture lookup failed: ", oneLine(system->geterror()));
    }

    static void decode(const Entry& e, int first, int count, float* values) {
        if (!e.srgb) return;
        for (int c = 0; c < count; ++c)
            if (e.colourChannel(first + c)) values[c] = srgbToLinear(values[c]);
    }
};

TextureSystem::TextureSystem(float cacheMegabytes) : impl_(std::make_unique<Impl>()) {
    if (!(cacheMegabytes > 0.0f) || !std::isfinite(cacheMegabytes))
        fail("the texture cache size must be a positive number of megabytes, not ",
             cacheMegabytes);
    // Private (not shared): its own ImageCache, sized and configured here.
    impl_->system = OiioSystem::create(false);
    if (!impl_->system) fail("cannot create an OpenImageIO texture system: ", OIIO::geterror());
    OiioSystem& system = *impl_->system;
    setAttribute(system, "max_memory_MB", cacheMegabytes);
    setAttribute(system, "automip", 1);  // MIP levels on the fly for JPEG, PNG, ...
    setAttribute(system, "autotile", kAutotile);
    // Values as stored: colour channels not multiplied by alpha (PNG, TIFF).
    setAttribute(system, "unassociatedalpha", 1);
}

TextureSystem::~TextureSystem() = default;

TextureHandle TextureSystem::add(const fs::path& file, TextureEncoding encoding) {
    const std::string name = file.string();
    std::error_code ec;
    if (!fs::exists(file, ec)) fail(name, ": cannot read the texture: no such file");
    if (!fs::is_regular_file(file, ec))
        fail(name, ": cannot read the texture: not a regular file");
    const fs::path canonical = fs::canonical(file, ec);
    if (ec) fail(name, ": cannot read the texture: ", ec.message());

    auto key = std::make_pair(canonical.string(), encoding);
    if (const auto found = impl_->index.find(key); found != impl_->index.end())
        return TextureHandle{found->second};

    // The header, read now so that an unreadable file fails before rendering.
    OIIO::ImageSpec spec;
    {
        std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(key.first);
        if (!in) fail(name, ": cannot read the texture: ", oneLine(OIIO::geterror()));
        spec = in->spec();
        in->close();
    }
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        fail(name, ": the texture is empty (", spec.width, " x ", spec.height, ", ",
             spec.nchannels, " channels)");
    if (spec.depth > 1)
        fail(name, ": is a volume image (depth ", spec.depth, "), not a 2D texture");

    OiioSystem& system = *impl_->system;
    OiioSystem::Perthread* perthread = impl_->perthread();
    OiioSystem::TextureHandle* handle =
        system.get_texture_handle(OIIO::ustring(key.first), perthread);
    OIIO::ImageSpec cached;
    if (!handle || !system.good(handle) || !system.get_imagespec(handle, perthread, 0, cached))
        fail(name, ": cannot read the texture: ", oneLine(system.geterror()));

    Entry entry;
    entry.handle = handle;
    entry.file = name;
    entry.channels = std::min(spec.nchannels, 4);
    entry.width = spec.width;
    entry.height = spec.height;
    entry.srgb = encoding == TextureEncoding::Color && isSrgbFormat(spec.format);

    const auto index = static_cast<uint32_t>(impl_->entries.size());
    impl_->entries.push_back(std::move(entry));
    impl_->index.emplace(std::move(key), index);
    return TextureHandle{index};
}

Vec4 TextureSystem::lookup(TextureHandle texture, const Vec2& st, float footprint,
                           const TextureSampling& sampling) const {
    const Entry& e = impl_->entry(texture);
    float v[4] = {};
    impl_->filter(e, 0, e.channels, st, footprint, sampling, v);
    return e.grey() ? Vec4(v[0], v[0], v[0], e.channels == 2 ? v[1] : 1.0f)
                    : Vec4(v[0], v[1], v[2], e.channels == 4 ? v[3] : 1.0f);
}

Vec3 TextureSystem::lookupSlope(TextureHandle texture, const Vec2& st,
                                const TextureSampling& sampling) const {
    return impl_->slope(impl_->entry(texture), st, sampling);
}

Color TextureSystem::lookupColor(TextureHandle texture, const Vec2& st, float footprint,
                                 const TextureSampling& sampling) const {
    const Entry& e = impl_->entry(texture);
    float v[3] = {};
    impl_->filter(e, 0, e.grey() ? 1 : 3, st, footprint, sampling, v);
    return e.grey() ? Color(v[0]) : Color(v[0], v[1], v[2]);
}

float TextureSystem::lookupChannel(TextureHandle texture, int channel, const Vec2& st,
                                   float footprint, const TextureSampling& sampling) const {
    const Entry& e = impl_->entry(texture);
    if (channel < 0 || channel > 3)
        fail(e.file, ": texture channel ", channel, " requested; channels are 0 to 3 (RGBA)");
    const int stored = e.storedChannel(channel);
    if (stored < 0) return 1.0f;  // alpha of an image without one
    float value = 0.0f;
    impl_->filter(e, stored, 1, st, footprint, sampling, &value);
    return value;
}

Vec4 TextureSystem::triplanar(TextureHandle texture, const Vec3& p, const Vec3& n, float scale,
                              float sharpness, float footprint,
                              const TextureSampling& sampling) const {
    // |n|^sharpness relative to the largest component: scale-invariant in n,
    // and the dominant weight is 1 however large the exponent.
    const Vec3 a = glm::abs(n);
    const float largest = maxComponent(a);
    Vec3 w(1.0f);  // a zero or non-finite normal blends all three equally
    if (isFinite(n) && largest > 0.0f) {
        const float k = sharpness > 0.0f ? sharpness : 0.0f;  // NaN, negative: no sharpening
        w = Vec3(std::pow(a.x / largest, k), std::pow(a.y / largest, k),
                 std::pow(a.z / largest, k));
    }
    w /= w.x + w.y + w.z;
    for (int i = 0; i < 3; ++i)
        if (w[i] < kMinTriplanarWeight) w[i] = 0.0f;
    w /= w.x + w.y + w.z;  // the dominant weight survives, so the sum is positive

    const Vec3 q = p * scale;
    Vec4 result(0.0f);
    if (w.x > 0.0f) result += w.x * lookup(texture, Vec2(q.y, q.z), footprint, sampling);
    if (w.y > 0.0f) result += w.y * lookup(texture, Vec2(q.x, q.z), footprint, sampling);
    if (w.z > 0.0f) result += w.z * lookup(texture, Vec2(q.x, q.y), footprint, sampling);
    return result;
}

glm::ivec2 TextureSystem::resolution(TextureHandle texture) const {
    const Entry& e = impl_->entry(texture);
    return glm::ivec2(e.width, e.height);
}

size_t TextureSystem::textureCount() const { return impl_->entries.size(); }

}  // namespace strahl
