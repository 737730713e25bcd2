#include "denoise_command.h"

#include <OpenImageIO/imageio.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>

#include "image_files.h"
#include "strahl/core/error.h"
#include "strahl/denoise/denoiser.h"
#include "strahl/film/denoise_layers.h"
#include "strahl/film/image_output.h"

namespace strahl::app {

namespace fs = std::filesystem;

namespace {

// An EXR read whole: channel names, their types and interleaved float pixels.
struct ExrImage {
    OIIO::ImageSpec spec;
    std::vector<float> pixels;
    std::map<std::string, size_t> column;  // channel name -> index
    size_t pixelCount() const { return size_t(spec.width) * size_t(spec.height); }
};

ExrImage readExr(const fs::path& file) {
    const std::string name = file.string();
    std::error_code ec;
    if (!fs::exists(file, ec)) fail(name, ": no such file");
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(name);
    if (!in) fail(name, ": cannot read: ", OIIO::geterror());
    if (std::string(in->format_name()) != "openexr")
        fail(name,
             ": not an OpenEXR image (strahl denoise reads the EXR of a strahl render "
             "with --denoise)");
    ExrImage image;
    image.spec = in->spec();
    if (image.spec.width <= 0 || image.spec.height <= 0 || image.spec.depth != 1)
        fail(name, ": image size ", image.spec.width, "x", image.spec.height, " is not usable");
    image.pixels.resize(image.pixelCount() * size_t(image.spec.nchannels));
    if (!in->read_image(0, 0, 0, image.spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        fail(name, ": cannot read: ", in->geterror());
    for (int c = 0; c < image.spec.nchannels; ++c)
        image.column[image.spec.channel_name(c)] = size_t(c);
    return image;
}

// The named channels, interleaved.
std::vector<float> gather(const ExrImage& image, const std::vector<std::string>& names) {
    const size_t n = image.pixelCount(), stride = size_t(image.spec.nchannels);
    std::vector<float> out(n * names.size());
    for (size_t c = 0; c < names.size(); ++c) {
        const size_t from = image.column.at(names[c]);
        for (size_t i = 0; i < n; ++i) out[i * names.size() + c] = image.pixels[i * stride + from];
    }
    return out;
}

// The denoiser's input; one error naming every missing layer.
DenoiseInput denoiseInputOf(const ExrImage& image, const std::string& source) {
    std::vector<std::string> missingLayers;
    const auto require = [&](const std::vector<std::string>& channels, const std::string& layer) {
        for (const std::string& c : channels)
            if (!image.column.count(c)) {
                missingLayers.push_back(layer);
                return;
            }
    };
    const std::vector<std::string> variance{"variance.R", "variance.G", "variance.B"};
    for (int h = 0; h < 2; ++h) require(halfLayerChannels(h), halfLayerName(h));
    require(variance, "variance");
    if (!missingLayers.empty()) {
        std::string list;
        for (const std::string& l : missingLayers) list += (list.empty() ? "" : ", ") + l;
        fail(source, ": lacks the denoiser's layers ", list,
             " (render with --denoise, or merge --sample-offset parts rendered with --denoise)");
    }
    const int spp = image.spec.get_int_attribute("strahl:spp", 0);
    if (spp > 0 && spp < 2)
        fail(source, ": has ", spp,
             " sample per pixel; the denoiser needs at least 2 (one for "
             "each half)");

    DenoiseInput input;
    input.width = image.spec.width;
    input.height = image.spec.height;
    for (int h = 0; h < 2; ++h) {
        const std::vector<std::string> names = halfLayerChannels(h);
        DenoiseHalf& half = input.halves[size_t(h)];
        half.color = gather(image, {names[0], names[1], names[2]});
        half.albedo = gather(image, {names[3], names[4], names[5]});
        half.normal = gather(image, {names[6], names[7], names[8]});
        half.depth = gather(image, {names[9]});
    }
    input.variance = gather(image, variance);
    return input;
}

// The input's channels with the denoised beauty as R, G, B and the noisy one
// as noisy.*, in a fresh spec of the same windows, formats and metadata.
void writeDenoisedExr(const ExrImage& image, const std::vector<float>& denoised,
                      const fs::path& file) {
    const bool wasDenoised = image.column.count("noisy.R") > 0;
    const std::vector<std::string> noisySource =
        wasDenoised ? std::vector<std::string>{"noisy.R", "noisy.G", "noisy.B"}
                    : std::vector<std::string>{"R", "G", "B"};
    OIIO::ImageSpec spec = image.spec;
    std::vector<std::string> names{"R", "G", "B", "noisy.R", "noisy.G", "noisy.B"};
    std::vector<size_t> from;  // input column of each output channel after the first three
    for (const std::string& c : noisySource) from.push_back(image.column.at(c));
    const auto formatOf = [&](size_t c) { return image.spec.channelformat(int(c)); };
    std::vector<OIIO::TypeDesc> formats(3, formatOf(image.column.at("R")));
    for (size_t c : from) formats.push_back(formatOf(c));
    for (int c = 0; c < image.spec.nchannels; ++c) {
        const std::string& name = image.spec.channel_name(c);
        if (name == "R" || name == "G" || name == "B" || name.rfind("noisy.", 0) == 0) continue;
        names.push_back(name);
        from.push_back(size_t(c));
        formats.push_back(formatOf(size_t(c)));
    }
    spec.nchannels = int(names.size());
    spec.channelnames = names;
    spec.channelformats = formats;
    spec.alpha_channel = -1;
    spec.z_channel = -1;
    spec.attribute("strahl:denoiser", "nfor");

    const size_t n = image.pixelCount(), inStride = size_t(image.spec.nchannels);
    std::vector<float> pixels(n * names.size());
    for (size_t i = 0; i < n; ++i) {
        float* out = pixels.data() + i * names.size();
        for (size_t c = 0; c < 3; ++c) out[c] = denoised[3 * i + c];
        for (size_t k = 0; k < from.size(); ++k) out[3 + k] = image.pixels[i * inStride + from[k]];
    }
    writeExrFile(file, spec, pixels);
}

}  // namespace

CLI::App* addDenoiseCommand(CLI::App& app, DenoiseOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "denoise", "Denoise an EXR rendered with --denoise (or merged from --denoise parts)");
    cmd->add_option("input", o.input, "EXR with the layers half0, half1 and variance")->required();
    cmd->add_option("-o,--output", o.outputs,
                    "Output image; repeat for several. .exr keeps every layer of the input with "
                    "the denoised beauty as R, G, B and the noisy one as noisy.*; .png/.jpg/.tif "
                    "show the denoised beauty through the OCIO display transform")
        ->required();
    cmd->add_option("--threads", o.threads, "Worker threads; 0 = all cores (default)")
        ->check(CLI::Range(0, 4096));
    addDisplayOptions(*cmd, o.color);
    cmd->add_flag("-q,--quiet", o.quiet, "No lines saying what was written");
    return cmd;
}

int runDenoise(const DenoiseOptions& o) {
    // Outputs are checked first: a bad path fails before the work.
    for (const std::string& out : o.outputs) checkOutputPath(out);
    if (std::any_of(o.outputs.begin(), o.outputs.end(),
                    [](const std::string& f) { return !isExr(f); }) ||
        !o.color.configFile.empty())
        DisplayTransform::get(o.color);
    const ExrImage image = readExr(o.input);
    const DenoiseInput input = denoiseInputOf(image, o.input);
    DenoiseSettings settings;
    settings.threads = o.threads;
    const auto start = std::chrono::steady_clock::now();
    const std::vector<float> denoised = denoise(input, settings, o.input);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    ImageMetadata metadata;  // for display outputs: what they can carry
    metadata.extra["denoiser"] = "nfor";
    OutputSettings output;
    output.color = o.color;
    for (const std::string& out : o.outputs) {
        if (isExr(out))
            writeDenoisedExr(image, denoised, out);
        else
            writeDisplayImage(denoised, input.width, input.height, out, output, metadata);
        if (!o.quiet) std::fprintf(stderr, "wrote %s\n", out.c_str());
    }
    if (!o.quiet)
        std::fprintf(stderr, "denoised %dx%d (NFOR) in %.2f s\n", input.width, input.height,
                     seconds);
    return 0;
}

}  // namespace strahl::app
