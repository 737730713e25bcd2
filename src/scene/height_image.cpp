// Height images through OpenImageIO (see height_image.h).

#include "height_image.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <system_error>

#include "strahl/core/error.h"

namespace fs = std::filesystem;

namespace strahl::scene_detail {

namespace {

// More samples than any sensible height field (8192 x 8192) and a cap on what
// a corrupt or hostile header can make us allocate: 2^26 floats are 256 MiB.
constexpr size_t kMaxSamples = size_t(1) << 26;

// OIIO's messages may span lines and end in a newline; keep them on one line.
std::string oneLine(std::string message) {
    for (char& c : message)
        if (c == '\n' || c == '\r') c = ' ';
    while (!message.empty() && message.back() == ' ') message.pop_back();
    return message.empty() ? std::string("unknown error") : message;
}

}  // namespace

HeightImage loadHeightImage(const fs::path& file) {
    const std::string name = file.string();
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        fail(name, ": cannot read the height image: ",
             fs::exists(file, ec) ? "not a regular file" : "no such file");

    // Values as stored: no premultiplying by an alpha channel (PNG, TIFF).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(name, &config);
    if (!in) fail(name, ": cannot read the height image: ", oneLine(OIIO::geterror()));
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        fail(name, ": the height image is empty (", spec.width, " x ", spec.height, ", ",
             spec.nchannels, " channels)");
    if (spec.depth > 1)
        fail(name, ": is a volume image (depth ", spec.depth, "), not a height image");
    const size_t columns = static_cast<size_t>(spec.width), rows = static_cast<size_t>(spec.height);
    if (columns > kMaxSamples || rows > kMaxSamples || columns * rows > kMaxSamples)
        fail(name, ": the height image is ", columns, " x ", rows,
             " pixels, more than the limit of 2^26 (", kMaxSamples, ") samples");

    // Only the channels used: the first, or the first three for luminance.
    const int channels = spec.nchannels >= 3 ? 3 : 1;
    std::vector<float> pixels(columns * rows * static_cast<size_t>(channels));
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
        fail(name, ": cannot read the height image: ", oneLine(in->geterror()));
    in->close();

    HeightImage image;
    image.columns = spec.width;
    image.rows = spec.height;
    image.heights.resize(columns * rows);
    for (size_t k = 0; k < image.heights.size(); ++k) {
        const float* p = &pixels[k * static_cast<size_t>(channels)];
        const float h = channels == 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
        if (!std::isfinite(h))
            fail(name, ": the height image has a non-finite value at pixel (", k % columns, ", ",
                 k / columns, ")");
        image.heights[k] = h;
    }
    return image;
}

}  // namespace strahl::scene_detail
