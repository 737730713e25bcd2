// Height images through OpenImageIO (see height_image.h).

#include "height_image.h"

#include <cstddef>

#include "image_reader.h"

namespace strahl::scene_detail {

// More samples than any sensible height field (8192 x 8192) and a cap on what
// a corrupt or hostile header can make us allocate: 2^26 floats are 256 MiB.
constexpr size_t kMaxSamples = size_t(1) << 26;

HeightImage loadHeightImage(const std::filesystem::path& file) {
    const FloatImage pixels = readFloatImage(file, "height image", kMaxSamples);
    HeightImage image;
    image.columns = pixels.width;
    image.rows = pixels.height;
    image.heights.resize(static_cast<size_t>(pixels.width) * static_cast<size_t>(pixels.height));
    for (size_t k = 0; k < image.heights.size(); ++k) {
        // The Rec. 709 luminance of colour images.
        const float* p = &pixels.pixels[k * static_cast<size_t>(pixels.channels)];
        image.heights[k] =
            pixels.channels == 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
    }
    return image;
}

}  // namespace strahl::scene_detail
