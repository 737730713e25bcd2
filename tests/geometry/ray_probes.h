#pragma once
// Random rays and a brute-force nearest hit over a UserShape's primitives, for
// the geometry tests of implicit and parametric surfaces.

#include <random>

#include "strahl/geometry/user_shape.h"
#include "strahl/core/point3.h"

namespace strahl {

inline DVec3 randomPoint(std::mt19937& rng, double extent) {
    std::uniform_real_distribution<double> u(-extent, extent);
    return DVec3(u(rng), u(rng), u(rng));
}

inline DVec3 randomDirection(std::mt19937& rng) {
    std::normal_distribution<double> n;
    for (;;) {
        const DVec3 d(n(rng), n(rng), n(rng));
        if (glm::length(d) > 1e-3) return glm::normalize(d);
    }
}

// A ray from a random point at `distance` from the origin towards a random
// point of the cube [-extent, extent]³.
inline Ray rayTowards(std::mt19937& rng, double distance, double extent) {
    Ray ray;
    ray.origin = Vec3(randomDirection(rng) * distance);
    ray.dir = Vec3(glm::normalize(randomPoint(rng, extent) - DVec3(ray.origin)));
    return ray;
}

// The nearest hit over all of a shape's cells, as an accelerator would find
// it: each cell is asked with tfar shrunk to the best hit so far.
inline Hit nearestHit(const UserShape& shape, const Ray& ray) {
    Hit best;
    for (uint32_t prim = 0; prim < shape.primitiveCount(); ++prim) {
        Ray clipped = ray;
        clipped.tfar = best.t;
        Hit hit;
        if (shape.intersect(clipped, prim, hit)) {
            best = hit;
            best.geomID = 0;
            best.primID = prim;
        }
    }
    return best;
}

}  // namespace strahl
