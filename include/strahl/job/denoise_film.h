#pragma once
// The bridge from a rendered film to the denoiser (denoise/denoiser.h): the
// even and odd sample halves' beauty and features, and the variance AOV.

#include "strahl/denoise/denoiser.h"
#include "strahl/film/film.h"

namespace strahl {

// Throws strahl::Error if the film does not keep the halves (Film::keepHalves)
// or lacks the variance AOV.
DenoiseInput denoiseInputOf(const Film& film);

}  // namespace strahl
