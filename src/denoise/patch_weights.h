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

#include "planar_image.h"

namespace strahl::denoise_detail {

class PatchWeights {
public:
    // guide and variance have the same size and channel count.
    PatchWeights(const PlanarImage& guide, const PlanarImage& variance, int patchRadius, float k);

    // Writes w(p, p + (dx, dy)) for every p of `region` (row-major,
    // region.pixels() values) into `out`; 0 where p or p + (dx, dy) lies
    // outside the image. `scratch` is reused between calls.
    void compute(const Region& region, int dx, int dy, float* out,
                 std::vector<float>& scratch) const;

private:
    const PlanarImage& guide_;
    const PlanarImage& variance_;
    int f_;
    float k2_;
};

}  // namespace strahl::denoise_detail
