#pragma once
// One sampled direction of a BSDF (bsdf.h states the conventions).

#include "strahl/core/math.h"

namespace strahl {

struct BsdfSample {
    Color f{0.0f};
    Vec3 wi{0.0f};
    float pdf = 0.0f;  // solid-angle density, or the lobe probability for a specular sample
    bool specular = false;
    bool transmission = false;
    float eta = 1.0f;  // relative index of refraction crossed (1 for reflection)
};

}  // namespace strahl
