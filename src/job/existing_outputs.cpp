#include "strahl/job/existing_outputs.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <memory>
#include <system_error>
#include <vector>

#include "strahl/core/error.h"

namespace strahl {

namespace fs = std::filesystem;

namespace {

// Reads every pixel, a band of scanlines at a time (little memory for any
// size): a file cut short by a full disk or a killed copy fails here, which
// its header alone would not show.
bool decodes(OIIO::ImageInput& in, std::string& error) {
    const OIIO::ImageSpec& spec = in.spec();
    const size_t rowValues = static_cast<size_t>(spec.width) * static_cast<size_t>(spec.nchannels);
    if (spec.tile_width > 0) {  // strahl writes scanline files; read others whole
        std::vector<float> all(rowValues * static_cast<size_t>(spec.height));
        if (in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data())) return true;
        error = in.geterror();
        return false;
    }
    constexpr int kBand = 64;
    std::vector<float> band(rowValues * kBand);
    for (int y = spec.y; y < spec.y + spec.height; y += kBand) {
        const int end = std::min(y + kBand, spec.y + spec.height);
        if (!in.read_scanlines(0, 0, y, end, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                               band.data())) {
            error = in.geterror();
            return false;
        }
    }
    return true;
}

}  // namespace

std::string incompleteReason(const fs::path& file, const ExpectedImage& expected) {
    std::error_code ec;
    if (!fs::exists(file, ec)) return "does not exist";
    if (!fs::is_regular_file(file, ec)) return "is not a regular file";
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(file.string());
    if (!in) return "cannot be read (" + OIIO::geterror() + ")";
    const OIIO::ImageSpec& spec = in->spec();
    const PixelRect& r = expected.region;
    if (std::string(in->format_name()) == "openexr") {
        if (spec.full_x != 0 || spec.full_y != 0 || spec.full_width != expected.fullWidth ||
            spec.full_height != expected.fullHeight)
            return concat("is a ", spec.full_width, "x", spec.full_height, " image, not ",
                          expected.fullWidth, "x", expected.fullHeight);
        if (spec.x != r.x0 || spec.y != r.y0 || spec.width != r.width() ||
            spec.height != r.height())
            return concat("holds pixels ", spec.x, " ", spec.y, " ", spec.x + spec.width, " ",
                          spec.y + spec.height, ", not the region ", r.x0, " ", r.y0, " ", r.x1,
                          " ", r.y1);
    } else if (spec.width != r.width() || spec.height != r.height()) {
        return concat("is ", spec.width, "x", spec.height, ", not ", r.width(), "x", r.height());
    }
    if (spec.get_string_attribute("strahl:partial") == "1") {
        const std::string stopped = spec.get_string_attribute("strahl:stopped");
        return "is partial" + (stopped.empty() ? std::string() : " (stopped by " + stopped + ")");
    }
    const std::string fingerprint = spec.get_string_attribute("strahl:fingerprint");
    if (!fingerprint.empty() && fingerprint != expected.fingerprint)
        return "was rendered with other settings (" + fingerprint + ")";
    std::string error;
    if (!decodes(*in, error)) return "is damaged (" + error + ")";
    return {};
}

bool recordsPartial(const fs::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".exr" || ext == ".png";
}

}  // namespace strahl
