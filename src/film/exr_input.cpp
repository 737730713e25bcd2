#include "strahl/film/exr_input.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <system_error>

#include "strahl/core/error.h"
#include "strahl/film/denoise_layers.h"
#include "strahl/film/exact_part.h"

namespace strahl {

namespace fs = std::filesystem;

namespace {

// Metadata of strahl's own that is not free-form (not copied into `extra`).
bool isStructuredKey(const std::string& key) {
    return key == "version" || key == "renderTime" || key == "spp" || key == "integrator" ||
           key == "camera" || key == "samples_begin" || key == "samples_end" ||
           key == "sample_ranges" || key == "split_fingerprint";
}

std::string channelName(AovKind kind, char suffix) { return concat(aovName(kind), ".", suffix); }

size_t channelIndex(const ExrHeader& h, const std::string& name) {
    const auto it = std::find(h.channels.begin(), h.channels.end(), name);
    return static_cast<size_t>(it - h.channels.begin());  // == size() if absent
}

}  // namespace

ExrHeader readExrHeader(const fs::path& file) {
    const std::string name = file.string();
    std::error_code ec;
    if (!fs::exists(file, ec)) fail(name, ": cannot read: no such file");
    if (fs::is_directory(file, ec)) fail(name, ": is a folder, not an image");
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(name);
    if (!in) fail(name, ": cannot read: ", OIIO::geterror());
    if (std::string(in->format_name()) != "openexr")
        fail(name, ": not an OpenEXR image (a ", in->format_name(),
             " file; strahl merge reads the EXR outputs of strahl render)");
    const OIIO::ImageSpec& spec = in->spec();

    ExrHeader h;
    h.file = file;
    h.fullWidth = spec.full_width;
    h.fullHeight = spec.full_height;
    h.dataWindow = PixelRect{spec.x, spec.y, spec.x + spec.width, spec.y + spec.height};
    if (spec.full_x != 0 || spec.full_y != 0 || spec.depth != 1 ||
        !PixelRect{0, 0, h.fullWidth, h.fullHeight}.contains(h.dataWindow))
        fail(name, ": its data window is not inside a display window starting at 0, 0 (not an "
                   "image of strahl render)");
    for (int c = 0; c < spec.nchannels; ++c) {
        h.channels.push_back(spec.channel_name(c));
        const OIIO::TypeDesc type = spec.channelformat(c);
        h.channelTypes.push_back(type.c_str());
    }

    // Every channel must be one strahl writes.
    for (const char* rgb : {"R", "G", "B"})
        if (channelIndex(h, rgb) == h.channels.size())
            fail(name, ": has no channel '", rgb, "' (not an image of strahl render)");
    for (size_t k = 0; k < aovNames().size(); ++k) {
        const auto kind = static_cast<AovKind>(k);
        size_t present = 0;
        const std::string suffixes = exrChannelSuffixes(kind);
        for (char s : suffixes) present += channelIndex(h, channelName(kind, s)) < h.channels.size();
        if (present == 0) continue;
        if (present != suffixes.size())
            fail(name, ": the ", aovName(kind), " AOV lacks some of its channels");
        h.aovs.push_back(kind);
    }
    for (const std::string& channel : h.channels) {
        if (channel == "R" || channel == "G" || channel == "B" || channel.rfind("strahl.", 0) == 0 ||
            isDenoiseLayerChannel(channel))
            continue;
        const size_t dot = channel.find('.');
        const auto kind = aovFromName(channel.substr(0, dot));
        if (!kind || std::find(h.aovs.begin(), h.aovs.end(), *kind) == h.aovs.end() ||
            channel.size() != dot + 2 ||
            std::strchr(exrChannelSuffixes(*kind), channel.back()) == nullptr)
            fail(name, ": channel '", channel, "' is not one that strahl render writes");
    }
    h.exrFloat = h.channelTypes[channelIndex(h, "R")] == "float";

    // Metadata.
    ImageMetadata& m = h.metadata;
    m.renderSeconds = spec.get_float_attribute("strahl:renderTime", 0.0f);
    m.spp = spec.get_int_attribute("strahl:spp", 0);
    m.integrator = spec.get_string_attribute("strahl:integrator");
    m.camera = spec.get_string_attribute("strahl:camera");
    if (const OIIO::ParamValue* p = spec.find_attribute("worldToCamera", OIIO::TypeMatrix44))
        std::memcpy(&m.worldToCamera, p->data(), sizeof(float) * 16);
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        const std::string key = p.name().string();
        if (key.rfind("strahl:", 0) != 0 || p.type() != OIIO::TypeString) continue;
        const std::string sub = key.substr(7);
        if (!isStructuredKey(sub)) m.extra[sub] = spec.get_string_attribute(key);
    }
    if (m.spp <= 0)
        fail(name, ": has no sample count (strahl:spp; not an image of strahl render)");
    h.samples = static_cast<uint32_t>(m.spp);
    // A partial or ray-traced image says how many samples every pixel has.
    if (const auto it = m.extra.find("samples"); it != m.extra.end()) {
        const long n = std::strtol(it->second.c_str(), nullptr, 10);
        if (n > 0) h.samples = static_cast<uint32_t>(n);
    }

    // The exact state of a part of a split render.
    const std::string fingerprint = spec.get_string_attribute("strahl:split_fingerprint");
    const std::string ranges = spec.get_string_attribute("strahl:sample_ranges");
    const bool channels = hasExactChannels(h.channels);
    if (!fingerprint.empty() || !ranges.empty() || channels) {
        if (fingerprint.empty() || ranges.empty() || !channels)
            fail(name, ": carries only part of the exact sums of a split render (",
                 fingerprint.empty() ? "no strahl:split_fingerprint" : "",
                 ranges.empty() ? " no strahl:sample_ranges" : "",
                 channels ? "" : " no strahl.sum channels", ")");
        const auto parsed = parseRanges(ranges);
        if (!parsed) fail(name, ": strahl:sample_ranges '", ranges, "' is not a list of ranges");
        SamplePart part;
        part.ranges = *parsed;
        part.fingerprint = fingerprint;
        if (part.sampleCount() > ExactSum::kMaxSamples)
            fail(name, ": strahl:sample_ranges '", ranges, "' holds more than ",
                 ExactSum::kMaxSamples, " samples");
        h.samples = static_cast<uint32_t>(part.sampleCount());
        m.part = std::move(part);
    }
    return h;
}

Film readExrFilm(const ExrHeader& h) {
    const std::string name = h.file.string();
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(name);
    if (!in) fail(name, ": cannot read: ", OIIO::geterror());
    const size_t stride = h.channels.size();
    const PixelRect& window = h.dataWindow;
    const size_t count = size_t(window.width()) * size_t(window.height());
    // Half and float both widen to float exactly, and so do the exact pieces.
    std::vector<float> pixels(count * stride);
    if (!in->read_image(0, 0, 0, static_cast<int>(stride), OIIO::TypeDesc::FLOAT, pixels.data()))
        fail(name, ": cannot read: ", in->geterror());

    Film film(h.fullWidth, h.fullHeight, window, h.aovs);
    if (h.exact()) {
        // A part rendered with --denoise carries the even samples' sums too.
        if (channelIndex(h, "strahl.sum.even.R.0") < h.channels.size()) film.keepHalves(0);
        readExactChannels(film, h.channels, pixels, name);
        // A complete part has every sample of its ranges in every pixel; an
        // interrupted one (or one stopped by --time-limit) does not, and its
        // ranges would claim samples it never took.
        for (int y = window.y0; y < window.y1; ++y)
            for (int x = window.x0; x < window.x1; ++x)
                if (film.sampleCount(x, y) != h.samples)
                    fail(name, ": pixel (", x, ", ", y, ") has ", film.sampleCount(x, y),
                         " samples, its sample ranges ", formatRanges(h.metadata.part->ranges),
                         " hold ", h.samples,
                         ": a partial render cannot be merged (finish it with --resume)");
        return film;
    }

    // Only the means: rebuild sums of h.samples samples from them.
    const auto column = [&](AovKind kind, int c) {
        return channelIndex(h, channelName(kind, exrChannelSuffixes(kind)[c]));
    };
    const size_t r = channelIndex(h, "R"), g = channelIndex(h, "G"), b = channelIndex(h, "B");
    const auto has = [&](AovKind kind) {
        return std::find(h.aovs.begin(), h.aovs.end(), kind) != h.aovs.end();
    };
    size_t i = 0;
    for (int y = window.y0; y < window.y1; ++y)
        for (int x = window.x0; x < window.x1; ++x, ++i) {
            const float* px = pixels.data() + i * stride;
            FilmPixel p;
            // An adaptive render's pixels have their own counts (the samples AOV).
            p.samples = h.samples;
            if (has(AovKind::Samples)) {
                const float taken = px[column(AovKind::Samples, 0)];
                if (!(taken >= 0.0f && taken <= float(h.samples)) || taken != std::floor(taken))
                    fail(name, ": pixel (", x, ", ", y, ") has a samples value of ", taken,
                         ", not a count from 0 to ", h.samples);
                p.samples = static_cast<uint32_t>(taken);
            }
            const double n = p.samples;
            const auto sum3 = [&](ExactSum3& sum, size_t c0, size_t c1, size_t c2, double w) {
                sum = {ExactSum::fromValue(double(px[c0]) * w), ExactSum::fromValue(double(px[c1]) * w),
                       ExactSum::fromValue(double(px[c2]) * w)};
            };
            sum3(p.radiance, r, g, b, n);
            // Depth +inf marks a pixel that no sample hit; without depth,
            // take every sample as a hit.
            const bool hit = !has(AovKind::Depth) || std::isfinite(px[column(AovKind::Depth, 0)]);
            p.hits = hit ? p.samples : 0;
            if (has(AovKind::Normal))
                sum3(p.normal, column(AovKind::Normal, 0), column(AovKind::Normal, 1),
                     column(AovKind::Normal, 2), n);
            if (has(AovKind::Albedo))
                sum3(p.albedo, column(AovKind::Albedo, 0), column(AovKind::Albedo, 1),
                     column(AovKind::Albedo, 2), n);
            if (has(AovKind::Position))
                sum3(p.position, column(AovKind::Position, 0), column(AovKind::Position, 1),
                     column(AovKind::Position, 2), hit ? n : 0.0);
            if (has(AovKind::Depth) && hit)
                p.depth = ExactSum::fromValue(double(px[column(AovKind::Depth, 0)]) * n);
            if (has(AovKind::ObjectId)) p.objectId = px[column(AovKind::ObjectId, 0)];
            if (has(AovKind::Variance)) {
                // The variance of the mean is M2 / (n (n - 1)); the beauty is the mean.
                for (int c = 0; c < 3; ++c) {
                    p.mean[c] = px[c == 0 ? r : c == 1 ? g : b];
                    p.m2[c] = static_cast<float>(double(px[column(AovKind::Variance, c)]) * n *
                                                 (n - 1.0));
                }
            }
            film.setPixel(x, y, p);
        }
    return film;
}

}  // namespace strahl
