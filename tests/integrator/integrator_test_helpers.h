#pragma once
// Shared by the integrator tests: two uniform random numbers as a sample point.

#include "strahl/core/math.h"
#include "strahl/core/rng.h"

namespace strahl::test {

// The next two floats of `rng` as a point of [0,1)^2, x drawn first.
inline Vec2 next2D(Pcg32& rng) {
    const float x = rng.nextFloat();
    return Vec2(x, rng.nextFloat());
}

}  // namespace strahl::test
