// The equal-area octahedral map (core/equal_area.h): a bijection between the
// sphere and the square that preserves area, with pbrt-v4's orientation.

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/core/equal_area.h"
#include "strahl/core/rng.h"

namespace strahl {
namespace {

TEST(EqualArea, SquareToSphereAndBackIsTheIdentity) {
    for (int j = 0; j <= 20; ++j)
        for (int i = 0; i <= 20; ++i) {
            const Vec2 p(static_cast<float>(i) / 20.0f, static_cast<float>(j) / 20.0f);
            const Vec3 d = equalAreaSquareToSphere(p);
            EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
            const Vec2 q = equalAreaSphereToSquare(d);
            // The square's edges fold onto each other: compare the directions
            // there, the points elsewhere.
            if (i == 0 || i == 20 || j == 0 || j == 20) {
                const Vec3 e = equalAreaSquareToSphere(q);
                EXPECT_NEAR(glm::dot(d, e), 1.0f, 1e-5f) << i << " " << j;
            } else {
                EXPECT_NEAR(q.x, p.x, 2e-6f) << i << " " << j;
                EXPECT_NEAR(q.y, p.y, 2e-6f) << i << " " << j;
            }
        }
}

TEST(EqualArea, TheCentreIsUpTheCornersDownAndTheAxesWhereTheSignsSay) {
    const Vec3 up = equalAreaSquareToSphere(Vec2(0.5f, 0.5f));
    EXPECT_NEAR(up.z, 1.0f, 1e-6f);
    EXPECT_NEAR(equalAreaSquareToSphere(Vec2(0.0f, 0.0f)).z, -1.0f, 1e-6f);
    const Vec3 px = equalAreaSquareToSphere(Vec2(1.0f, 0.5f));  // the middle of the right edge
    EXPECT_NEAR(px.x, 1.0f, 1e-6f);
    const Vec3 py = equalAreaSquareToSphere(Vec2(0.5f, 1.0f));
    EXPECT_NEAR(py.y, 1.0f, 1e-6f);
}

TEST(EqualArea, UniformPointsOfTheSquareAreUniformOnTheSphere) {
    // Equal areas: the fraction of uniform square points in a cap of height h
    // is h / 2, in any direction.
    Pcg32 rng(7, 0);
    constexpr int kPoints = 200000;
    int above = 0, capZ = 0, capX = 0;
    for (int k = 0; k < kPoints; ++k) {
        const Vec3 d = equalAreaSquareToSphere(Vec2(rng.nextFloat(), rng.nextFloat()));
        above += d.z > 0.0f;
        capZ += d.z > 0.5f;
        capX += d.x > 0.8f;
    }
    // Binomial standard deviations are at most 0.0012 here: 5 of them.
    EXPECT_NEAR(above / double(kPoints), 0.5, 0.006);
    EXPECT_NEAR(capZ / double(kPoints), 0.25, 0.006);
    EXPECT_NEAR(capX / double(kPoints), 0.1, 0.006);
}

}  // namespace
}  // namespace strahl
