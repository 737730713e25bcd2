#pragma once
// What one camera sample adds to the film: the integrator's radiance along the
// camera ray (its miss radiance if the ray saw nothing) and the first-hit AOVs.
// The ray tracer (render/renderer.cpp) and the rasterizer (raster/) both call
// this, so a hit they agree on is shaded identically whichever found it.

#include "strahl/core/ray.h"
#include "strahl/core/rng.h"
#include "strahl/film/film.h"
#include "strahl/integrator/integrator.h"
#include "strahl/integrator/world.h"

namespace strahl {

struct CameraSample {
    Color radiance{0.0f};  // finite: a non-finite result is dropped to black
    AovSample aov;
};

// `ray` is the camera ray with tfar = infinity, `hit` its closest hit (invalid
// for a miss). AOV values are computed only if `wantAovs`.
CameraSample shadeCameraSample(const World& world, const Integrator& integrator, const Ray& ray,
                               const Hit& hit, SampleRng& rng, ShadingStats& stats, bool wantAovs);

}  // namespace strahl
