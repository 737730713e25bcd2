// Bilinear patches (geometry/bilinear_patches.h): the Bézier patch of the
// degree elevation is the bilinear surface exactly, its normal faces the side
// the corners run counter-clockwise around, a flat patch is recognised, a
// saddle intersected directly has its hits on the surface, and bad input is
// one clear error.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "ray_probes.h"
#include "strahl/geometry/bilinear_patches.h"
#include "strahl/geometry/parametric_shape.h"
#include "test_support.h"

namespace strahl {
namespace {

DVec3 bilinear(const DVec3 q[4], double u, double v) {
    return (1 - u) * (1 - v) * q[0] + u * (1 - v) * q[1] + u * v * q[2] + (1 - u) * v * q[3];
}

TEST(BilinearPatches, TheBezierPatchIsTheBilinearSurfaceExactly) {
    const std::vector<DVec3> positions = {{0, 0, 0}, {2, 0, 0.5}, {2.5, 1.5, -0.3}, {-0.2, 1, 1}};
    const std::vector<uint32_t> corners = {0, 1, 2, 3};
    const ParametricSurfacePtr surface = makeBilinearPatchSet(positions, corners, "test");
    ASSERT_EQ(surface->patchCount(), 1u);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 200; ++i) {
        const double u = unit(rng), v = unit(rng);
        const DVec3 expected = bilinear(positions.data(), u, v);
        const Point3<double> p = surface->evaluate(0, u, v);
        EXPECT_NEAR(p.x, expected.x, 1e-12);
        EXPECT_NEAR(p.y, expected.y, 1e-12);
        EXPECT_NEAR(p.z, expected.z, 1e-12);
        // The partials of f: ∂u f = (1 − v)(q10 − q00) + v (q11 − q01), ∂v f alike.
        const SurfacePoint s = surface->partials(0, u, v);
        const DVec3 du = (1 - v) * (positions[1] - positions[0]) + v * (positions[2] - positions[3]);
        const DVec3 dv = (1 - u) * (positions[3] - positions[0]) + u * (positions[2] - positions[1]);
        EXPECT_LT(glm::length(s.dpdu - du), 1e-12);
        EXPECT_LT(glm::length(s.dpdv - dv), 1e-12);
    }
    // The corners are the given points bit for bit.
    const Point3<double> corner = surface->evaluate(0, 1.0, 1.0);
    EXPECT_EQ(corner.x, 2.5);
    EXPECT_EQ(corner.y, 1.5);
    EXPECT_EQ(corner.z, -0.3);
}

TEST(BilinearPatches, TheNormalFacesWhereTheCornersRunCounterClockwise) {
    // The unit square in z = 0, corners counter-clockwise seen from +z.
    const std::vector<DVec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<uint32_t> ccw = {0, 1, 2, 3}, cw = {0, 3, 2, 1};
    EXPECT_GT(makeBilinearPatchSet(positions, ccw, "")->normal(0, 0.3, 0.6).z, 0.0);
    EXPECT_LT(makeBilinearPatchSet(positions, cw, "")->normal(0, 0.3, 0.6).z, 0.0);
}

TEST(BilinearPatches, FlatPatchesAreRecognisedAndTwistedOnesAreNot) {
    const DVec3 a(0, 0, 0), b(2, 0, 0), c(1.5, 1, 0), d(0.5, 1, 0);  // a trapezoid
    EXPECT_TRUE(bilinearPatchIsFlat(a, b, c, d, 1e-6));
    // Lifting one corner by h moves the centre off the plane of the
    // diagonals by about h / 4.
    EXPECT_FALSE(bilinearPatchIsFlat(a, b, c + DVec3(0, 0, 0.01), d, 1e-4));
    EXPECT_TRUE(bilinearPatchIsFlat(a, b, c + DVec3(0, 0, 1e-6), d, 1e-4));
    // Degenerate (all corners on a line): never taken as two triangles.
    EXPECT_FALSE(bilinearPatchIsFlat(a, b, a, b, 1e-4));
}

TEST(BilinearPatches, ASaddleIntersectedDirectlyHasItsHitsOnTheSurface) {
    // The patch with corners (±1, ±1, ±1) is the saddle z = x y.
    const std::vector<DVec3> positions = {{-1, -1, 1}, {1, -1, -1}, {1, 1, 1}, {-1, 1, -1}};
    const std::vector<uint32_t> corners = {0, 1, 2, 3};
    const ParametricShape shape(makeBilinearPatchSet(positions, corners, "saddle"), Mat4(1.0f),
                                ParametricShapeOptions{});
    std::mt19937 rng(8);
    int hits = 0;
    for (int i = 0; i < 5000; ++i) {
        const Ray ray = rayTowards(rng, 4.0, 0.9);
        const Hit hit = nearestHit(shape, ray);
        if (!hit.valid()) continue;
        ++hits;
        const SurfaceInteraction si = shape.interaction(ray, hit);
        EXPECT_NEAR(si.p.z, si.p.x * si.p.y, 1e-5f);
        EXPECT_LE(std::abs(si.p.x), 1.0f + 1e-5f);
        EXPECT_LE(std::abs(si.p.y), 1.0f + 1e-5f);
    }
    EXPECT_GT(hits, 1000);
}

TEST(BilinearPatches, BadInputIsOneClearError) {
    const std::vector<DVec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<uint32_t> three = {0, 1, 2}, outOfRange = {0, 1, 2, 4};
    EXPECT_EQ(test::errorMessage([&] { makeBilinearPatchSet(positions, three, "p"); }),
              "bilinear patches 'p': 3 corner indices, not a multiple of 4");
    EXPECT_EQ(test::errorMessage([&] { makeBilinearPatchSet(positions, outOfRange, "p"); }),
              "bilinear patches 'p': corner 3 of patch 0 is index 4, but there are only 4 positions");
    std::vector<DVec3> nan = positions;
    nan[2].y = std::nan("");
    const std::vector<uint32_t> corners = {0, 1, 2, 3};
    EXPECT_EQ(test::errorMessage([&] { makeBilinearPatchSet(nan, corners, "p"); }),
              "bilinear patches 'p': position 2 is not finite (1 nan 0)");
}

}  // namespace
}  // namespace strahl
