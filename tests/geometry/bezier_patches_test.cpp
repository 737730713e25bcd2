// Bicubic Bézier patch sets: hand-written partials against automatic
// differentiation, linear precision (a planar net gives the plane), the
// interval bounds (conservative over random sub-rectangles, tight on small
// ones), the cubic range helpers, and the errors of bad input.

#include "strahl/geometry/bezier_patches.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "strahl/core/error.h"
#include "test_support.h"

#include "surface_checks.h"

namespace strahl {
namespace {

using test::axis;
using test::expectNear;

using test::contains;

BezierPatch randomPatch(std::mt19937& rng, double extent) {
    std::uniform_real_distribution<double> c(-extent, extent);
    BezierPatch p;
    for (DVec3& q : p.points) q = DVec3(c(rng), c(rng), c(rng));
    return p;
}

// A planar net: P_ij = origin + (i/3) e1 + (j/3) e2, so f(u, v) = origin + u e1 + v e2.
BezierPatch planarPatch(const DVec3& origin, const DVec3& e1, const DVec3& e2) {
    BezierPatch p;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            p.points[size_t(4 * i + j)] = origin + (i / 3.0) * e1 + (j / 3.0) * e2;
    return p;
}

TEST(BezierPatches, PartialsMatchAutomaticDifferentiation) {
    std::mt19937 rng(11);
    const ParametricSurfacePtr s = makeBezierPatchSet(
        {randomPatch(rng, 2.0), randomPatch(rng, 5.0), randomPatch(rng, 0.1)}, "random");
    std::uniform_real_distribution<double> t(0.0, 1.0);
    for (uint32_t patch = 0; patch < 3; ++patch)
        for (int k = 0; k < 200; ++k) {
            // Corners and edges too, where a basis derivative is at its extreme.
            const double u = k < 4 ? double(k & 1) : t(rng), v = k < 4 ? double(k >> 1) : t(rng);
            const SurfacePoint hand = s->partials(patch, u, v);
            const SurfacePoint autoDiff = s->automaticPartials(patch, u, v);
            const std::string where = "patch " + std::to_string(patch) + " at (" +
                                      std::to_string(u) + ", " + std::to_string(v) + ")";
            expectNear(hand.p, autoDiff.p, 1e-12, where + " p");
            expectNear(hand.dpdu, autoDiff.dpdu, 1e-11, where + " dpdu");
            expectNear(hand.dpdv, autoDiff.dpdv, 1e-11, where + " dpdv");
            expectNear(hand.p, s->point(patch, u, v), 1e-12, where + " point");
        }
}

TEST(BezierPatches, PlanarNetGivesThePlane) {
    const DVec3 origin(1.0, -2.0, 0.5), e1(3.0, 0.0, 0.0), e2(0.0, 2.0, 0.0);
    const ParametricSurfacePtr s = makeBezierPatchSet({planarPatch(origin, e1, e2)}, "plane");
    EXPECT_EQ(s->patchCount(), 1u);
    const ParamDomain& d = s->domain();
    EXPECT_EQ(d.u0, 0.0);
    EXPECT_EQ(d.u1, 1.0);
    EXPECT_EQ(d.v0, 0.0);
    EXPECT_EQ(d.v1, 1.0);
    EXPECT_FALSE(d.periodicU || d.periodicV);
    for (const double u : {0.0, 0.1, 0.5, 0.77, 1.0})
        for (const double v : {0.0, 0.3, 0.5, 1.0}) {
            const SurfacePoint sp = s->partials(0, u, v);
            expectNear(sp.p, origin + u * e1 + v * e2, 1e-14, "plane point");
            expectNear(sp.dpdu, e1, 1e-13, "plane dpdu");
            expectNear(sp.dpdv, e2, 1e-13, "plane dpdv");
            expectNear(s->normal(0, u, v), DVec3(0, 0, 1), 1e-14, "plane normal");
        }
    // The corners are the corner control points exactly.
    const BezierPatch p = planarPatch(origin, e1, e2);
    EXPECT_EQ(s->point(0, 0, 0), p.points[0]);
    EXPECT_EQ(s->point(0, 0, 1), p.points[3]);
    EXPECT_EQ(s->point(0, 1, 0), p.points[12]);
    EXPECT_EQ(s->point(0, 1, 1), p.points[15]);
}

TEST(BezierPatches, EachPatchIsItsOwnNet) {
    const ParametricSurfacePtr s =
        makeBezierPatchSet({planarPatch(DVec3(0), DVec3(1, 0, 0), DVec3(0, 1, 0)),
                            planarPatch(DVec3(0, 0, 5), DVec3(0, 2, 0), DVec3(0, 0, 1))},
                           "two");
    EXPECT_EQ(s->patchCount(), 2u);
    expectNear(s->point(0, 0.5, 0.5), DVec3(0.5, 0.5, 0), 1e-15, "patch 0");
    expectNear(s->point(1, 0.5, 0.5), DVec3(0, 1, 5.5), 1e-15, "patch 1");
    EXPECT_TRUE(contains(s->describe(), "'two'")) << s->describe();
    EXPECT_TRUE(contains(s->describe(), "2 patches")) << s->describe();
    EXPECT_NO_THROW(validateParametricSurface(*s));
}

TEST(BezierPatches, IntervalEnclosesSampledPointsOfRandomSubRectangles) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> t(0.0, 1.0);
    std::uniform_real_distribution<double> logWidth(-8.0, 0.0);
    for (int trial = 0; trial < 300; ++trial) {
        const ParametricSurfacePtr s =
            makeBezierPatchSet({randomPatch(rng, trial % 2 ? 100.0 : 1.0)}, "");
        // Random widths from 1e-8 to 1, some at the domain's edges.
        const double wu = std::pow(10.0, logWidth(rng)), wv = std::pow(10.0, logWidth(rng));
        const double u0 = trial % 5 == 0 ? 0.0 : t(rng) * (1.0 - wu);
        const double v0 = trial % 7 == 0 ? 1.0 - wv : t(rng) * (1.0 - wv);
        const num::Interval U(u0, u0 + wu), V(v0, v0 + wv);
        const Point3<num::Interval> box = s->evaluate(0, U, V);
        for (int k = 0; k < 60; ++k) {
            // Corners first, then random points.
            const double u = k < 4 ? (k & 1 ? U.hi : U.lo) : U.lo + t(rng) * wu;
            const double v = k < 4 ? (k & 2 ? V.hi : V.lo) : V.lo + t(rng) * wv;
            const DVec3 p = s->point(0, std::min(u, U.hi), std::min(v, V.hi));
            for (int a = 0; a < 3; ++a)
                ASSERT_TRUE(axis(box, a).contains(p[a]))
                    << "trial " << trial << " axis " << a << ": " << p[a] << " not in ["
                    << axis(box, a).lo << ", " << axis(box, a).hi << "]";
        }
    }
}

TEST(BezierPatches, IntervalOfASmallSubRectangleIsTight) {
    std::mt19937 rng(3);
    const ParametricSurfacePtr s = makeBezierPatchSet({randomPatch(rng, 1.0)}, "");
    const Point3<num::Interval> whole = s->evaluate(0, num::Interval(0, 1), num::Interval(0, 1));
    const double h = 1e-3;
    const num::Interval U(0.4, 0.4 + h), V(0.6, 0.6 + h);
    const Point3<num::Interval> small = s->evaluate(0, U, V);
    const SurfacePoint sp = s->partials(0, 0.4, 0.6);
    for (int a = 0; a < 3; ++a) {
        // The box of the sub-patch is about |∂u f| h + |∂v f| h wide (plus
        // second-order terms): far below the whole patch's, and close to the
        // true extent of the sub-patch.
        const double firstOrder = (std::abs(sp.dpdu[a]) + std::abs(sp.dpdv[a])) * h;
        EXPECT_LT(axis(small, a).width(), 1e-2 * axis(whole, a).width()) << "axis " << a;
        EXPECT_LT(axis(small, a).width(), 1.05 * firstOrder + 50.0 * h * h) << "axis " << a;
    }
    // A point interval is the point, give or take the rounding allowance.
    const Point3<num::Interval> point = s->evaluate(0, num::Interval(0.3), num::Interval(0.9));
    const DVec3 p = s->point(0, 0.3, 0.9);
    for (int a = 0; a < 3; ++a) {
        EXPECT_TRUE(axis(point, a).contains(p[a]));
        EXPECT_LT(axis(point, a).width(), 1e-12);
    }
}

TEST(BezierPatches, IntervalBeyondTheDomainStaysConservative) {
    std::mt19937 rng(5);
    const ParametricSurfacePtr s = makeBezierPatchSet({randomPatch(rng, 1.0)}, "");
    const num::Interval U(-0.5, 1.5), V(0.9, 1.3);
    const Point3<num::Interval> box = s->evaluate(0, U, V);
    std::uniform_real_distribution<double> t(0.0, 1.0);
    for (int k = 0; k < 500; ++k) {
        const DVec3 p = s->point(0, U.lo + t(rng) * U.width(), V.lo + t(rng) * V.width());
        for (int a = 0; a < 3; ++a) EXPECT_TRUE(axis(box, a).contains(p[a]));
    }
    // Unbounded or NaN parameters give the whole line, never a wrong box.
    const Point3<num::Interval> inf = s->evaluate(0, num::Interval::entire(), V);
    EXPECT_EQ(inf.x.lo, -num::kInf);
    EXPECT_EQ(inf.z.hi, num::kInf);
    const Point3<num::Interval> nan = s->evaluate(0, num::Interval(std::nan(""), 1.0), V);
    EXPECT_EQ(nan.y.lo, -num::kInf);
}

TEST(BezierCubicRange, ContainsTheCubicAndShrinksWithTheRange) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> c(-3.0, 3.0), t(-0.5, 1.5), unit(0.0, 1.0);
    for (int trial = 0; trial < 500; ++trial) {
        const std::array<double, 4> cp = {c(rng), c(rng), c(rng), c(rng)};
        double a = t(rng), b = t(rng);
        if (a > b) std::swap(a, b);
        const num::Interval range = bezier::cubicRange(cp, {a, b});
        // The restricted net reproduces the end points.
        const std::array<double, 4> q = bezier::restrictCubic(cp, a, b);
        auto value = [&](double x) {
            const std::array<double, 4> w = bezier::basis(x);
            return w[0] * cp[0] + w[1] * cp[1] + w[2] * cp[2] + w[3] * cp[3];
        };
        EXPECT_NEAR(q[0], value(a), 1e-12);
        EXPECT_NEAR(q[3], value(b), 1e-12);
        for (int k = 0; k < 50; ++k) {
            const double x = a + unit(rng) * (b - a);
            ASSERT_TRUE(range.contains(value(std::min(x, b)))) << "trial " << trial;
        }
    }
    // The whole cubic lies in the hull of its control points.
    const std::array<double, 4> cp = {0.0, 3.0, -1.0, 2.0};
    const num::Interval whole = bezier::cubicRange(cp, {0.0, 1.0});
    EXPECT_LE(whole.lo, -1.0 + 1e-12);
    EXPECT_GE(whole.lo, -1.0 - 1e-12);
    EXPECT_LE(whole.hi, 3.0 + 1e-12);
    EXPECT_GE(whole.hi, 3.0 - 1e-12);
}

TEST(BezierPatches, BadInputIsAnError) {
    const std::string empty = test::errorMessage([] { makeBezierPatchSet({}, "lid.bpt"); });
    EXPECT_TRUE(contains(empty, "'lid.bpt'")) << empty;
    EXPECT_TRUE(contains(empty, "no patches")) << empty;

    std::mt19937 rng(1);
    std::vector<BezierPatch> patches = {randomPatch(rng, 1.0), randomPatch(rng, 1.0),
                                        randomPatch(rng, 1.0)};
    patches[2].points[5].y = std::nan("");
    const std::string nan = test::errorMessage([&] { makeBezierPatchSet(patches, "pot"); });
    EXPECT_TRUE(contains(nan, "control point 5 of patch 2")) << nan;
    EXPECT_TRUE(contains(nan, "not finite")) << nan;

    patches[2].points[5].y = 0.0;
    patches[1].points[15].z = num::kInf;
    const std::string inf = test::errorMessage([&] { makeBezierPatchSet(patches, ""); });
    EXPECT_TRUE(contains(inf, "control point 15 of patch 1")) << inf;
}

}  // namespace
}  // namespace strahl
