#include "strahl/film/z_test.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "strahl/core/error.h"
#include "strahl/film/image_output.h"

namespace strahl {

namespace {

// Linear Rec. 709 (sRGB primaries, D65) to CIE XYZ: the matrix Mitsuba's
// Bitmap conversion uses.
constexpr double kRgbToXyz[3][3] = {{0.412453, 0.357580, 0.180423},
                                    {0.212671, 0.715160, 0.072169},
                                    {0.019334, 0.119193, 0.950227}};

double xyz(const std::vector<float>& rgb, size_t pixel, int channel) {
    const float* c = &rgb[3 * pixel];
    return kRgbToXyz[channel][0] * c[0] + kRgbToXyz[channel][1] * c[1] +
           kRgbToXyz[channel][2] * c[2];
}

int channelIndex(const OIIO::ImageSpec& spec, const char* name, int fallback) {
    for (int c = 0; c < spec.nchannels; ++c)
        if (spec.channelnames[size_t(c)] == name) return c;
    return fallback;
}

}  // namespace

RgbImage readRgbImage(const std::filesystem::path& file) {
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(file.string());
    if (!in) fail(file.string(), ": cannot read the image: ", OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.nchannels < 3)
        fail(file.string(), ": has ", spec.nchannels, " channel(s), not R, G and B");
    std::vector<float> all(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
        fail(file.string(), ": cannot read the pixels: ", in->geterror());
    const int r = channelIndex(spec, "R", 0), g = channelIndex(spec, "G", 1),
              b = channelIndex(spec, "B", 2);
    RgbImage image;
    image.width = spec.width;
    image.height = spec.height;
    const size_t pixels = size_t(spec.width) * size_t(spec.height);
    image.rgb.resize(3 * pixels);
    for (size_t i = 0; i < pixels; ++i) {
        const float* p = &all[i * size_t(spec.nchannels)];
        image.rgb[3 * i] = p[r];
        image.rgb[3 * i + 1] = p[g];
        image.rgb[3 * i + 2] = p[b];
    }
    return image;
}

ZTestResult zTest(const RgbImage& mean, double spp, const RgbImage& reference,
                  const RgbImage& variance, const ZTestOptions& options) {
    for (const RgbImage* image : {&reference, &variance})
        if (image->width != mean.width || image->height != mean.height)
            fail("z-test: the images differ in size (", mean.width, "x", mean.height, " and ",
                 image->width, "x", image->height, ")");
    if (!(spp > 0)) fail("z-test: the sample count must be positive, got ", spp);
    const size_t pixels = size_t(mean.width) * size_t(mean.height);
    ZTestResult result;
    result.values = 3 * pixels;
    // Šidák: the per-value level at which N independent tests keep a
    // family-wise error of `significance` (N = the pixel count, as Mitsuba's).
    result.alpha = 1.0 - std::pow(1.0 - options.significance, 1.0 / double(pixels));
    result.z.resize(3 * pixels);
    std::vector<ZTestValue> all;
    all.reserve(3 * pixels);
    for (size_t i = 0; i < pixels; ++i) {
        for (int c = 0; c < 3; ++c) {
            ZTestValue v;
            v.x = int(i % size_t(mean.width));
            v.y = int(i / size_t(mean.width));
            v.channel = c;
            v.mean = xyz(mean.rgb, i, c);
            v.reference = xyz(reference.rgb, i, c);
            const double var = std::max(xyz(variance.rgb, i, c), options.minVariance);
            v.z = std::abs(v.mean - v.reference) * std::sqrt(spp / var);
            v.p = std::erfc(v.z / std::sqrt(2.0));  // two-sided, standard normal
            if (!std::isfinite(v.z)) v.p = 0.0;     // a NaN or infinite pixel fails
            result.z[3 * i + size_t(c)] = static_cast<float>(v.z);
            if (v.p > result.alpha) ++result.passing;
            all.push_back(v);
        }
    }
    result.passed = double(result.passing) >= options.requiredFraction * double(result.values);
    const size_t worst = std::min<size_t>(10, all.size());
    std::partial_sort(all.begin(), all.begin() + std::ptrdiff_t(worst), all.end(),
                      [](const ZTestValue& a, const ZTestValue& b) { return a.p < b.p; });
    result.worst.assign(all.begin(), all.begin() + std::ptrdiff_t(worst));
    return result;
}

std::string ZTestResult::summary() const {
    char line[160];
    std::snprintf(line, sizeof line, "%.2f %% of %zu values pass (need 99.75 %%, alpha %.3g)",
                  100.0 * passingFraction(), values, alpha);
    std::string text = line;
    const char* names = "XYZ";
    for (size_t i = 0; i < worst.size() && i < 5; ++i) {
        const ZTestValue& v = worst[i];
        std::snprintf(line, sizeof line, "%s(%d, %d) %c mean %.4g ref %.4g z %.3g", i ? "; " : "; worst: ",
                      v.x, v.y, names[v.channel], v.mean, v.reference, v.z);
        text += line;
    }
    return text;
}

void writeZTestImage(const std::filesystem::path& file, const RgbImage& mean,
                     const RgbImage& reference, const ZTestResult& result) {
    const size_t pixels = size_t(mean.width) * size_t(mean.height);
    constexpr int kChannels = 10;
    std::vector<float> data(pixels * kChannels);
    for (size_t i = 0; i < pixels; ++i) {
        float* d = &data[i * kChannels];
        bool fails = false;
        for (int c = 0; c < 3; ++c) {
            d[c] = mean.rgb[3 * i + size_t(c)];
            d[3 + c] = reference.rgb[3 * i + size_t(c)];
            const double z = result.z[3 * i + size_t(c)];
            d[6 + c] = static_cast<float>(z);
            fails |= !(std::erfc(z / std::sqrt(2.0)) > result.alpha);
        }
        d[9] = fails ? 1.0f : 0.0f;
    }
    OIIO::ImageSpec spec(mean.width, mean.height, kChannels, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"mean.R",      "mean.G",      "mean.B", "reference.R", "reference.G",
                         "reference.B", "z.X",         "z.Y",    "z.Z",         "fails"};
    writeFileAtomically(file, [&](const std::filesystem::path& temp) -> std::string {
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(temp.string());
        if (!out || !out->open(temp.string(), spec)) return OIIO::geterror();
        if (!out->write_image(OIIO::TypeDesc::FLOAT, data.data())) return out->geterror();
        if (!out->close()) return out->geterror();
        return {};
    });
}

}  // namespace strahl
