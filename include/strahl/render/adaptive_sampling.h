#pragma once
// Adaptive sampling: after a minimum number of samples, a pixel whose noise is
// below a threshold stops, and the render's later passes go only to the
// pixels that are still noisy (docs/adaptive.md).
//
// The noise of a pixel is the relative standard error of its mean radiance:
// with I the mean of the three channels of the pixel's mean and s the
// standard error of I,
//     e = s / sqrt(I^2 + 0.1^2),
// which is s / I for I well above 0.1 and 10 s for darker pixels, so a dark
// pixel is not held to a relative error it could never show. Squared and
// averaged over the image, e^2 is the relative MSE pbrt's and Mitsuba's
// papers measure renders by (with the same epsilon 0.01). s comes from the
// film's running variance (Welford), bounded above by the mean of the
// channels' standard errors (Cauchy-Schwarz: sd(sum) <= sum of sd), as the
// channels' covariance is not kept.
//
// A pixel stops when the noise of every pixel of its 3 x 3 neighbourhood
// (clipped to the rendered rectangle) is below the threshold: a pixel whose
// few samples happened to agree is not fooled if its neighbours are still
// noisy. (A 5 x 5 neighbourhood, used before, kept a ring of quiet pixels
// sampling around every noisy one: for the same image error it took up to
// 1.9x the samples of 3 x 3 on the default scene; bench/RESULTS.md.)
// Decisions are taken only between sample passes, from the film alone, and
// recorded in it (Film::trackConvergence): the same film gives the same
// decisions whatever the threads, tiles, checkpoints or ranks that made it.

#include <cstddef>

#include "strahl/film/film.h"

namespace strahl {

// The neighbourhood a decision looks at: (2 r + 1)^2 pixels.
inline constexpr int kNeighbourhoodRadius = 1;

// The level below which a pixel's error counts as absolute (see above).
inline constexpr float kDarkFloor = 0.1f;

struct AdaptiveSampling {
    // Off at 0. The relative error a pixel may keep: 0.05 is a good start.
    float threshold = 0.0f;
    // Samples every pixel takes before any may stop: too few and the variance
    // estimate itself is noise (at 16 its relative error is about 37 %: sqrt(2 / (n - 1))).
    int minSamples = 16;
    bool enabled() const { return threshold > 0.0f; }
};

// Whether pixels are judged after `samples` passes: after minSamples, then
// after every eighth more (16, 18, 20, 22, 24, 27, 30, 33, 37, ...): about
// eight decisions per doubling, so their cost stays small beside the passes',
// and a pixel takes at most 1/8 more samples than it needed. It depends on
// the pass count alone, so a resumed render decides where the whole one did.
bool isDecisionPass(int samples, int minSamples);

// The noise of pixel (x, y) of `film` as defined above; +inf below 2 samples,
// 0 for a pixel all of whose samples were the same.
float pixelNoise(const Film& film, int x, int y);

// Stops (Film::setConverged) every running pixel of `film` whose
// neighbourhood is below the threshold. Returns the pixels still running.
// Runs in the caller's task arena (its thread count).
size_t stopConvergedPixels(Film& film, const AdaptiveSampling& adaptive);

}  // namespace strahl
