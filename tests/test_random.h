#pragma once
// Shared by the sampling tests of every folder: two uniform random numbers as
// a sample point.

#include "strahl/core/math.h"
#include "strahl/core/rng.h"

namespace strahl::test {

// The next two floats of `rng` as a point of [0,1)^2, x drawn first (one
// statement, Vec2(rng.nextFloat(), rng.nextFloat()), would leave the order
// of the two draws to the compiler).
inline Vec2 next2D(Pcg32& rng) {
    const float x = rng.nextFloat();
    return Vec2(x, rng.nextFloat());
}

}  // namespace strahl::test
