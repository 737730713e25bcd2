#include "strahl/film/image_output.h"

#include <fstream>

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <memory>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/film/denoise_layers.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

enum class Encoding {
    SceneLinearExr,  // OpenEXR, half or float, with AOVs and metadata
    Display8,        // display-referred 8-bit
    Display16,       // display-referred 16-bit
};

struct Format {
    const char* extension;   // lower case, with the dot
    const char* oiioFormat;  // OpenImageIO plugin name
    Encoding encoding;
};

constexpr Format kFormats[] = {
    {".exr", "openexr", Encoding::SceneLinearExr}, {".png", "png", Encoding::Display8},
    {".jpg", "jpeg", Encoding::Display8},          {".jpeg", "jpeg", Encoding::Display8},
    {".tif", "tiff", Encoding::Display16},         {".tiff", "tiff", Encoding::Display16},
};

// The extensions of kFormats, as the public list.
constexpr auto kExtensions = [] {
    std::array<std::string_view, std::size(kFormats)> extensions{};
    for (size_t i = 0; i < extensions.size(); ++i) extensions[i] = kFormats[i].extension;
    return extensions;
}();

std::string supportedExtensions() {
    std::string list;
    for (const Format& format : kFormats) list += concat(list.empty() ? "" : " ", format.extension);
    return list;
}

const Format& formatOf(const fs::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const Format& format : kFormats)
        if (ext == format.extension) return format;
    fail(file.string(), ": unsupported image format ",
         ext.empty() ? std::string("(no extension)") : "'" + ext + "'",
         " (supported: ", supportedExtensions(), ")");
}

// A name in the destination folder that no other writer uses: hidden, unique
// per process and call, and ending in the original extension, which is what
// OpenImageIO and tools that look at the folder go by.
fs::path temporaryPath(const fs::path& file) {
    static std::atomic<unsigned> counter{0};
    const std::string name = concat(".", file.stem().string(), ".strahl-tmp-", ::getpid(), "-",
                                    counter.fetch_add(1), file.extension().string());
    return file.parent_path() / name;
}

// Removes the temporary file unless the write got as far as renaming it.
class TemporaryFile {
  public:
    explicit TemporaryFile(fs::path path) : path_(std::move(path)) {}
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    ~TemporaryFile() {
        if (!renamed_) {
            std::error_code ignored;
            fs::remove(path_, ignored);
        }
    }
    const fs::path& path() const { return path_; }
    void renamed() { renamed_ = true; }

  private:
    fs::path path_;
    bool renamed_ = false;
};

void addMetadata(OIIO::ImageSpec& spec, const ImageMetadata& metadata) {
    spec.attribute("Software", "strahl " STRAHL_VERSION);
    spec.attribute("strahl:version", STRAHL_VERSION);
    spec.attribute("strahl:renderTime", static_cast<float>(metadata.renderSeconds));
    spec.attribute("strahl:spp", metadata.spp);
    spec.attribute("strahl:integrator", metadata.integrator);
    spec.attribute("strahl:camera", metadata.camera);
    // GLM stores column-major matrices for column vectors (p' = M p); read in
    // row-major order, the same 16 floats are the matrix for row vectors
    // (p' = p M) that OpenEXR's worldToCamera (Imath::M44f) expects.
    spec.attribute("worldToCamera", OIIO::TypeMatrix44, glm::value_ptr(metadata.worldToCamera));
    for (const auto& [key, value] : metadata.extra) spec.attribute("strahl:" + key, value);
    if (metadata.part && !metadata.part->ranges.empty()) {
        const std::vector<SampleRange>& ranges = metadata.part->ranges;
        spec.attribute("strahl:samples_begin", static_cast<int>(ranges.front().begin));
        spec.attribute("strahl:samples_end", static_cast<int>(ranges.back().end));
        spec.attribute("strahl:sample_ranges", formatRanges(ranges));
        spec.attribute("strahl:split_fingerprint", metadata.part->fingerprint);
    }
}

}  // namespace

// EXR channel name suffixes, one per channel, after the usual conventions:
// XYZ for vectors and points, Z for depth, RGB for colours (the variance is per
// colour channel), and X for a single non-depth value (Blender's object index
// pass is IndexOB.X; "Z" would make tools take the ids for depth).

const char* exrChannelSuffixes(AovKind kind) {
    switch (kind) {
        case AovKind::Normal:
            return "XYZ";
        case AovKind::Depth:
            return "Z";
        case AovKind::Albedo:
            return "RGB";
        case AovKind::Position:
            return "XYZ";
        case AovKind::ObjectId:
            return "X";
        case AovKind::Variance:
            return "RGB";
        case AovKind::Samples:
            return "X";
    }
    fail("invalid AovKind value ", static_cast<int>(kind));
}

namespace {

// EXR: the crop is the data window inside the full display window, so crops
// of one image composite into the whole.
OIIO::ImageSpec exrSpec(const Film& film, const OutputSettings& settings,
                        const ImageMetadata& metadata, const std::vector<float>* denoised,
                        std::vector<float>& pixels) {
    const OIIO::TypeDesc format = settings.exrFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF;
    std::vector<std::string> names{"R", "G", "B"};
    std::vector<OIIO::TypeDesc> formats(3, format);
    std::vector<std::vector<float>> planes;
    if (denoised) {
        // The denoised image is the main one; the rendered beauty stays as a layer.
        planes.push_back(*denoised);
        planes.push_back(film.resolveBeauty());
        for (const char* c : {"noisy.R", "noisy.G", "noisy.B"}) names.push_back(c);
        formats.resize(names.size(), format);
    } else {
        planes.push_back(film.resolveBeauty());
    }
    for (AovKind kind : film.aovs()) {
        // Ids and counts are always float: half holds integers exactly only up to 2048.
        const OIIO::TypeDesc aovFormat =
            kind == AovKind::ObjectId || kind == AovKind::Samples ? OIIO::TypeDesc::FLOAT : format;
        for (const char* suffix = exrChannelSuffixes(kind); *suffix != '\0'; ++suffix) {
            names.push_back(concat(aovName(kind), ".", *suffix));
            formats.push_back(aovFormat);
        }
        planes.push_back(film.resolveAov(kind));
    }
    if (film.keepsHalves()) {
        appendHalfLayers(film, names, planes);
        formats.resize(names.size(), format);
    }
    // A part of a split render: the exact state, as float channels (exact_part.h).
    if (metadata.part) {
        appendExactChannels(film, names, planes);
        formats.resize(names.size(), OIIO::TypeDesc::FLOAT);
    }

    const PixelRect& crop = film.crop();
    const size_t count = static_cast<size_t>(crop.width()) * static_cast<size_t>(crop.height());
    const size_t channels = names.size();
    pixels.assign(count * channels, 0.0f);
    size_t first = 0;  // the first interleaved channel of the current plane
    for (const std::vector<float>& plane : planes) {
        const size_t planeChannels = plane.size() / count;
        for (size_t i = 0; i < count; ++i)
            for (size_t c = 0; c < planeChannels; ++c)
                pixels[i * channels + first + c] = plane[i * planeChannels + c];
        first += planeChannels;
    }

    OIIO::ImageSpec spec(crop.width(), crop.height(), static_cast<int>(channels), format);
    spec.channelnames = names;
    // Per-channel formats only when they differ, so a uniform file stays as it was.
    if (std::any_of(formats.begin(), formats.end(),
                    [&](const OIIO::TypeDesc& f) { return f != format; }))
        spec.channelformats = formats;
    // The constructor named channel 3 "A" and made it alpha; none of ours is.
    spec.alpha_channel = -1;
    spec.z_channel = -1;
    spec.x = crop.x0;
    spec.y = crop.y0;
    spec.full_x = 0;
    spec.full_y = 0;
    spec.full_width = film.fullWidth();
    spec.full_height = film.fullHeight();
    spec.attribute("compression", "zip");
    addMetadata(spec, metadata);
    return spec;
}

// Display-referred formats: the crop alone, through the display transform,
// clamped to [0, 1] (NaN to 0) and rounded to the nearest code value.
template <typename T>
std::vector<T> quantise(const std::vector<float>& values) {
    constexpr float kMax = static_cast<float>(std::numeric_limits<T>::max());
    std::vector<T> out(values.size());
    for (size_t i = 0; i < values.size(); ++i) {
        const float v = std::isnan(values[i]) ? 0.0f : std::clamp(values[i], 0.0f, 1.0f);
        out[i] = static_cast<T>(std::lround(v * kMax));
    }
    return out;
}

// `pixels` are interleaved values of type `pixelType`; OpenImageIO converts
// them to spec.format.
void writeFile(const fs::path& file, const Format& format, OIIO::ImageSpec& spec,
               OIIO::TypeDesc pixelType, const void* pixels) {
    writeFileAtomically(file, [&](const fs::path& temp) {
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(format.oiioFormat);
        if (!out) return OIIO::geterror();
        if (!out->open(temp.string(), spec) || !out->write_image(pixelType, pixels) || !out->close())
            return out->geterror();
        return std::string();
    });  // the output is destroyed, and the file closed, before any rename or removal
}

}  // namespace

void writeFileAtomically(const fs::path& file,
                         const std::function<std::string(const fs::path& temp)>& write) {
    TemporaryFile temp(temporaryPath(file));
    std::string error = write(temp.path());
    if (error.empty()) {
        std::error_code ec;
        fs::rename(temp.path(), file, ec);
        if (ec)
            error = ec.message();
        else
            temp.renamed();
    }
    if (!error.empty()) fail(file.string(), ": cannot write: ", error);
}

std::span<const std::string_view> supportedImageExtensions() { return kExtensions; }

void checkOutputPath(const fs::path& file) {
    formatOf(file);
    std::error_code ec;
    if (fs::is_directory(file, ec)) fail(file.string(), ": is a folder, not an image file name");
    const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    if (!fs::exists(folder, ec))
        fail(file.string(), ": cannot write: folder '", folder.string(), "' does not exist");
    if (!fs::is_directory(folder, ec))
        fail(file.string(), ": cannot write: '", folder.string(), "' is not a folder");

    // Permissions alone do not tell (ACLs, read-only mounts, root): try it.
    const fs::path probe = temporaryPath(file);
    std::FILE* handle = std::fopen(probe.c_str(), "wx");  // "x": fail rather than reuse a file
    if (handle == nullptr) {
        const int error = errno;
        fail(file.string(), ": cannot write in folder '", folder.string(),
             "': ", std::strerror(error));
    }
    std::fclose(handle);
    fs::remove(probe, ec);
}

void writeImage(const Film& film, const fs::path& file, const OutputSettings& settings,
                const ImageMetadata& metadata, const std::vector<float>* denoised) {
    const Format& format = formatOf(file);
    if (denoised && denoised->size() != size_t(film.crop().width()) * size_t(film.crop().height()) * 3)
        fail(file.string(), ": the denoised image does not match the film's size");
    if (format.encoding == Encoding::SceneLinearExr) {
        std::vector<float> pixels;
        OIIO::ImageSpec spec = exrSpec(film, settings, metadata, denoised, pixels);
        writeFile(file, format, spec, OIIO::TypeDesc::FLOAT, pixels.data());
        return;
    }

    writeDisplayImage(denoised ? *denoised : film.resolveBeauty(), film.crop().width(),
                      film.crop().height(), file, settings, metadata);
}

void writeDisplayImage(std::vector<float> rgb, int width, int height, const fs::path& file,
                       const OutputSettings& settings, const ImageMetadata& metadata) {
    const Format& format = formatOf(file);
    if (format.encoding == Encoding::SceneLinearExr)
        fail(file.string(), ": writeDisplayImage writes PNG, JPEG or TIFF, not EXR");
    DisplayTransform::get(settings.color)->apply(rgb, width, height);
    const OIIO::TypeDesc type =
        format.encoding == Encoding::Display16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(width, height, 3, type);
    addMetadata(spec, metadata);  // each format keeps what it can represent
    if (type == OIIO::TypeDesc::UINT16) {
        const std::vector<uint16_t> pixels = quantise<uint16_t>(rgb);
        writeFile(file, format, spec, type, pixels.data());
    } else {
        const std::vector<uint8_t> pixels = quantise<uint8_t>(rgb);
        writeFile(file, format, spec, type, pixels.data());
    }
}

void writeTextFileAtomically(const std::filesystem::path& file, const std::string& text) {
    writeFileAtomically(file, [&](const std::filesystem::path& temp) {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        out << text;
        out.close();
        return out ? std::string() : std::string("write failed (disk full?)");
    });
}

}  // namespace strahl
