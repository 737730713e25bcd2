#include "image_reader.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <memory>
#include <string>
#include <system_error>

#include "strahl/core/error.h"

namespace fs = std::filesystem;

namespace strahl::scene_detail {

namespace {

// OIIO's messages may span lines and end in a newline; keep them on one line.
std::string oneLine(std::string message) {
    for (char& c : message)
        if (c == '\n' || c == '\r') c = ' ';
    while (!message.empty() && message.back() == ' ') message.pop_back();
    return message.empty() ? std::string("unknown error") : message;
}

}  // namespace

FloatImage readFloatImage(const fs::path& file, const char* what, size_t maxPixels) {
    const std::string name = file.string();
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        fail(name, ": cannot read the ", what, ": ",
             fs::exists(file, ec) ? "not a regular file" : "no such file");

    // Values as stored: no premultiplying by an alpha channel (PNG, TIFF).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(name, &config);
    if (!in) fail(name, ": cannot read the ", what, ": ", oneLine(OIIO::geterror()));
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        fail(name, ": the ", what, " is empty (", spec.width, " x ", spec.height, ", ",
             spec.nchannels, " channels)");
    if (spec.depth > 1) fail(name, ": is a volume image (depth ", spec.depth, "), not a ", what);
    const size_t columns = static_cast<size_t>(spec.width), rows = static_cast<size_t>(spec.height);
    // Checked before allocating: a corrupt or hostile header must not make us
    // allocate what it claims.
    if (columns > maxPixels || rows > maxPixels || columns * rows > maxPixels)
        fail(name, ": the ", what, " is ", columns, " x ", rows, " pixels, more than the limit of ",
             maxPixels, " pixels");

    FloatImage image;
    image.width = spec.width;
    image.height = spec.height;
    image.channels = spec.nchannels >= 3 ? 3 : 1;
    image.integer = spec.format.basetype != OIIO::TypeDesc::FLOAT &&
                    spec.format.basetype != OIIO::TypeDesc::HALF &&
                    spec.format.basetype != OIIO::TypeDesc::DOUBLE;
    image.pixels.resize(columns * rows * static_cast<size_t>(image.channels));
    if (!in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        fail(name, ": cannot read the ", what, ": ", oneLine(in->geterror()));
    in->close();
    for (size_t k = 0; k < image.pixels.size(); ++k) {
        if (!std::isfinite(image.pixels[k])) {
            const size_t pixel = k / static_cast<size_t>(image.channels);
            fail(name, ": the ", what, " has a non-finite value at pixel (", pixel % columns, ", ",
                 pixel / columns, ")");
        }
    }
    return image;
}

}  // namespace strahl::scene_detail
