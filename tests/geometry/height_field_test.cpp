// Height fields: partials against automatic differentiation, samples
// reproduced at their grid positions (row 0 at +y), C¹ across cells, the flat
// continuation outside the domain, conservative interval bounds (both the
// per-cell and the sample-range paths, with Catmull–Rom overshoot), the upward
// normal, and the errors of bad input.

#include "strahl/geometry/height_field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "strahl/core/error.h"
#include "test_support.h"

#include "surface_checks.h"

namespace strahl {
namespace {

using test::axis;
using test::expectNear;

using test::contains;

std::vector<float> randomHeights(std::mt19937& rng, int columns, int rows, float amplitude) {
    std::uniform_real_distribution<float> h(-amplitude, amplitude);
    std::vector<float> heights(size_t(columns) * size_t(rows));
    for (float& x : heights) x = h(rng);
    return heights;
}

TEST(HeightField, PartialsMatchAutomaticDifferentiation) {
    std::mt19937 rng(21);
    const ParametricSurfacePtr s =
        makeHeightField(randomHeights(rng, 7, 5, 1.0f), 7, 5, 3.0, 2.0, 0.7);
    std::uniform_real_distribution<double> u(-1.5, 1.5), v(-1.0, 1.0), outside(-3.0, 3.0);
    for (int k = 0; k < 400; ++k) {
        // Inside, then also outside the domain (the flat continuation).
        const double uv = k < 300 ? u(rng) : outside(rng), vv = k < 300 ? v(rng) : outside(rng);
        const SurfacePoint hand = s->partials(0, uv, vv);
        const SurfacePoint autoDiff = s->automaticPartials(0, uv, vv);
        const std::string where = "at (" + std::to_string(uv) + ", " + std::to_string(vv) + ")";
        expectNear(hand.p, autoDiff.p, 1e-13, where + " p");
        expectNear(hand.dpdu, autoDiff.dpdu, 1e-12, where + " dpdu");
        expectNear(hand.dpdv, autoDiff.dpdv, 1e-12, where + " dpdv");
    }
    // Sample positions (cell borders) too.
    for (int c = 0; c < 7; ++c)
        for (int r = 0; r < 5; ++r) {
            const double uv = -1.5 + c * 0.5, vv = 1.0 - r * 0.5;
            const SurfacePoint hand = s->partials(0, uv, vv);
            const SurfacePoint autoDiff = s->automaticPartials(0, uv, vv);
            expectNear(hand.dpdu, autoDiff.dpdu, 1e-12, "sample dpdu");
            expectNear(hand.dpdv, autoDiff.dpdv, 1e-12, "sample dpdv");
        }
}

TEST(HeightField, SamplesAreReproducedAtTheirPositions) {
    // 5 x 3 samples over 4 x 2: one unit per sample, so the positions are exact.
    std::mt19937 rng(1);
    const std::vector<float> heights = randomHeights(rng, 5, 3, 2.0f);
    const ParametricSurfacePtr s = makeHeightField(heights, 5, 3, 4.0, 2.0, 1.5);
    const ParamDomain& d = s->domain();
    EXPECT_EQ(d.u0, -2.0);
    EXPECT_EQ(d.u1, 2.0);
    EXPECT_EQ(d.v0, -1.0);
    EXPECT_EQ(d.v1, 1.0);
    EXPECT_FALSE(d.periodicU || d.periodicV);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 5; ++c) {
            // Row 0 is the +y edge.
            const double u = -2.0 + c, v = 1.0 - r;
            EXPECT_EQ(s->point(0, u, v), DVec3(u, v, 1.5 * double(heights[size_t(r * 5 + c)])))
                << "column " << c << " row " << r;
        }
    // Any size: the samples up to rounding of the position.
    const ParametricSurfacePtr t = makeHeightField(heights, 5, 3, 0.3, 0.7, -2.0);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 5; ++c) {
            const double u = -0.15 + c * 0.3 / 4.0, v = 0.35 - r * 0.7 / 2.0;
            EXPECT_NEAR(t->point(0, u, v).z, -2.0 * double(heights[size_t(r * 5 + c)]), 1e-13);
        }
}

TEST(HeightField, IsSmoothAcrossCellsAndFlatOutside) {
    std::mt19937 rng(8);
    const ParametricSurfacePtr s =
        makeHeightField(randomHeights(rng, 6, 6, 1.0f), 6, 6, 5.0, 5.0, 1.0);
    // Cell borders at u = -2.5 + k: the slope is continuous (C¹).
    for (int k = 1; k < 5; ++k)
        for (const double v : {-2.2, 0.1, 1.7}) {
            const double u = -2.5 + k;
            const SurfacePoint left = s->partials(0, u - 1e-9, v), right = s->partials(0, u, v);
            EXPECT_NEAR(left.dpdu.z, right.dpdu.z, 1e-6);
            EXPECT_NEAR(left.dpdv.z, right.dpdv.z, 1e-6);
        }
    // Beyond the edge the height stays the edge height.
    EXPECT_EQ(s->point(0, 7.0, 0.3).z, s->point(0, 2.5, 0.3).z);
    EXPECT_EQ(s->point(0, 1.0, -9.0).z, s->point(0, 1.0, -2.5).z);
    EXPECT_EQ(s->point(0, 7.0, 0.3).x, 7.0);
    EXPECT_NO_THROW(validateParametricSurface(*s));
}

TEST(HeightField, NormalPointsUp) {
    std::mt19937 rng(12);
    const ParametricSurfacePtr s =
        makeHeightField(randomHeights(rng, 9, 4, 3.0f), 9, 4, 2.0, 1.0, 5.0);
    std::uniform_real_distribution<double> u(-1.0, 1.0), v(-0.5, 0.5);
    for (int k = 0; k < 100; ++k) EXPECT_GT(s->normal(0, u(rng), v(rng)).z, 0.0);
    const ParametricSurfacePtr flat =
        makeHeightField(std::vector<float>(4, 0.5f), 2, 2, 1.0, 1.0, 1.0);
    expectNear(flat->normal(0, 0.1, 0.2), DVec3(0, 0, 1), 1e-15, "flat normal");
    EXPECT_NEAR(flat->point(0, 0.1, 0.2).z, 0.5, 1e-15);  // the weights sum to 1 up to rounding
}

// Random sub-rectangles of all sizes, some reaching past the domain, on grids
// with smooth, random and spiky heights: every sampled point lies in the box.
TEST(HeightField, IntervalEnclosesSampledPoints) {
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> unit(0.0, 1.0), logWidth(-6.0, 0.3);
    const int columns = 40, rows = 30;
    std::vector<float> spikes(size_t(columns) * rows, 0.0f);
    for (size_t k = 0; k < spikes.size(); k += 7) spikes[k] = (k % 2) ? 10.0f : -3.0f;
    std::vector<float> step(size_t(columns) * rows, 0.0f);
    for (int r = 0; r < rows; ++r)
        for (int c = columns / 2; c < columns; ++c) step[size_t(r * columns + c)] = 1.0f;
    const ParametricSurfacePtr fields[] = {
        makeHeightField(randomHeights(rng, columns, rows, 1.0f), columns, rows, 4.0, 3.0, 1.0),
        makeHeightField(spikes, columns, rows, 4.0, 3.0, -0.5),
        makeHeightField(step, columns, rows, 4.0, 3.0, 2.0)};
    for (const ParametricSurfacePtr& s : fields) {
        const ParamDomain& d = s->domain();
        for (int trial = 0; trial < 400; ++trial) {
            const double wu = std::pow(10.0, logWidth(rng)) * d.width();
            const double wv = std::pow(10.0, logWidth(rng)) * d.height();
            const double u0 = d.u0 - 0.1 * d.width() + unit(rng) * 1.2 * d.width() - 0.5 * wu;
            const double v0 = d.v0 - 0.1 * d.height() + unit(rng) * 1.2 * d.height() - 0.5 * wv;
            const num::Interval U(u0, u0 + wu), V(v0, v0 + wv);
            const Point3<num::Interval> box = s->evaluate(0, U, V);
            EXPECT_EQ(box.x.lo, U.lo);
            EXPECT_EQ(box.y.hi, V.hi);
            for (int k = 0; k < 80; ++k) {
                const double u =
                    k < 4 ? (k & 1 ? U.hi : U.lo) : std::min(U.lo + unit(rng) * wu, U.hi);
                const double v =
                    k < 4 ? (k & 2 ? V.hi : V.lo) : std::min(V.lo + unit(rng) * wv, V.hi);
                const double z = s->point(0, u, v).z;
                ASSERT_TRUE(box.z.contains(z))
                    << s->describe() << " trial " << trial << ": " << z << " not in [" << box.z.lo
                    << ", " << box.z.hi << "]";
            }
        }
    }
}

TEST(HeightField, OvershootIsCoveredByTheLargeRangeBound) {
    // A step overshoots below 0 and above 1 next to the edge (Catmull–Rom
    // is not monotone); the whole-domain bound must still hold it.
    const int columns = 64, rows = 64;
    std::vector<float> step(size_t(columns) * rows, 0.0f);
    for (int r = 0; r < rows; ++r)
        for (int c = columns / 2; c < columns; ++c) step[size_t(r * columns + c)] = 1.0f;
    const ParametricSurfacePtr s = makeHeightField(step, columns, rows, 63.0, 63.0, 1.0);
    double lo = 0.0, hi = 1.0;
    for (double u = -31.5; u <= 31.5; u += 1.0 / 64.0) {
        const double z = s->point(0, u, 0.25).z;
        lo = std::min(lo, z);
        hi = std::max(hi, z);
    }
    EXPECT_LT(lo, -0.01);
    EXPECT_GT(hi, 1.01);
    const Point3<num::Interval> whole =
        s->evaluate(0, num::Interval(-31.5, 31.5), num::Interval(-31.5, 31.5));
    EXPECT_LE(whole.z.lo, lo);
    EXPECT_GE(whole.z.hi, hi);
    // ... and stays within the documented 9/32 of the sample range.
    EXPECT_GE(whole.z.lo, -9.0 / 32.0 - 1e-9);
    EXPECT_LE(whole.z.hi, 1.0 + 9.0 / 32.0 + 1e-9);
}

TEST(HeightField, SmallSubRectangleIsTight) {
    std::mt19937 rng(17);
    const ParametricSurfacePtr s =
        makeHeightField(randomHeights(rng, 20, 20, 1.0f), 20, 20, 19.0, 19.0, 1.0);
    const Point3<num::Interval> whole =
        s->evaluate(0, num::Interval(-9.5, 9.5), num::Interval(-9.5, 9.5));
    const double h = 1e-3;
    const Point3<num::Interval> small =
        s->evaluate(0, num::Interval(0.3, 0.3 + h), num::Interval(-2.2, -2.2 + h));
    const SurfacePoint sp = s->partials(0, 0.3, -2.2);
    EXPECT_LT(small.z.width(), 1e-2 * whole.z.width());
    EXPECT_LT(small.z.width(),
              1.05 * (std::abs(sp.dpdu.z) + std::abs(sp.dpdv.z)) * h + 50.0 * h * h);
}

TEST(HeightField, BadInputIsAnError) {
    auto error = [](std::vector<float> h, int c, int r, double sx, double sy, double scale) {
        return test::errorMessage([&] { makeHeightField(std::move(h), c, r, sx, sy, scale); });
    };
    std::string m = error(std::vector<float>(5, 0.0f), 1, 5, 1.0, 1.0, 1.0);
    EXPECT_TRUE(contains(m, "at least 2 x 2")) << m;
    m = error(std::vector<float>(2, 0.0f), 2, -1, 1.0, 1.0, 1.0);
    EXPECT_TRUE(contains(m, "at least 2 x 2")) << m;
    m = error(std::vector<float>(5, 0.0f), 2, 3, 1.0, 1.0, 1.0);
    EXPECT_TRUE(contains(m, "5 heights for 2 x 3")) << m;
    std::vector<float> nan(6, 0.0f);
    nan[5] = std::nanf("");
    m = error(nan, 2, 3, 1.0, 1.0, 1.0);
    EXPECT_TRUE(contains(m, "column 1, row 2")) << m;
    EXPECT_TRUE(contains(m, "not finite")) << m;
    m = error(std::vector<float>(4, 0.0f), 2, 2, 0.0, 1.0, 1.0);
    EXPECT_TRUE(contains(m, "size must be positive")) << m;
    m = error(std::vector<float>(4, 0.0f), 2, 2, 1.0, num::kInf, 1.0);
    EXPECT_TRUE(contains(m, "size must be positive")) << m;
    m = error(std::vector<float>(4, 0.0f), 2, 2, 1.0, -2.0, 1.0);
    EXPECT_TRUE(contains(m, "size must be positive")) << m;
    m = error(std::vector<float>(4, 0.0f), 2, 2, 1.0, 1.0, std::nan(""));
    EXPECT_TRUE(contains(m, "height scale")) << m;
}

}  // namespace
}  // namespace strahl
