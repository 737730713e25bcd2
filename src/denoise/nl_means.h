#pragma once
// Non-local means with a separate guide (weights from patch_weights.h):
//   out(p) = sum_q w(p, q) data(q) / sum_q w(p, q),  q in the (2r+1)^2 window
// around p. The centre pixel's weight is 1, so the sum is never 0.

#include "patch_weights.h"
#include "planar_image.h"

namespace strahl::denoise_detail {

// Runs on the calling TBB arena; each output pixel depends only on its window.
PlanarImage nlMeans(const PlanarImage& data, const PatchWeights& weights, int windowRadius);

}  // namespace strahl::denoise_detail
