#pragma once
// Adaptive sampling: after a minimum number of samples, a pixel whose noise is
// below a threshold stops, and the render's later passes go only to the
// pixels that are still noisy (docs/adaptive.md).
//
// The noise of a pixel is the standard error of its mean radiance, measured
// in a display-like encoding: with I the mean of the three channels and s the
// standard error of I, a square-root encoding (about the sRGB curve) turns s
// into s / (2 sqrt(I)) (first order: d sqrt(I) = dI / (2 sqrt(I))), so dark
// pixels are not held to an absolute error they could never show, and bright
// ones not to a relative error nobody sees. s comes from the film's running
// variance (Welford), bounded above by the mean of the channels' standard
// errors (Cauchy-Schwarz: sd(sum) <= sum of sd), as the channels' covariance
// is not kept.
//
// A pixel stops when the noise of every pixel of its 3 x 3 neighbourhood
// (clipped to the rendered rectangle) is below the threshold: a pixel whose
// few samples happened to agree is not fooled if its neighbours are still
// noisy. Decisions are taken only between sample passes, from the film alone,
// and recorded in it (Film::trackConvergence): the same film gives the same
// decisions whatever the threads, tiles, checkpoints or ranks that made it.

#include <cstddef>

#include "strahl/film/film.h"

namespace strahl {

struct AdaptiveSampling {
    // Off at 0. Cycles' noise threshold is comparable; 0.01 is a good start.
    float threshold = 0.0f;
    // Samples every pixel takes before any may stop: too few and the variance
    // estimate itself is noise (at 16 its relative error is about 37 %: sqrt(2 / (n - 1))).
    int minSamples = 16;
    bool enabled() const { return threshold > 0.0f; }
};

// The noise of pixel (x, y) of `film` as defined above; +inf below 2 samples,
// 0 for a pixel all of whose samples were black.
float pixelNoise(const Film& film, int x, int y);

// Stops (Film::setConverged) every running pixel of `film` whose
// neighbourhood is below the threshold. Returns the pixels still running.
// `threads` as RenderOptions::threads (0: all).
size_t stopConvergedPixels(Film& film, const AdaptiveSampling& adaptive, int threads);

}  // namespace strahl
