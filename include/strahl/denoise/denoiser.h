#pragma once
// The denoiser: Nonlinearly Weighted First-Order Regression (NFOR, Bitterli et
// al. 2016), a feature-guided filter for Monte Carlo images that estimates its
// own error from two independent half renders. docs/denoising.md explains the
// method, its parameters and why it was chosen.
//
// Input: the beauty and the first-hit features (albedo, normal, depth) of the
// even and of the odd samples of every pixel, each the mean over its half, and
// the variance of the full image's beauty mean (the film's variance AOV).
// Output: the denoised beauty. Every step is a per-pixel function of its
// inputs computed in a fixed order, so the result is bit-identical for any
// thread count.

#include <array>
#include <string>
#include <vector>

namespace strahl {

// One half of the samples: row-major, top row first, interleaved channels.
struct DenoiseHalf {
    std::vector<float> color;   // RGB, scene-linear
    std::vector<float> albedo;  // RGB
    std::vector<float> normal;  // XYZ, world space (a mean: shorter than 1 at edges)
    std::vector<float> depth;   // 1 channel, +inf where no sample of the half hit
};

struct DenoiseInput {
    int width = 0, height = 0;
    std::array<DenoiseHalf, 2> halves;  // even samples, odd samples
    std::vector<float> variance;        // RGB: variance of the full beauty mean
};

struct DenoiseSettings {
    // The defaults were chosen by measurement (docs/denoising.md): against
    // NFOR's 19 x 19 windows, 7 x 7 patches and bandwidths 0.5 and 1, these
    // give lower error on strahl's test scenes at a third of the time.
    int windowRadius = 5;  // regression window: (2r+1)^2 pixels, 11 x 11
    int patchRadius = 1;   // NL-means patches of the regression weights: 3 x 3
    // Candidate bandwidths k of the regression weights: larger keeps less
    // detail and removes more noise; the MSE estimate picks per pixel.
    std::vector<float> bandwidths{0.35f, 1.0f};
    // Firefly limit (biased): before filtering, each half's value is capped,
    // per channel, at this factor times the other half's largest value in the
    // 3 x 3 pixels around it; 0 = off. 4 by measurement (docs/denoising.md):
    // on the default scene at 16 spp it halves the error (relMSE 0.0115 ->
    // 0.0068), with 2 or 8 slightly worse.
    float outlierFactor = 4.0f;
    // Consistency limit: the result stays within this many standard errors
    // of each pixel's own mean (the standard error from the variance AOV,
    // smoothed as everywhere in the filter: at least the mean of its 5 x 5
    // neighbourhood without the largest quarter); 0 = off. 3 by measurement
    // (docs/denoising.md): it removes the first-order fit's overshoots next
    // to small bright lights (DamagedHelmet relMSE 1.30 -> 0.019).
    float maxStandardErrors = 3.0f;
    int threads = 0;  // 0 = all cores
};

// Checks sizes and values: every buffer width x height x channels, colours,
// albedos, normals and the variance finite (the variance >= 0), depths finite
// or +inf. Throws strahl::Error naming `source` and the first bad buffer or
// pixel otherwise.
void checkDenoiseInput(const DenoiseInput& input, const std::string& source);

// The denoised beauty, RGB, width x height, interleaved. Throws strahl::Error
// (via checkDenoiseInput) for bad input.
std::vector<float> denoise(const DenoiseInput& input, const DenoiseSettings& settings = {},
                           const std::string& source = "denoise");

}  // namespace strahl
