#include "planar_image.h"

#include <algorithm>

namespace strahl::denoise_detail {

PlanarImage toPlanar(const std::vector<float>& interleaved, int width, int height, int channels) {
    PlanarImage image(width, height, channels);
    const size_t n = image.planeSize();
    for (int c = 0; c < channels; ++c) {
        float* plane = image.plane(c);
        for (size_t i = 0; i < n; ++i) plane[i] = interleaved[i * size_t(channels) + size_t(c)];
    }
    return image;
}

std::vector<float> toInterleaved(const PlanarImage& image) {
    const size_t n = image.planeSize();
    std::vector<float> out(n * size_t(image.channels));
    for (int c = 0; c < image.channels; ++c) {
        const float* plane = image.plane(c);
        for (size_t i = 0; i < n; ++i) out[i * size_t(image.channels) + size_t(c)] = plane[i];
    }
    return out;
}

std::vector<Region> imageTiles(int width, int height, int size) {
    std::vector<Region> tiles;
    for (int y = 0; y < height; y += size)
        for (int x = 0; x < width; x += size)
            tiles.push_back({x, y, std::min(x + size, width), std::min(y + size, height)});
    return tiles;
}

}  // namespace strahl::denoise_detail
