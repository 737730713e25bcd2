#include "strahl/render/adaptive_sampling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "strahl/core/error.h"

namespace strahl {

bool isDecisionPass(int samples, int minSamples) {
    for (int n = minSamples; n <= samples; n += std::max(1, n / 8))
        if (n == samples) return true;
    return false;
}

float pixelNoise(const Film& film, int x, int y) {
    const Film::Estimate e = film.estimate(x, y);
    if (e.samples < 2) return kInfinity;
    const float mean = std::max((e.mean.r + e.mean.g + e.mean.b) / 3.0f, 0.0f);
    const float error = (std::sqrt(e.varianceOfMean.r) + std::sqrt(e.varianceOfMean.g) +
                         std::sqrt(e.varianceOfMean.b)) /
                        3.0f;
    if (error == 0.0f) return 0.0f;  // every sample the same (black, or a flat emitter)
    return error / std::sqrt(mean * mean + kDarkFloor * kDarkFloor);
}

size_t stopConvergedPixels(Film& film, const AdaptiveSampling& adaptive) {
    constexpr int kR = kNeighbourhoodRadius;
    if (!film.tracksConvergence()) fail("adaptive sampling: the film does not track convergence");
    const PixelRect crop = film.crop();
    const int width = crop.width(), height = crop.height();
    const auto at = [&](int x, int y) { return size_t(y) * size_t(width) + size_t(x); };
    // The noise of the pixels a running pixel's decision reads (itself and
    // its neighbours); stopped regions cost nothing. NaN: not needed.
    std::vector<float> noise(size_t(width) * size_t(height), std::nanf(""));
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < width; ++x) {
                bool needed = false;
                for (int ny = std::max(y - kR, 0); ny <= std::min(y + kR, height - 1) && !needed;
                     ++ny)
                    for (int nx = std::max(x - kR, 0); nx <= std::min(x + kR, width - 1); ++nx)
                        if (!film.converged(crop.x0 + nx, crop.y0 + ny)) {
                            needed = true;
                            break;
                        }
                if (needed) noise[at(x, y)] = pixelNoise(film, crop.x0 + x, crop.y0 + y);
            }
    });
    // Each row only writes its own pixels' flags and reads the noise
    // computed above: the result does not depend on the partition.
    return tbb::parallel_reduce(
        tbb::blocked_range<int>(0, height), size_t{0},
        [&](const tbb::blocked_range<int>& rows, size_t running) {
            for (int y = rows.begin(); y != rows.end(); ++y)
                for (int x = 0; x < width; ++x) {
                    if (film.converged(crop.x0 + x, crop.y0 + y)) continue;
                    float worst = 0.0f;
                    for (int ny = std::max(y - kR, 0); ny <= std::min(y + kR, height - 1); ++ny)
                        for (int nx = std::max(x - kR, 0); nx <= std::min(x + kR, width - 1); ++nx)
                            worst = std::max(worst, noise[at(nx, ny)]);
                    if (worst < adaptive.threshold)
                        film.setConverged(crop.x0 + x, crop.y0 + y);
                    else
                        ++running;
                }
            return running;
        },
        [](size_t a, size_t b) { return a + b; });
}

}  // namespace strahl
