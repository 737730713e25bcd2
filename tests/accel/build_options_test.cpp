// AccelBuildOptions: every BVH quality and compact mode finds the same hits,
// compact mode saves memory, and the memory limit stops the build with a
// strahl::Error instead of letting it grow.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "strahl/accel/accel.h"
#include "strahl/core/error.h"
#include "strahl/core/rng.h"
#include "test_support.h"

namespace strahl {
namespace {

// A grid of (n+1)^2 vertices over [-1, 1]^2, bumped in z so the BVH has work.
TriangleMesh bumpyGrid(int n) {
    TriangleMesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float x = -1.0f + 2.0f * float(i) / float(n);
            const float y = -1.0f + 2.0f * float(j) / float(n);
            m.positions.push_back(Vec3(x, y, 0.1f * std::sin(9.0f * x) * std::cos(7.0f * y)));
        }
    const auto at = [n](int i, int j) { return uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1),
                                               at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    m.reservePadding();
    return m;
}

TEST(AccelBuildOptions, EveryQualityAndCompactModeFindsTheSameHits) {
    const TriangleMesh grid = bumpyGrid(120);
    const TriangleMesh* meshes[] = {&grid};
    const auto reference = buildEmbreeAccel(meshes, {});
    for (BvhQuality quality : {BvhQuality::Low, BvhQuality::Medium, BvhQuality::High})
        for (bool compact : {false, true}) {
            AccelBuildOptions options;
            options.quality = quality;
            options.compact = compact;
            const auto accel = buildEmbreeAccel(meshes, options);
            Pcg32 rng(7, 3);
            for (int r = 0; r < 2000; ++r) {
                Ray ray;
                ray.origin = Vec3(2.0f * rng.nextFloat() - 1.0f, 2.0f * rng.nextFloat() - 1.0f, 3.0f);
                ray.dir = glm::normalize(Vec3(0.2f * rng.nextFloat() - 0.1f, 0.1f, -1.0f));
                const Hit a = reference->intersect(ray), b = accel->intersect(ray);
                ASSERT_EQ(a.valid(), b.valid()) << bvhQualityName(quality) << " " << compact;
                if (!a.valid()) continue;
                // The same triangle, and t to float rounding (Embree's triangle
                // test depends on the layout: indexed or copied vertices).
                EXPECT_EQ(a.primID, b.primID) << bvhQualityName(quality) << " " << compact;
                EXPECT_NEAR(a.t, b.t, 1e-5f * a.t);
            }
        }
}

TEST(AccelBuildOptions, CompactModeTakesLessBvhMemory) {
    const TriangleMesh grid = bumpyGrid(200);
    const TriangleMesh* meshes[] = {&grid};
    AccelBuildOptions compact;
    compact.compact = true;
    const size_t normalBytes = buildEmbreeAccel(meshes, {})->memoryBytes();
    const size_t compactBytes = buildEmbreeAccel(meshes, compact)->memoryBytes();
    EXPECT_LT(compactBytes, normalBytes);
}

TEST(AccelBuildOptions, MemoryLimitStopsTheBuildWithAClearError) {
    const TriangleMesh grid = bumpyGrid(200);  // 80,000 triangles: megabytes of BVH
    const TriangleMesh* meshes[] = {&grid};
    AccelBuildOptions options;
    options.memoryLimitBytes = 64 << 20;
    options.memoryBaselineBytes = (64 << 20) - (16 << 10);  // 16 KiB left for the BVH
    EXPECT_THAT(test::errorMessage([&] { buildEmbreeAccel(meshes, options); }),
                testing::AllOf(testing::HasSubstr("memory limit of 64.0 MiB"),
                               testing::HasSubstr("--memory-limit")));
    // With room, the same build succeeds.
    options.memoryBaselineBytes = 0;
    EXPECT_GT(buildEmbreeAccel(meshes, options)->memoryBytes(), 0u);
}

TEST(AccelBuildOptions, QualityNamesRoundTrip) {
    for (BvhQuality quality : {BvhQuality::Low, BvhQuality::Medium, BvhQuality::High})
        EXPECT_EQ(bvhQualityFromName(bvhQualityName(quality)), quality);
    EXPECT_THAT(test::errorMessage([] { bvhQualityFromName("best"); }),
                testing::HasSubstr("unknown BVH quality 'best' (choose low, medium or high)"));
}

}  // namespace
}  // namespace strahl
