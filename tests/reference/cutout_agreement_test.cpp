// Alpha cut-outs in the accelerators (geometry/cutout.h): Embree's filter
// functions and the naive loop skip the same holes — hit for hit on random
// rays, for nearest hits, occlusion and instanced prototypes — and what lies
// behind a hole is found.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "strahl/accel/accel.h"
#include "strahl/core/rng.h"
#include "strahl/reference/naive_accel.h"

namespace strahl {
namespace {

// Solid where the barycentric u lies in the lower half of each of 8 stripes:
// about half of every triangle is a hole, with edges inside triangles.
class StripeCutout final : public Cutout {
public:
    bool solid(uint32_t, float u, float) const noexcept override {
        const float s = 8.0f * u;
        return s - std::floor(s) < 0.5f;
    }
};

// A z = const grid of cells x cells quads over [-2, 2]^2.
TriangleMesh grid(float z, int cells) {
    TriangleMesh m;
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i)
            m.positions.emplace_back(-2.0f + 4.0f * float(i) / float(cells),
                                     -2.0f + 4.0f * float(j) / float(cells), z);
    const auto row = static_cast<uint32_t>(cells + 1);
    for (uint32_t j = 0; j < uint32_t(cells); ++j)
        for (uint32_t i = 0; i < uint32_t(cells); ++i) {
            const uint32_t a = j * row + i;
            m.indices.insert(m.indices.end(), {a, a + 1, a + row + 1, a, a + row + 1, a + row});
        }
    m.reservePadding();
    return m;
}

// Rays from above the grids, downwards, in slightly random directions.
std::vector<Ray> downwardRays(int n, uint64_t seed) {
    Pcg32 rng(seed, 3);
    std::vector<Ray> rays;
    for (int k = 0; k < n; ++k) {
        Ray r;
        // Inside [-1.5, 1.5]^2, so that even the most slanted ray meets both grids.
        r.origin = Vec3(3.0f * rng.nextFloat() - 1.5f, 3.0f * rng.nextFloat() - 1.5f, 5.0f);
        r.dir = glm::normalize(Vec3(0.1f * rng.nextFloat() - 0.05f, 0.1f * rng.nextFloat() - 0.05f, -1.0f));
        rays.push_back(r);
    }
    return rays;
}

struct StripedScene {
    TriangleMesh top = grid(1.0f, 6), bottom = grid(0.0f, 3);
    StripeCutout stripes;
    std::vector<ShapeRef> shapes{ShapeRef{&top, nullptr, &stripes}, ShapeRef{&bottom, nullptr, nullptr}};
};

TEST(Cutout, EmbreeAndTheNaiveTracerSkipTheSameHoles) {
    const StripedScene scene;
    const auto naive = buildNaiveAccel(std::span<const ShapeRef>(scene.shapes));
    const auto embree = buildEmbreeAccel(std::span<const ShapeRef>(scene.shapes), {});
    int throughHoles = 0, onTop = 0;
    for (const Ray& ray : downwardRays(4000, 7)) {
        const Hit a = embree->intersect(ray), b = naive->intersect(ray);
        ASSERT_EQ(a.valid(), b.valid());
        ASSERT_TRUE(a.valid());  // the solid bottom grid catches what the top lets through
        EXPECT_EQ(a.geomID, b.geomID);
        EXPECT_EQ(a.primID, b.primID);
        EXPECT_NEAR(a.t, b.t, 1e-5f);
        if (a.geomID == 0) {
            ++onTop;
            EXPECT_TRUE(scene.stripes.solid(a.primID, a.u, a.v)) << "a hit on a hole";
        } else {
            ++throughHoles;
        }
        // A shadow ray that ends above the bottom grid is blocked only by the solid top.
        Ray shadow = ray;
        shadow.tfar = (ray.origin.z - 0.5f) / -ray.dir.z;
        EXPECT_EQ(embree->occluded(shadow), a.geomID == 0);
        EXPECT_EQ(naive->occluded(shadow), a.geomID == 0);
    }
    // About half of the top grid is holes.
    EXPECT_GT(throughHoles, 1600);
    EXPECT_GT(onTop, 1600);
}

TEST(Cutout, InstancedPrototypesKeepTheirHoles) {
    const StripedScene scene;
    AccelScene instanced;
    instanced.prototypes.push_back(scene.shapes);
    instanced.instances.push_back(AccelInstance{0, glm::translate(Mat4(1.0f), Vec3(0, 0, -2))});
    const auto naive = buildNaiveAccel(instanced);
    const auto embree = buildEmbreeAccel(instanced, {});
    int throughHoles = 0;
    for (const Ray& ray : downwardRays(2000, 11)) {
        const Hit a = embree->intersect(ray), b = naive->intersect(ray);
        ASSERT_TRUE(a.valid() && b.valid());
        EXPECT_EQ(a.geomID, b.geomID);
        EXPECT_EQ(a.primID, b.primID);
        EXPECT_EQ(a.instID, b.instID);
        throughHoles += a.geomID == 1;
    }
    EXPECT_GT(throughHoles, 800);
}

}  // namespace
}  // namespace strahl
