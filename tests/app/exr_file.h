#pragma once
// An image strahl wrote, read back for the CLI tests: its windows, channel
// names, float pixels and the strahl:* metadata the tests check; and the
// bit-for-bit comparison the determinism, resume, region and distributed
// tests rely on.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace strahl::test {

struct ExrFile {
    int x = 0, y = 0, width = 0, height = 0;  // data window
    int fullWidth = 0, fullHeight = 0;        // display window
    std::vector<std::string> channels;        // names, in file order
    std::vector<float> pixels;                // interleaved, row by row
    // strahl:partial, strahl:samples, strahl:stopped, strahl:frame, strahl:fingerprint
    std::string partial, samples, stopped, frame, fingerprint;
};

// Read through ImageInput, not ImageBuf: tests rewrite files under the same
// name, and ImageBuf's shared image cache would return the old pixels.
inline ExrFile readExr(const std::filesystem::path& file) {
    ExrFile e;
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(file.string());
    if (!in) {
        ADD_FAILURE() << "cannot read " << file << ": " << OIIO::geterror();
        return e;
    }
    const OIIO::ImageSpec& spec = in->spec();
    e.x = spec.x;
    e.y = spec.y;
    e.width = spec.width;
    e.height = spec.height;
    e.fullWidth = spec.full_width;
    e.fullHeight = spec.full_height;
    e.channels = spec.channelnames;
    e.pixels.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, e.pixels.data()))
        ADD_FAILURE() << "cannot read the pixels of " << file << ": " << in->geterror();
    e.partial = spec.get_string_attribute("strahl:partial");
    e.samples = spec.get_string_attribute("strahl:samples");
    e.stopped = spec.get_string_attribute("strahl:stopped");
    e.frame = spec.get_string_attribute("strahl:frame");
    e.fingerprint = spec.get_string_attribute("strahl:fingerprint");
    return e;
}

// The same channels and every value bit for bit (as float bits: a half value
// converts to exactly one float; the depth AOV's +inf compares equal).
inline void expectIdentical(const ExrFile& a, const ExrFile& b, const std::string& what = "") {
    ASSERT_EQ(a.channels, b.channels) << what;
    ASSERT_EQ(a.pixels.size(), b.pixels.size()) << what;
    size_t differing = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        differing += std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) != 0;
    EXPECT_EQ(differing, 0u) << what << ": " << differing << " of " << a.pixels.size()
                             << " values differ";
}

}  // namespace strahl::test
