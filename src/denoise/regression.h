#pragma once
// Collaborative first-order regression, the core of NFOR (Bitterli et al.
// 2016, sections 4 and 5). For every pixel p, a weighted least-squares fit
// of the colour over the window Omega_p = the (2r+1)^2 pixels around p,
//
//   beta_p = argmin_b  sum_{q in Omega_p} w(p, q) | c(q) - b^T x_p(q) |^2,
//   x_p(q) = [1, f(q) - f(p)]   (f: the kFeatureCount prefiltered features),
//
// with the NL-means weights w of patch_weights.h, computed on a guide image
// other than c (the other half of the samples: the weights do not see the
// noise they average). The fit is then evaluated at every pixel of the
// window, not only at p ("collaborative"), and each pixel q averages all the
// fits that cover it with the same weights:
//
//   out(q) = sum_p w(p, q) beta_p^T x_p(q) / sum_p w(p, q).
//
// The normal equations get a small ridge (see kRidge in regression.cpp) so
// that a window where a feature is constant gives a zero-order (NL-means)
// fit for it instead of a singular system.

#include <vector>

#include "patch_weights.h"
#include "planar_image.h"

namespace strahl::denoise_detail {

constexpr int kFeatureCount = 7;  // albedo RGB, normal XYZ, depth

// color: 3 channels; features: kFeatureCount channels of the same size;
// weights built with bandwidth 1. Returns one filtered colour image per
// bandwidth k (weights patchWeight(D / k^2)), all fitted in one sweep over
// the windows. Runs on the calling TBB arena.
std::vector<PlanarImage> collaborativeRegression(const PlanarImage& color,
                                                 const PlanarImage& features,
                                                 const PatchWeights& weights, int windowRadius,
                                                 const std::vector<float>& bandwidths);

}  // namespace strahl::denoise_detail
