#include "strahl/job/denoise_film.h"

#include <algorithm>

#include "strahl/core/error.h"

namespace strahl {

DenoiseInput denoiseInputOf(const Film& film) {
    if (!film.keepsHalves()) fail("denoise: the film does not keep the sample halves");
    const auto& aovs = film.aovs();
    if (std::find(aovs.begin(), aovs.end(), AovKind::Variance) == aovs.end())
        fail("denoise: the film has no variance AOV");
    DenoiseInput input;
    input.width = film.crop().width();
    input.height = film.crop().height();
    for (int h = 0; h < 2; ++h) {
        DenoiseHalf& half = input.halves[size_t(h)];
        half.color = film.resolveHalfBeauty(h);
        half.albedo = film.resolveHalfAov(h, AovKind::Albedo);
        half.normal = film.resolveHalfAov(h, AovKind::Normal);
        half.depth = film.resolveHalfAov(h, AovKind::Depth);
    }
    input.variance = film.resolveAov(AovKind::Variance);
    return input;
}

}  // namespace strahl
