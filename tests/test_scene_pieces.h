#pragma once
// Geometry that several accelerator tests build their scenes from: small
// meshes and fans of random rays shot at a scene from a shell around it.

#include <cmath>
#include <vector>

#include "strahl/core/ray.h"
#include "strahl/core/rng.h"
#include "strahl/geometry/triangle_mesh.h"

namespace strahl::test {

// A unit quad in the plane z = zPlane, two triangles, counter-clockwise seen
// from +z; its diagonal runs from (-1, -1) to (1, 1).
inline TriangleMesh unitQuad(float zPlane) {
    TriangleMesh m;
    m.positions = {{-1, -1, zPlane}, {1, -1, zPlane}, {1, 1, zPlane}, {-1, 1, zPlane}};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.reservePadding();
    return m;
}

// A 6 × 6 quad around z = −2, slightly warped so that it is not axis-aligned:
// the floor behind the implicit-shape test scenes.
inline TriangleMesh warpedBackdrop() {
    TriangleMesh m;
    m.positions = {{-3, -3, -2}, {3, -3, -2.5f}, {3, 3, -1.5f}, {-3, 3, -2}};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.reservePadding();
    return m;
}

// Rays from a sphere of radius 6 (lifted to z ≥ zLift, in front of the
// backdrop) towards uniform random points of the box [targetMin, targetMax].
// With scaleDirection the direction is also scaled by a random factor in
// [0.3, 1.5]: not normalised, so t is in units of |dir|, which shapes must honour.
struct RayFan {
    uint64_t stream = 7;  // PCG stream: different tests draw different rays
    float zLift = 1.0f;
    Vec3 targetMin{-1.0f}, targetMax{1.0f};
    bool scaleDirection = false;
};

inline std::vector<Ray> raysFromShell(int count, uint64_t seed, const RayFan& fan) {
    Pcg32 rng(seed, fan.stream);
    auto uniform = [&](float lo, float hi) { return lo + (hi - lo) * rng.nextFloat(); };
    std::vector<Ray> rays(static_cast<size_t>(count));
    for (Ray& ray : rays) {
        Vec3 from;
        do {
            from = Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
        } while (glm::dot(from, from) > 1.0f || glm::dot(from, from) < 0.01f);
        from = 6.0f * glm::normalize(from);
        from.z = std::abs(from.z) + fan.zLift;
        const Vec3 to(uniform(fan.targetMin.x, fan.targetMax.x),
                      uniform(fan.targetMin.y, fan.targetMax.y),
                      uniform(fan.targetMin.z, fan.targetMax.z));
        ray.origin = from;
        ray.dir = to - from;
        if (fan.scaleDirection) ray.dir = ray.dir * uniform(0.3f, 1.5f);
    }
    return rays;
}

}  // namespace strahl::test
