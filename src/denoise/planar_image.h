#pragma once
// The denoiser's working image: one contiguous plane per channel, so the inner
// loops run along rows of one channel and vectorise.

#include <cstddef>
#include <vector>

namespace strahl::denoise_detail {

struct PlanarImage {
    int width = 0, height = 0, channels = 0;
    size_t stride = 0;        // floats from one plane to the next (planeStride)
    std::vector<float> data;  // plane c, row y, column x at c*stride + y*width + x

    PlanarImage() = default;
    PlanarImage(int w, int h, int c)
        : width(w),
          height(h),
          channels(c),
          stride(planeStride(size_t(w) * size_t(h))),
          data(stride * size_t(c), 0.0f) {}

    // Plane c starts c cache lines past a multiple of 4 KiB: planes whose
    // starts differ by a multiple of 4 KiB share L1 cache sets, and loops
    // that read many planes at once (the regression reads 24) would thrash.
    static size_t planeStride(size_t pixels) { return (pixels + 1023) / 1024 * 1024 + 16; }

    size_t planeSize() const { return size_t(width) * size_t(height); }
    float* plane(int c) { return data.data() + size_t(c) * stride; }
    const float* plane(int c) const { return data.data() + size_t(c) * stride; }
    float& at(int c, int x, int y) { return plane(c)[size_t(y) * size_t(width) + size_t(x)]; }
    float at(int c, int x, int y) const { return plane(c)[size_t(y) * size_t(width) + size_t(x)]; }
};

// Interleaved (x, y, channel) <-> planar.
PlanarImage toPlanar(const std::vector<float>& interleaved, int width, int height, int channels);
std::vector<float> toInterleaved(const PlanarImage& image);

// A rectangle of pixels [x0, x1) x [y0, y1); may reach outside the image.
struct Region {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    size_t pixels() const { return size_t(width()) * size_t(height()); }
};

// Square tiles of `size` pixels covering the image, row by row.
std::vector<Region> imageTiles(int width, int height, int size);

}  // namespace strahl::denoise_detail
