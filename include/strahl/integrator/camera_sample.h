#pragma once
// What one camera sample adds to the film: the integrator's radiance along the
// camera ray (its miss radiance if the ray saw nothing) and the first-hit AOVs.
// The ray tracer (render/renderer.cpp) and the rasterizer (raster/) both call
// this, so a hit they agree on is shaded identically whichever found it.

#include "strahl/core/ray.h"
#include "strahl/core/sampler.h"
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
// The object a valid hit belongs to, for the objectid AOV: the top-level
// shape's index (geomID), or for a hit inside an instance the instance's ID
// (shapes.size() + its index), so every placement of a group is its own object.
uint32_t objectId(const Hit& hit);

CameraSample shadeCameraSample(const World& world, const Integrator& integrator, const Ray& ray,
                               const Hit& hit, Sampler& sampler, ShadingStats& stats, bool wantAovs);

}  // namespace strahl
