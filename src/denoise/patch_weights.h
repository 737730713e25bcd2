#pragma once
// Non-local-means weights between pixel patches, normalised by the noise
// variance (Rousselle, Knaus and Zwicker 2012, eq. 4-6, as NFOR uses them):
// for pixels p and q = p + offset, per channel c
//
//   d_c(p, q) = [ (u_c(p) - u_c(q))^2 - (v_c(p) + min(v_c(p), v_c(q))) ]
//               / [ eps + k^2 (v_c(p) + v_c(q)) ]
//
// u the guide image, v its per-pixel variance, k the bandwidth. Subtracting
// the variance makes two noisy samples of the same value have distance ~0
// (the min() keeps a noisy pixel from pulling in everything when its
// neighbour is clean). The patch distance D(p, q) is the mean of d over the
// channels and over the (2f+1)^2 pixel pairs (p + s, q + s), |s| <= f, and
// the weight is w(p, q) = exp(-max(0, D)). Patch pixels outside the image
// are clamped to the border; q outside the image gets weight 0.
//
// Apart from the tiny eps, D scales as 1/k^2: the weights of several
// bandwidths come from one distance computed with k = 1, as
// patchWeight(D / k^2) (the regression fits all its candidates at once).

#include <algorithm>
#include <bit>
#include <vector>

#include "planar_image.h"

namespace strahl::denoise_detail {

// Weights below e^-kMaxWeightDistance count as 0: they change no sum
// measurably, and their products with small feature differences would be
// subnormal floats, which cost a hundred cycles each on x86.
constexpr float kMaxWeightDistance = 30.0f;
// The distance written for pairs that get no weight at all (q outside the image).
constexpr float kNoWeight = 1e30f;

// e^x for x in [-kMaxWeightDistance, 0], as 2^(x log2 e) split into an integer
// power (built in the exponent bits) and 2^f, f in [0, 1), by a degree-6
// polynomial (Taylor of 2^f = e^(f ln 2); relative error below 2e-7). Plain
// arithmetic, so the loops around it vectorise; std::exp does not.
inline float expNonPositive(float x) {
    const float t = x * 1.44269504f;  // log2(e), t in [-44, 0]
    // floor(t) as the truncation of t + 64 > 0, minus 64: no library call, no
    // branch, so it vectorises.
    const int i = static_cast<int>(t + 64.0f) - 64;
    const float f = t - static_cast<float>(i);
    const float l = 0.69314718f * f;
    const float p =
        1.0f +
        l * (1.0f +
             l * (0.5f + l * (1.0f / 6 + l * (1.0f / 24 + l * (1.0f / 120 + l * (1.0f / 720))))));
    return p * std::bit_cast<float>((i + 127) << 23);  // i >= -44: a normal float
}

// The weight of a patch distance D >= 0 (kNoWeight: 0).
inline float patchWeight(float D) {
    const float w = expNonPositive(-std::min(D, kMaxWeightDistance));
    return w * static_cast<float>(D < kMaxWeightDistance);
}

class PatchWeights {
public:
    // guide and variance have the same size and channel count.
    PatchWeights(const PlanarImage& guide, const PlanarImage& variance, int patchRadius, float k);

    // Writes the patch distance D(p, p + (dx, dy)) >= 0 for every p of
    // `region` (row-major, region.pixels() values) into `out`; kNoWeight
    // where p or p + (dx, dy) lies outside the image. `scratch` is reused
    // between calls.
    void distances(const Region& region, int dx, int dy, float* out,
                   std::vector<float>& scratch) const;

private:
    const PlanarImage& guide_;
    const PlanarImage& variance_;
    int f_;
    float k2_;
};

}  // namespace strahl::denoise_detail
