#include "strahl/core/spherical_triangle.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "core_test_helpers.h"
#include "strahl/core/rng.h"
#include "strahl/core/sampling.h"
#include "test_random.h"

namespace strahl {
namespace {

using test::chiSquareCritical;

using test::next2D;

TEST(TriangleSolidAngle, OctantIsHalfPi) {
    const Vec3 o(0.0f);
    EXPECT_NEAR(triangleSolidAngle(o, Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)), 0.5 * kPi,
                1e-6);
    // Orientation, scale and translation do not matter.
    EXPECT_NEAR(triangleSolidAngle(o, Vec3(0, 0, 1), Vec3(0, 1, 0), Vec3(1, 0, 0)), 0.5 * kPi,
                1e-6);
    const Vec3 t(3.0f, -2.0f, 5.0f);
    EXPECT_NEAR(triangleSolidAngle(t, t + Vec3(7, 0, 0), t + Vec3(0, 0.1f, 0), t + Vec3(0, 0, 2)),
                0.5 * kPi, 1e-6);
}

TEST(TriangleSolidAngle, HalfACubeFaceFromTheCentreIsOneTwelfthOfTheSphere) {
    // A cube face subtends 4 pi / 6 at the centre; a diagonal halves it.
    const float omega =
        triangleSolidAngle(Vec3(0.0f), Vec3(-1, -1, 1), Vec3(1, -1, 1), Vec3(1, 1, 1));
    EXPECT_NEAR(omega, kPi / 3.0f, 1e-6);
}

TEST(TriangleSolidAngle, SmallFarTriangleMatchesProjectedAreaOverDistanceSquared) {
    // Area 5e-7 facing the point at distance 100: omega = A / d^2 = 5e-11 (to
    // relative 1e-8 at this angular size). Float evaluation would return noise.
    const Vec3 p(0.0f, 0.0f, -100.0f);
    const float omega = triangleSolidAngle(p, Vec3(0, 0, 0), Vec3(1e-3f, 0, 0), Vec3(0, 1e-3f, 0));
    EXPECT_NEAR(omega / 5e-11f, 1.0f, 1e-5f);
}

TEST(TriangleSolidAngle, ApproachesTwoPiCloseToALargeTriangle) {
    const float omega = triangleSolidAngle(Vec3(0, 1e-3f, 0), Vec3(-1e3f, 0, -1e3f),
                                           Vec3(1e3f, 0, -1e3f), Vec3(0, 0, 2e3f));
    EXPECT_GT(omega, 2.0f * kPi - 1e-3f);
    EXPECT_LE(omega, 2.0f * kPi);
}

TEST(TriangleSolidAngle, DegenerateIsZero) {
    EXPECT_EQ(triangleSolidAngle(Vec3(0.5f, 0, 0.5f), Vec3(0), Vec3(1, 0, 0), Vec3(0, 0, 1)), 0.0f);
    EXPECT_EQ(triangleSolidAngle(Vec3(0, 1, 0), Vec3(0), Vec3(1, 0, 0), Vec3(2, 0, 0)), 0.0f);
    EXPECT_FALSE(sampleSphericalTriangle(Vec3(0.5f, 0, 0.5f), Vec3(0), Vec3(1, 0, 0), Vec3(0, 0, 1),
                                         Vec2(0.5f)));
}

TEST(SampleSphericalTriangle, CornersOfTheSquareMapToTheVertices) {
    // u.x = 0 collapses the sub-triangle onto the arc from p0 to p1 (u.y = 0
    // gives p1, u.y -> 1 gives p0); u = (1, 1) reaches p2.
    const Vec3 p(0.2f, -1.0f, 0.1f), a(0, 0, 0), b(1, 0, 0), c(0.3f, 0, 1.2f);
    const auto atB = sampleSphericalTriangle(p, a, b, c, Vec2(0.0f, 0.0f));
    const auto atA = sampleSphericalTriangle(p, a, b, c, Vec2(0.0f, 1.0f));
    const auto atC = sampleSphericalTriangle(p, a, b, c, Vec2(1.0f, 1.0f));
    ASSERT_TRUE(atA && atB && atC);
    EXPECT_NEAR(atB->barycentrics.y, 1.0f, 1e-5f);
    EXPECT_NEAR(atA->barycentrics.x, 1.0f, 1e-5f);
    EXPECT_NEAR(atC->barycentrics.z, 1.0f, 1e-5f);
}

TEST(SampleSphericalTriangle, SamplesLieInsideWithPdfOneOverSolidAngle) {
    Pcg32 rng(3, 9);
    for (int t = 0; t < 50; ++t) {
        // Random triangles around the origin seen from random points.
        auto point = [&] {
            return Vec3(rng.nextFloat(), rng.nextFloat(), rng.nextFloat()) * 4.0f - Vec3(2.0f);
        };
        const Vec3 p = point(), p0 = point(), p1 = point(), p2 = point();
        const float omega = triangleSolidAngle(p, p0, p1, p2);
        if (omega < 1e-4f) continue;
        for (int i = 0; i < 200; ++i) {
            const auto s = sampleSphericalTriangle(p, p0, p1, p2, next2D(rng));
            ASSERT_TRUE(s);
            const Vec3 b = s->barycentrics;
            ASSERT_GE(b.x, 0.0f);
            ASSERT_GE(b.y, 0.0f);
            ASSERT_GE(b.z, 0.0f);
            ASSERT_NEAR(b.x + b.y + b.z, 1.0f, 1e-5f);
            ASSERT_NEAR(glm::length(s->dir), 1.0f, 1e-5f);
            const Vec3 towards = glm::normalize(b.x * p0 + b.y * p1 + b.z * p2 - p);
            ASSERT_GT(glm::dot(towards, s->dir), 1.0f - 1e-4f);
            ASSERT_EQ(s->pdf, 1.0f / omega);
        }
    }
}

// The four triangles cut by the edge midpoints, classified by barycentrics.
int subTriangle(const Vec3& b) {
    if (b.x > 0.5f) return 0;
    if (b.y > 0.5f) return 1;
    if (b.z > 0.5f) return 2;
    return 3;
}

TEST(SampleSphericalTriangle, IsUniformInSolidAngle) {
    // Close to a large triangle, so uniform area sampling would be far off:
    // each midpoint sub-triangle must receive samples in proportion to its
    // own solid angle.
    const Vec3 p(0.1f, 0.3f, 0.0f);
    const std::array<Vec3, 3> v = {Vec3(-2, 0, -1), Vec3(3, 0, -1), Vec3(0, 0, 4)};
    const std::array<Vec3, 3> m = {0.5f * (v[1] + v[2]), 0.5f * (v[2] + v[0]),
                                   0.5f * (v[0] + v[1])};
    const std::array<double, 4> omegas = {
        triangleSolidAngle(p, v[0], m[2], m[1]), triangleSolidAngle(p, m[2], v[1], m[0]),
        triangleSolidAngle(p, m[1], m[0], v[2]), triangleSolidAngle(p, m[0], m[1], m[2])};
    const double omega = triangleSolidAngle(p, v[0], v[1], v[2]);
    EXPECT_NEAR(omegas[0] + omegas[1] + omegas[2] + omegas[3], omega, 1e-5);
    Pcg32 rng(5, 1);
    const int n = 40000;
    std::array<int, 4> counts{};
    for (int i = 0; i < n; ++i) {
        const auto s = sampleSphericalTriangle(p, v[0], v[1], v[2], next2D(rng));
        ASSERT_TRUE(s);
        ++counts[static_cast<size_t>(subTriangle(s->barycentrics))];
    }
    double chi2 = 0.0;
    for (size_t k = 0; k < 4; ++k) {
        const double expected = n * omegas[k] / omega;
        chi2 += (counts[k] - expected) * (counts[k] - expected) / expected;
    }
    EXPECT_LT(chi2, chiSquareCritical(3));
}

TEST(SampleSphericalTriangle, AreaSamplingEstimateOfTheSolidAngleAgrees) {
    // omega = integral over the triangle of |cos theta_light| / dist^2 dA.
    const Vec3 p(0.3f, 0.8f, -0.2f);
    const Vec3 p0(-1, 0, -1), p1(1.5f, 0, -0.5f), p2(0, 0.4f, 1.5f);
    const Vec3 cross = glm::cross(p1 - p0, p2 - p0);
    const float area = 0.5f * glm::length(cross);
    const Vec3 n = glm::normalize(cross);
    Pcg32 rng(8, 8);
    const int count = 200000;
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
        const Vec3 b = sampleUniformTriangle(next2D(rng));
        const Vec3 d = b.x * p0 + b.y * p1 + b.z * p2 - p;
        const float dist2 = glm::dot(d, d);
        sum += area * std::abs(glm::dot(n, d)) / (dist2 * std::sqrt(dist2));
    }
    const double estimate = sum / count;
    EXPECT_NEAR(estimate / triangleSolidAngle(p, p0, p1, p2), 1.0, 0.01);
}

}  // namespace
}  // namespace strahl
