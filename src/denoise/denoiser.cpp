// The NFOR pipeline (Bitterli et al. 2016; docs/denoising.md):
//  0. fireflies: each half's colour is capped at a multiple of the other
//     half's neighbourhood (limitOutliers; strahl's addition, biased);
//  1. features: each of albedo, normal and depth is the mean of its two
//     halves, prefiltered by NL-means with its own variance, estimated from
//     the halves' difference;
//  2. for each candidate bandwidth k, each half of the colour is fitted by
//     the collaborative first-order regression (regression.h) with weights
//     from the *other* half (cross-filtering: the weights do not see the
//     noise they average, which would otherwise survive the filter);
//  3. each candidate's error is estimated per pixel against the other half,
//     the estimates are smoothed, and each pixel takes the candidates in
//     the proportions a smoothed "which is best" map gives;
//  4. the result is kept within a few standard errors of each pixel's own
//     mean (limitToStandardErrors; strahl's addition).
// Every step that reads the colour variance reads robustVariance: the
// variance AOV smoothed over the neighbourhood without its largest values.

#include "strahl/denoise/denoiser.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "nl_means.h"
#include "patch_weights.h"
#include "planar_image.h"
#include "regression.h"
#include "strahl/core/error.h"

namespace strahl {

using denoise_detail::collaborativeRegression;
using denoise_detail::kFeatureCount;
using denoise_detail::nlMeans;
using denoise_detail::PatchWeights;
using denoise_detail::PlanarImage;
using denoise_detail::toInterleaved;
using denoise_detail::toPlanar;

namespace {

// Feature prefiltering (NFOR section 6): NL-means, 11 x 11 window, 7 x 7
// patches, bandwidth 0.5. First-hit features are nearly noise-free except
// where a pixel sees several surfaces or through depth of field; this
// removes what noise they carry without moving their edges.
constexpr int kFeatureWindow = 5;
constexpr int kFeaturePatch = 3;
constexpr float kFeatureBandwidth = 0.5f;
// The error estimates and the selection maps are smoothed by NL-means on
// the colour with 3 x 3 patches and bandwidth 1 over an 11 x 11 window: the
// per-pixel estimates rest on one sample of a squared difference each.
constexpr int kErrorWindow = 5;
constexpr int kErrorPatch = 1;
constexpr float kErrorBandwidth = 1.0f;

void checkBuffer(const std::vector<float>& buffer, int width, size_t expected,
                 const std::string& source, const char* what, int channels, bool depth,
                 bool nonNegative) {
    if (buffer.size() != expected * size_t(channels))
        fail(source, ": denoiser buffer '", what, "' has ", buffer.size(), " values, expected ",
             expected * size_t(channels));
    for (size_t i = 0; i < buffer.size(); ++i) {
        const float v = buffer[i];
        const bool ok = std::isfinite(v) ? (!nonNegative || v >= 0.0f)
                                         : depth && v == std::numeric_limits<float>::infinity();
        if (!ok) {
            const size_t pixel = i / size_t(channels);
            fail(source, ": denoiser buffer '", what, "' holds ", v, " at pixel (",
                 pixel % size_t(width), ", ", pixel / size_t(width), ") (",
                 depth         ? "depth must be finite or +inf"
                 : nonNegative ? "must be finite and >= 0"
                               : "must be finite",
                 ")");
        }
    }
}

// The half's features as kFeatureCount planes: albedo, normal, depth / maxDepth
// (0 where no sample hit).
PlanarImage featurePlanes(const DenoiseHalf& half, int width, int height, float maxDepth) {
    PlanarImage f(width, height, kFeatureCount);
    const size_t n = f.planeSize();
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) {
            f.plane(c)[i] = half.albedo[3 * i + size_t(c)];
            f.plane(3 + c)[i] = half.normal[3 * i + size_t(c)];
        }
        const float d = half.depth[i];
        f.plane(6)[i] = std::isfinite(d) && maxDepth > 0.0f ? d / maxDepth : 0.0f;
    }
    return f;
}

// Calls row(y) for every y in [0, height), rows in parallel: for the
// per-pixel steps, whose every output pixel depends only on the inputs (so
// the result does not depend on the thread count).
template <class Row>
void forEachRow(int height, Row&& row) {
    tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const auto& range) {
        for (int y = range.begin(); y != range.end(); ++y) row(y);
    });
}

// 3 x 3 box mean with clamped borders.
PlanarImage boxFilter3(const PlanarImage& in) {
    PlanarImage out(in.width, in.height, in.channels);
    forEachRow(in.height, [&](int y) {
        for (int c = 0; c < in.channels; ++c)
            for (int x = 0; x < in.width; ++x) {
                float sum = 0.0f;
                for (int j = -1; j <= 1; ++j)
                    for (int i = -1; i <= 1; ++i)
                        sum += in.at(c, std::clamp(x + i, 0, in.width - 1),
                                     std::clamp(y + j, 0, in.height - 1));
                out.at(c, x, y) = sum / 9.0f;
            }
    });
    return out;
}

// Calls visit(i, j) for the pixels of the (2r+1) x (2r+1) block around
// (x, y) that lie inside the image.
template <class Visit>
void forEachAround(int x, int y, int r, int width, int height, Visit&& visit) {
    for (int j = std::max(0, y - r); j <= std::min(height - 1, y + r); ++j)
        for (int i = std::max(0, x - r); i <= std::min(width - 1, x + r); ++i) visit(i, j);
}

// Fireflies: a value far above anything the other half shows near the pixel
// is one rare sample, not the image. The regression would spread it over its
// window (its weights come from the other half, which does not have it) into
// a bright blob. Each half's value is limited, per channel, to `factor` times
// the largest value of the other half in the 3 x 3 pixels around it (the
// pixel included, so a highlight both halves see stays). Biased, as every
// firefly filter is: the energy above the limit is lost.
void limitOutliers(PlanarImage (&color)[2], float factor) {
    const int W = color[0].width, H = color[0].height;
    PlanarImage limited[2] = {color[0], color[1]};
    forEachRow(H, [&](int y) {
        for (int h = 0; h < 2; ++h)
            for (int c = 0; c < 3; ++c)
                for (int x = 0; x < W; ++x) {
                    float most = 0.0f;
                    forEachAround(x, y, 1, W, H, [&](int i, int j) {
                        most = std::max(most, color[1 - h].at(c, i, j));
                    });
                    float& v = limited[h].at(c, x, y);
                    v = std::min(v, factor * most);
                }
    });
    color[0] = std::move(limited[0]);
    color[1] = std::move(limited[1]);
}

// The variance the filter works with: per channel, the larger of the pixel's
// own variance and the mean of its 5 x 5 neighbourhood's without the largest
// quarter (6 of 25). A pixel's variance from 16 samples is itself noisy:
//  - where light arrives through rare paths (Sponza's arcades), most pixels
//    saw none and report variance 0; the weights then find bright-sampled
//    pixels unlike everything and darken the region, and a consistency limit
//    (below) would keep those pixels black. The neighbourhood mean is the
//    region's variance;
//  - a small noisy lamp (the DamagedHelmet's visor) has a variance thousands
//    of times its neighbours'; dropping the largest values keeps it out of
//    the neighbours' estimates, where a plain mean would let them be pulled
//    up to the lamp.
// The quarter was chosen by measurement (docs/denoising.md): dropping 4
// still let the lamps through, dropping 8 or a median (half) left Sponza's
// unlit pixels black.
PlanarImage robustVariance(const PlanarImage& variance) {
    constexpr int kRadius = 2;
    PlanarImage out(variance.width, variance.height, variance.channels);
    const int W = variance.width, H = variance.height;
    forEachRow(H, [&](int y) {
        for (int c = 0; c < variance.channels; ++c)
            for (int x = 0; x < W; ++x) {
                float around[(2 * kRadius + 1) * (2 * kRadius + 1)];
                int n = 0;
                forEachAround(x, y, kRadius, W, H,
                              [&](int i, int j) { around[n++] = variance.at(c, i, j); });
                const int kept = n - n / 4;
                std::nth_element(around, around + kept, around + n);
                double sum = 0.0;
                for (int k = 0; k < kept; ++k) sum += around[k];
                out.at(c, x, y) = std::max(float(sum / kept), variance.at(c, x, y));
            }
    });
    return out;
}

// Consistency limit: the denoised value stays within `k` standard errors of
// the pixel's own mean, sigma = sqrt(variance) of the robust variance.
// Removing noise moves a pixel by about one standard error; a first-order
// fit can move it by far
// more where a neighbour it averaged with is much brighter and the features
// do not tell them apart (the small lamps seen through the DamagedHelmet's
// visor came out as bright crosses, 100 times too bright: such a value is
// not consistent with the pixel's own samples, so it is not kept).
void limitToStandardErrors(PlanarImage& denoised, const PlanarImage& mean,
                           const PlanarImage& variance, float k) {
    for (size_t i = 0; i < denoised.data.size(); ++i) {
        const float tolerance = k * std::sqrt(variance.data[i]);
        denoised.data[i] =
            std::clamp(denoised.data[i], mean.data[i] - tolerance, mean.data[i] + tolerance);
    }
}

// Step 1: the prefiltered features shared by both halves' regressions.
PlanarImage prefilterFeatures(const PlanarImage& f0, const PlanarImage& f1) {
    PlanarImage out(f0.width, f0.height, kFeatureCount);
    const size_t n = out.planeSize();
    // Albedo, normal and depth are filtered separately: each has its own edges.
    const int groups[3][2] = {{0, 3}, {3, 3}, {6, 1}};
    for (const auto& group : groups) {
        const int first = group[0], count = group[1];
        PlanarImage mean(f0.width, f0.height, count), diff(f0.width, f0.height, count);
        for (int c = 0; c < count; ++c)
            for (size_t i = 0; i < n; ++i) {
                const float a = f0.plane(first + c)[i], b = f1.plane(first + c)[i];
                mean.plane(c)[i] = 0.5f * (a + b);
                // E[(a - b)^2] = 2 var(half) and var(mean) = var(half) / 2.
                diff.plane(c)[i] = 0.25f * (a - b) * (a - b);
            }
        const PlanarImage variance = boxFilter3(diff);
        const PatchWeights weights(mean, variance, kFeaturePatch, kFeatureBandwidth);
        const PlanarImage filtered = nlMeans(mean, weights, kFeatureWindow);
        std::copy(filtered.data.begin(), filtered.data.end(), out.plane(first));
    }
    return out;
}

// One filtering pass over both halves: every candidate bandwidth's
// regression of each noisy half, with weights from the other half's guide,
// then the per-pixel choice among the candidates.
struct FilterPass {
    PlanarImage halves[2];  // each half filtered, candidates blended by the selection
    PlanarImage combined;   // their mean: the pass's result
};

// color: the noisy halves, each with variance colorVariance; guide: the
// images the weights compare (guide[1 - h] for half h), with guideVariance;
// guideMean, guideMeanVariance: their mean, which guides the smoothing of
// the error estimates.
FilterPass filterPass(const PlanarImage (&color)[2], const PlanarImage& colorVariance,
                      const PlanarImage (&guide)[2], const PlanarImage& guideVariance,
                      const PlanarImage& guideMean, const PlanarImage& guideMeanVariance,
                      const PlanarImage& features, const DenoiseSettings& settings) {
    const int W = color[0].width, H = color[0].height;
    const size_t n = color[0].planeSize();
    const int K = static_cast<int>(settings.bandwidths.size());
    std::vector<PlanarImage> filtered[2];
    for (int h = 0; h < 2; ++h) {
        const PatchWeights weights(guide[1 - h], guideVariance, settings.patchRadius, 1.0f);
        filtered[h] = collaborativeRegression(color[h], features, weights, settings.windowRadius,
                                              settings.bandwidths);
    }

    FilterPass pass{{PlanarImage(W, H, 3), PlanarImage(W, H, 3)}, PlanarImage(W, H, 3)};
    if (K == 1) {
        pass.halves[0] = filtered[0][0];
        pass.halves[1] = filtered[1][0];
    } else {
        // Each candidate's squared error, estimated per pixel: (F_A - c_B)^2
        // - var(c_B) is unbiased where F_A does not depend on c_B (its
        // weights do, a little, through the guide).
        PlanarImage errors(W, H, K);
        for (int k = 0; k < K; ++k) {
            float* error = errors.plane(k);
            for (size_t i = 0; i < n; ++i) {
                float e = 0.0f;
                for (int c = 0; c < 3; ++c) {
                    const float ea = filtered[0][size_t(k)].plane(c)[i] - color[1].plane(c)[i];
                    const float eb = filtered[1][size_t(k)].plane(c)[i] - color[0].plane(c)[i];
                    e += 0.5f * (ea * ea + eb * eb) - colorVariance.plane(c)[i];
                }
                error[i] = e / 3.0f;
            }
        }
        // Smoothed estimates, the best candidate per pixel, and the smoothed
        // one-hot choice as blending weights (no seams between choices).
        const PatchWeights smoothing(guideMean, guideMeanVariance, kErrorPatch, kErrorBandwidth);
        const PlanarImage smoothedErrors = nlMeans(errors, smoothing, kErrorWindow);
        PlanarImage best(W, H, K);
        for (size_t i = 0; i < n; ++i) {
            int arg = 0;
            for (int k = 1; k < K; ++k)
                if (smoothedErrors.plane(k)[i] < smoothedErrors.plane(arg)[i]) arg = k;
            best.plane(arg)[i] = 1.0f;
        }
        const PlanarImage selection = nlMeans(best, smoothing, kErrorWindow);
        for (int h = 0; h < 2; ++h)
            for (size_t i = 0; i < n; ++i) {
                float total = 0.0f;
                for (int k = 0; k < K; ++k) total += selection.plane(k)[i];
                for (int c = 0; c < 3; ++c) {
                    float v = 0.0f;
                    for (int k = 0; k < K; ++k)
                        v += selection.plane(k)[i] * filtered[h][size_t(k)].plane(c)[i];
                    pass.halves[h].plane(c)[i] = v / total;
                }
            }
    }
    for (size_t i = 0; i < pass.combined.data.size(); ++i)
        pass.combined.data[i] = 0.5f * (pass.halves[0].data[i] + pass.halves[1].data[i]);
    return pass;
}

}  // namespace

void checkDenoiseInput(const DenoiseInput& input, const std::string& source) {
    if (input.width <= 0 || input.height <= 0)
        fail(source, ": denoiser image size ", input.width, "x", input.height, " is not positive");
    const size_t n = size_t(input.width) * size_t(input.height);
    const char* names[2][4] = {{"half 0 beauty", "half 0 albedo", "half 0 normal", "half 0 depth"},
                               {"half 1 beauty", "half 1 albedo", "half 1 normal", "half 1 depth"}};
    for (int h = 0; h < 2; ++h) {
        const DenoiseHalf& half = input.halves[size_t(h)];
        checkBuffer(half.color, input.width, n, source, names[h][0], 3, false, false);
        checkBuffer(half.albedo, input.width, n, source, names[h][1], 3, false, false);
        checkBuffer(half.normal, input.width, n, source, names[h][2], 3, false, false);
        checkBuffer(half.depth, input.width, n, source, names[h][3], 1, true, true);
    }
    checkBuffer(input.variance, input.width, n, source, "variance", 3, false, true);
}

std::vector<float> denoise(const DenoiseInput& input, const DenoiseSettings& settings,
                           const std::string& source) {
    checkDenoiseInput(input, source);
    if (settings.windowRadius < 1 || settings.patchRadius < 0 || settings.bandwidths.empty() ||
        !(settings.outlierFactor >= 0.0f) || !(settings.maxStandardErrors >= 0.0f))
        fail(source,
             ": denoiser settings need a window radius >= 1, a patch radius >= 0, a "
             "bandwidth, and an outlier factor and a standard-error limit >= 0");
    const int W = input.width, H = input.height;

    std::vector<float> result;
    tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        float maxDepth = 0.0f;
        for (const DenoiseHalf& half : input.halves)
            for (float d : half.depth)
                if (std::isfinite(d)) maxDepth = std::max(maxDepth, d);
        const PlanarImage features =
            prefilterFeatures(featurePlanes(input.halves[0], W, H, maxDepth),
                              featurePlanes(input.halves[1], W, H, maxDepth));

        PlanarImage color[2] = {toPlanar(input.halves[0].color, W, H, 3),
                                toPlanar(input.halves[1].color, W, H, 3)};
        if (settings.outlierFactor > 0.0f) limitOutliers(color, settings.outlierFactor);
        // Each half holds about half the samples: twice the variance of the full mean.
        const PlanarImage fullVariance = robustVariance(toPlanar(input.variance, W, H, 3));
        PlanarImage halfVariance = fullVariance;
        for (float& v : halfVariance.data) v *= 2.0f;
        PlanarImage mean(W, H, 3);
        for (size_t i = 0; i < mean.data.size(); ++i)
            mean.data[i] = 0.5f * (color[0].data[i] + color[1].data[i]);

        // Weights from the other half's noisy colour (cross-filtering).
        FilterPass pass = filterPass(color, halfVariance, color, halfVariance, mean, fullVariance,
                                     features, settings);
        if (settings.maxStandardErrors > 0.0f)
            limitToStandardErrors(pass.combined, mean, fullVariance, settings.maxStandardErrors);
        // A first-order fit may dip below 0 in dark regions; radiance cannot.
        for (float& v : pass.combined.data) v = std::max(v, 0.0f);
        result = toInterleaved(pass.combined);
    });
    return result;
}

}  // namespace strahl
