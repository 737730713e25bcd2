#include "strahl/core/ray.h"

#include <gtest/gtest.h>

#include "strahl/core/sampler.h"

namespace strahl {
namespace {

TEST(OffsetRayOrigin, LeavesTheErrorBoxOnTheRequestedSide) {
    const Vec3 n(0.0f, 0.0f, 1.0f);
    const Vec3 p(1000.0f, -2000.0f, 3.0f);
    const Vec3 err(1e-3f, 1e-3f, 2e-4f);
    const Vec3 up = offsetRayOrigin(p, err, n, Vec3(0.3f, 0.0f, 1.0f));
    const Vec3 down = offsetRayOrigin(p, err, n, Vec3(0.3f, 0.0f, -1.0f));
    EXPECT_GT(up.z, p.z + err.z);
    EXPECT_LT(down.z, p.z - err.z);
    EXPECT_EQ(up.x, p.x);  // only the normal direction moves for an axis-aligned n
}

TEST(OffsetRayOrigin, ScalesWithTheErrorNotAnAbsoluteEpsilon) {
    const Vec3 n = glm::normalize(Vec3(1.0f, 1.0f, 0.0f));
    const Vec3 tiny = offsetRayOrigin(Vec3(1e-6f), Vec3(1e-12f), n, n);
    EXPECT_LT(glm::length(tiny - Vec3(1e-6f)), 1e-10f);
}

TEST(SpawnRayTo, StopsShortOfTheTarget) {
    const Ray r = spawnRayTo(Vec3(0.0f), Vec3(1e-6f), Vec3(0, 1, 0), Vec3(0, 2, 0));
    EXPECT_GT(r.origin.y, 0.0f);
    EXPECT_LT(r.tfar, 1.0f);
    EXPECT_NEAR(r.at(1.0f).y, 2.0f, 1e-6f);
}

TEST(GammaBound, MatchesDefinition) {
    constexpr float eps = 0.5f * std::numeric_limits<float>::epsilon();
    EXPECT_FLOAT_EQ(gammaBound(3), 3 * eps / (1 - 3 * eps));
}

TEST(Pcg32, IsDeterministicAndUniformInUnitInterval) {
    Pcg32 a = pixelSampleRng(1, 2, 3, 4), b = pixelSampleRng(1, 2, 3, 4);
    Pcg32 c = pixelSampleRng(1, 2, 3, 5);
    double sum = 0.0;
    int differ = 0;
    for (int i = 0; i < 10000; ++i) {
        const float x = a.nextFloat();
        EXPECT_EQ(x, b.nextFloat());
        EXPECT_GE(x, 0.0f);
        EXPECT_LT(x, 1.0f);
        differ += x != c.nextFloat();
        sum += x;
    }
    EXPECT_NEAR(sum / 10000.0, 0.5, 0.02);
    EXPECT_GT(differ, 9900);  // other sample index, other stream
}

}  // namespace
}  // namespace strahl
