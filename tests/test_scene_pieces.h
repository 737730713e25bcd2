#pragma once
// Geometry that several accelerator tests build their scenes from: small
// meshes and fans of random rays shot at a scene from a shell around it.

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "strahl/core/ray.h"
#include "strahl/core/rng.h"
#include "strahl/geometry/catmull_clark.h"
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

// The cube [-1, 1]³ as a subdivision cage of six quads, counter-clockwise
// seen from outside; vertex i is at (±1, ±1, ±1) by the bits of i (x, y, z).
inline SubdivisionCage cubeCage() {
    SubdivisionCage c;
    for (int i = 0; i < 8; ++i) c.positions.emplace_back(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0);
    c.faceSizes.assign(6, 4);
    c.indices = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};
    return c;
}

// A subdivided icosahedron projected onto a sphere: 20 * 4^level triangles,
// closed, every edge shared by two triangles, irregular float coordinates.
inline TriangleMesh icosphere(int level, const Vec3& centre, float radius) {
    const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<Vec3> unit = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                              {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                              {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (Vec3& p : unit) p = glm::normalize(p);
    std::vector<uint32_t> tris = {0, 11, 5, 0, 5,  1,  0,  1,  7,  0,  7, 10, 0, 10, 11,
                                  1, 5,  9, 5, 11, 4,  11, 10, 2,  10, 7, 6,  7, 1,  8,
                                  3, 9,  4, 3, 4,  2,  3,  2,  6,  3,  6, 8,  3, 8,  9,
                                  4, 9,  5, 2, 4,  11, 6,  2,  10, 8,  6, 7,  9, 8,  1};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto found = midpoints.find(key);
            if (found != midpoints.end()) return found->second;
            unit.push_back(glm::normalize(unit[a] + unit[b]));
            const auto index = static_cast<uint32_t>(unit.size() - 1);
            midpoints.emplace(key, index);
            return index;
        };
        std::vector<uint32_t> finer;
        for (size_t t = 0; t < tris.size(); t += 3) {
            const uint32_t a = tris[t], b = tris[t + 1], c = tris[t + 2];
            const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        tris = std::move(finer);
    }
    TriangleMesh m;
    for (const Vec3& p : unit) m.positions.push_back(centre + radius * p);
    m.indices = std::move(tris);
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
