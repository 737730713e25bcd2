#include "strahl/integrator/environment_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/core/rng.h"
#include "test_random.h"

namespace strahl {
namespace {

using test::next2D;

void expectNear(const Vec3& a, const Vec3& b, float tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

// A map whose texels are all different, with a black band to exercise zero rows.
EnvironmentMap randomMap(int w, int h, uint64_t seed) {
    Pcg32 rng(seed, 1);
    std::vector<Color> texels;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Color c(rng.nextFloat(), rng.nextFloat(), rng.nextFloat());
            texels.push_back(y == 2 || y == 3 ? Color(0.0f) : 10.0f * c * c * c);
        }
    return EnvironmentMap(w, h, texels);
}

Vec2 pixelCentre(int x, int y, int w, int h) {
    return Vec2((static_cast<float>(x) + 0.5f) / static_cast<float>(w),
                (static_cast<float>(y) + 0.5f) / static_cast<float>(h));
}

TEST(EnvironmentMap, ConventionCentreIsPlusXLeftEdgeMinusXTopIsUp) {
    expectNear(EnvironmentMap::direction(Vec2(0.5f, 0.5f)), Vec3(1, 0, 0), 1e-6f);
    expectNear(EnvironmentMap::direction(Vec2(0.0f, 0.5f)), Vec3(-1, 0, 0), 1e-6f);
    expectNear(EnvironmentMap::direction(Vec2(0.25f, 0.5f)), Vec3(0, 0, -1), 1e-6f);
    expectNear(EnvironmentMap::direction(Vec2(0.75f, 0.5f)), Vec3(0, 0, 1), 1e-6f);
    expectNear(EnvironmentMap::direction(Vec2(0.3f, 0.0f)), Vec3(0, 1, 0), 1e-6f);
    expectNear(EnvironmentMap::direction(Vec2(0.3f, 1.0f)), Vec3(0, -1, 0), 1e-6f);
    // Not mirrored: facing the centre (+x) with +y up, "right" is +x cross +y =
    // +z, and moving right in the image (u up) must turn that way.
    const Vec3 right = glm::cross(Vec3(1, 0, 0), Vec3(0, 1, 0));
    EXPECT_GT(glm::dot(EnvironmentMap::direction(Vec2(0.55f, 0.5f)), right), 0.1f);
    // Above the horizon is the upper half of the image.
    EXPECT_GT(EnvironmentMap::direction(Vec2(0.5f, 0.4f)).y, 0.1f);
}

TEST(EnvironmentMap, UvInvertsDirection) {
    Pcg32 rng(2, 2);
    for (int i = 0; i < 1000; ++i) {
        const Vec2 uv(rng.nextFloat(), 0.001f + 0.998f * rng.nextFloat());
        const Vec2 back = EnvironmentMap::uv(EnvironmentMap::direction(uv));
        EXPECT_NEAR(back.x, uv.x, 2e-6f);
        EXPECT_NEAR(back.y, uv.y, 2e-6f);
    }
    // Any length.
    const Vec2 scaled = EnvironmentMap::uv(Vec3(0, 0, 5));
    EXPECT_NEAR(scaled.x, 0.75f, 1e-6f);
    EXPECT_NEAR(scaled.y, 0.5f, 1e-6f);
}

TEST(EnvironmentMap, LookupAtAPixelCentreReturnsThatPixel) {
    const int w = 16, h = 8;
    const EnvironmentMap map = randomMap(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Vec3 dir = EnvironmentMap::direction(pixelCentre(x, y, w, h));
            expectNear(map.lookup(dir), map.texel(x, y), 1e-4f);
        }
}

TEST(EnvironmentMap, LookupInterpolatesAndWrapsAcrossTheSeam) {
    // Two columns: 0 black, 1 white. The seam u = 0 lies half-way between the
    // centres of column 1 (wrapped) and column 0.
    const EnvironmentMap map(2, 1, {Color(0.0f), Color(1.0f)});
    EXPECT_NEAR(map.lookup(EnvironmentMap::direction(Vec2(0.0f, 0.5f))).r, 0.5f, 1e-5f);
    EXPECT_NEAR(map.lookup(EnvironmentMap::direction(Vec2(0.5f, 0.5f))).r, 0.5f, 1e-5f);
    EXPECT_NEAR(map.lookup(EnvironmentMap::direction(Vec2(0.375f, 0.2f))).r, 0.25f, 1e-5f);
    // Rows clamp at the poles (v = 0.01 is above the only row's centre).
    EXPECT_NEAR(map.lookup(EnvironmentMap::direction(Vec2(0.25f, 0.01f))).r, 0.0f, 1e-5f);
    EXPECT_NEAR(map.lookup(EnvironmentMap::direction(Vec2(0.75f, 0.99f))).r, 1.0f, 1e-5f);
}

TEST(EnvironmentMap, SamplePdfMatchesPdfAndIntegratesToOne) {
    const int w = 32, h = 16;
    const EnvironmentMap map = randomMap(w, h, 9);
    Pcg32 rng(6, 6);
    for (int i = 0; i < 5000; ++i) {
        float pdf;
        const Vec3 dir = map.sample(next2D(rng), pdf);
        ASSERT_NEAR(glm::length(dir), 1.0f, 1e-5f);
        ASSERT_GT(pdf, 0.0f);
        ASSERT_NEAR(map.pdf(dir) / pdf, 1.0f, 1e-3f);
    }
    // Midpoint rule over the sphere in (theta, phi), 4 x 4 points per texel:
    // integral of pdf d omega = sum pdf sin(theta) dtheta dphi.
    double integral = 0.0;
    const int nu = 4 * w, nv = 4 * h;
    for (int y = 0; y < nv; ++y)
        for (int x = 0; x < nu; ++x) {
            const Vec2 uv = pixelCentre(x, y, nu, nv);
            const double sinTheta = std::sin(kPi * uv.y);
            integral += map.pdf(EnvironmentMap::direction(uv)) * sinTheta;
        }
    integral *= (2.0 * kPi / nu) * (kPi / nv);
    EXPECT_NEAR(integral, 1.0, 1e-3);
}

TEST(EnvironmentMap, OneBrightTexelAttractsTheSamples) {
    const int w = 32, h = 16, bx = 20, by = 7;
    std::vector<Color> texels(static_cast<size_t>(w * h), Color(0.0f));
    texels[static_cast<size_t>(by * w + bx)] = Color(100.0f, 80.0f, 50.0f);
    const EnvironmentMap map(w, h, texels);
    Pcg32 rng(12, 1);
    const int n = 20000;
    int inTexel = 0;
    for (int i = 0; i < n; ++i) {
        float pdf;
        const Vec3 dir = map.sample(next2D(rng), pdf);
        const Vec2 uv = EnvironmentMap::uv(dir);
        const int x = static_cast<int>(uv.x * w), y = static_cast<int>(uv.y * h);
        // Bilinear lookup spreads the texel into its 3 x 3 neighbourhood, so the
        // samples go there and nowhere else.
        ASSERT_LE(std::abs(x - bx), 1);
        ASSERT_LE(std::abs(y - by), 1);
        inTexel += x == bx && y == by;
    }
    // The texel's own share of the bilinear image: (6/8)^2 in each direction
    // for the (1, 6, 1) / 8 mean; rows differ only by sin(theta) ~ +-10%.
    EXPECT_NEAR(static_cast<double>(inTexel) / n, 36.0 / 64.0, 0.03);
}

TEST(EnvironmentMap, RowsFromPoleToPoleSitOnTheZenithAndTheNadir) {
    const int w = 8, h = 5;
    const EnvironmentMap map = [&] {
        const EnvironmentMap random = randomMap(w, h, 21);
        std::vector<Color> texels;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) texels.push_back(random.texel(x, y));
        return EnvironmentMap(w, h, texels, RowLayout::PoleToPole);
    }();
    EXPECT_EQ(map.rows(), RowLayout::PoleToPole);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // Row y at v = y / (h - 1); columns at their centres as always.
            // On the poles themselves all columns meet in one direction, so
            // the first and last rows are looked at a hair (1e-5) away.
            const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(w);
            const float v =
                std::clamp(static_cast<float>(y) / static_cast<float>(h - 1), 1e-5f, 1.0f - 1e-5f);
            const Vec3 dir = EnvironmentMap::direction(Vec2(u, v));
            expectNear(map.lookup(dir), map.texel(x, y), 1e-3f);
        }
    EXPECT_THROW(EnvironmentMap(2, 1, {Color(1.0f), Color(1.0f)}, RowLayout::PoleToPole), Error);
}

class EnvironmentMapLayouts : public testing::TestWithParam<RowLayout> {};

TEST_P(EnvironmentMapLayouts, ImportanceSamplingIntegratesTheBilinearRadiance) {
    // Sparse bright texels on black: the estimate sum L / pdf over samples must
    // converge to the integral of lookup() over the sphere (computed here by a
    // fine midpoint rule), so no radiance is out of reach of the sampler,
    // whichever row layout.
    const int w = 16, h = 8;
    std::vector<Color> texels(static_cast<size_t>(w * h), Color(0.0f));
    texels[3 * w + 5] = Color(8.0f);
    texels[0 * w + 0] = Color(2.0f, 0.5f, 0.0f);
    texels[6 * w + 15] = Color(0.0f, 0.0f, 4.0f);
    const EnvironmentMap map(w, h, texels, GetParam());
    glm::dvec3 reference(0.0);
    const int nu = 16 * w, nv = 16 * h;
    for (int y = 0; y < nv; ++y)
        for (int x = 0; x < nu; ++x) {
            const Vec2 uv = pixelCentre(x, y, nu, nv);
            reference += glm::dvec3(map.lookup(EnvironmentMap::direction(uv))) *
                         std::sin(static_cast<double>(kPi) * uv.y);
        }
    reference *= (2.0 * kPi / nu) * (kPi / nv);
    Pcg32 rng(1, 77);
    glm::dvec3 estimate(0.0);
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        float pdf;
        const Vec3 dir = map.sample(next2D(rng), pdf);
        estimate += glm::dvec3(map.lookup(dir)) / static_cast<double>(pdf);
    }
    estimate /= n;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(estimate[c] / reference[c], 1.0, 0.02) << c;
}

INSTANTIATE_TEST_SUITE_P(RowLayouts, EnvironmentMapLayouts,
                         testing::Values(RowLayout::Centred, RowLayout::PoleToPole));

TEST(EnvironmentMap, AverageIsTheMeanOverTheSphere) {
    const EnvironmentMap constant(8, 4, std::vector<Color>(32, Color(0.5f, 1.0f, 2.0f)));
    expectNear(constant.average(), Color(0.5f, 1.0f, 2.0f), 1e-6f);
    const EnvironmentMap poles(8, 4, std::vector<Color>(32, Color(0.5f, 1.0f, 2.0f)),
                               RowLayout::PoleToPole);
    expectNear(poles.average(), Color(0.5f, 1.0f, 2.0f), 1e-6f);
    // Only the top row lit: its share of the sphere is (1 - cos(pi / 4)) / 2.
    std::vector<Color> texels(32, Color(0.0f));
    for (int x = 0; x < 8; ++x) texels[static_cast<size_t>(x)] = Color(1.0f);
    const EnvironmentMap top(8, 4, texels);
    EXPECT_NEAR(top.average().g, (1.0 - std::cos(kPi / 4.0)) / 2.0, 1e-6);
}

TEST(EnvironmentMap, RejectsBadImages) {
    EXPECT_THROW(EnvironmentMap(0, 4, {}), Error);
    EXPECT_THROW(EnvironmentMap(2, 2, std::vector<Color>(3)), Error);
    EXPECT_THROW(EnvironmentMap(1, 1, {Color(-1.0f)}), Error);
    EXPECT_THROW(EnvironmentMap(1, 1, {Color(NAN)}), Error);
}

}  // namespace
}  // namespace strahl
