// Surfaces of revolution: partials against automatic differentiation, the
// profile points reproduced at integer s, a cylinder profile, the documented
// normal orientation, interval bounds, and the errors of bad profiles.

#include "strahl/geometry/revolution_surface.h"

#include <gtest/gtest.h>

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

constexpr double kTwoPi = 2.0 * num::kPiD;

// A vase: a pole at the bottom, a belly, a neck and an open rim.
std::vector<glm::dvec2> vase() {
    return {{0.0, 0.0}, {0.8, 0.1}, {1.2, 0.8}, {0.6, 1.6}, {0.5, 2.0}, {0.9, 2.4}};
}

TEST(SurfaceOfRevolution, PartialsMatchAutomaticDifferentiation) {
    const ParametricSurfacePtr s = makeSurfaceOfRevolution(vase());
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> phi(0.0, kTwoPi), sParam(0.0, 5.0);
    for (int k = 0; k < 400; ++k) {
        // Every knot (integer s) and both ends, then random points.
        const double sv = k <= 5 ? double(k) : sParam(rng);
        const double pv = phi(rng);
        const SurfacePoint hand = s->partials(0, pv, sv);
        const SurfacePoint autoDiff = s->automaticPartials(0, pv, sv);
        const std::string where = "at (" + std::to_string(pv) + ", " + std::to_string(sv) + ")";
        expectNear(hand.p, autoDiff.p, 1e-13, where + " p");
        expectNear(hand.dpdu, autoDiff.dpdu, 1e-12, where + " dpdphi");
        expectNear(hand.dpdv, autoDiff.dpdv, 1e-12, where + " dpds");
    }
}

TEST(SurfaceOfRevolution, IntegerParametersGiveTheProfilePoints) {
    const std::vector<glm::dvec2> profile = vase();
    const ParametricSurfacePtr s = makeSurfaceOfRevolution(profile);
    const ParamDomain& d = s->domain();
    EXPECT_EQ(d.u0, 0.0);
    EXPECT_NEAR(d.u1, kTwoPi, 1e-15);
    EXPECT_EQ(d.v0, 0.0);
    EXPECT_EQ(d.v1, 5.0);
    EXPECT_TRUE(d.periodicU);
    EXPECT_FALSE(d.periodicV);
    for (size_t k = 0; k < profile.size(); ++k) {
        // φ = 0: (r, 0, z) exactly.
        EXPECT_EQ(s->point(0, 0.0, double(k)), DVec3(profile[k].x, 0.0, profile[k].y)) << k;
        const DVec3 p = s->point(0, 2.0, double(k));
        EXPECT_EQ(p.z, profile[k].y) << k;
        EXPECT_NEAR(std::hypot(p.x, p.y), profile[k].x, 1e-15) << k;
    }
    // The seam closes: φ = 2π is φ = 0.
    expectNear(s->point(0, kTwoPi, 2.5), s->point(0, 0.0, 2.5), 1e-14, "seam");
}

TEST(SurfaceOfRevolution, ProfileIsC1AtTheKnots) {
    const ParametricSurfacePtr s = makeSurfaceOfRevolution(vase());
    for (int k = 1; k < 5; ++k) {
        const SurfacePoint before = s->partials(0, 0.7, k - 1e-9);
        const SurfacePoint after = s->partials(0, 0.7, double(k));
        expectNear(before.dpdv, after.dpdv, 1e-7, "knot " + std::to_string(k));
    }
}

TEST(SurfaceOfRevolution, CylinderProfileStaysAtItsRadius) {
    const ParametricSurfacePtr s =
        makeSurfaceOfRevolution({{1.5, 0.0}, {1.5, 1.0}, {1.5, 2.0}, {1.5, 3.0}});
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> phi(0.0, kTwoPi), sParam(0.0, 3.0);
    for (int k = 0; k < 200; ++k) {
        const double pv = phi(rng), sv = sParam(rng);
        const DVec3 p = s->point(0, pv, sv);
        EXPECT_NEAR(std::hypot(p.x, p.y), 1.5, 1e-14);
        // Evenly spaced points make z linear in s.
        EXPECT_NEAR(p.z, sv, 1e-14);
        // Outward, as the profile rises.
        const DVec3 n = s->normal(0, pv, sv);
        expectNear(n, DVec3(std::cos(pv), std::sin(pv), 0.0), 1e-12, "cylinder normal");
    }
    // Two points: a straight segment (here a cone from r = 2 at z = 0 to the apex).
    const ParametricSurfacePtr cone = makeSurfaceOfRevolution({{2.0, 0.0}, {0.0, 1.0}});
    for (const double sv : {0.0, 0.25, 0.5, 1.0}) {
        const DVec3 p = cone->point(0, 0.0, sv);
        EXPECT_NEAR(p.x, 2.0 * (1.0 - sv), 1e-15);
        EXPECT_NEAR(p.z, sv, 1e-15);
    }
    EXPECT_NO_THROW(validateParametricSurface(*cone));
}

TEST(SurfaceOfRevolution, NormalLiesToTheRightOfTheProfile) {
    // Counterclockwise around a solid: bottom pole, out, up the side, in to the top pole.
    const ParametricSurfacePtr s =
        makeSurfaceOfRevolution({{0.0, 0.0}, {1.0, 0.05}, {1.0, 1.95}, {0.0, 2.0}});
    EXPECT_NO_THROW(validateParametricSurface(*s));
    for (const double pv : {0.0, 1.0, 4.0}) {
        const DVec3 radial(std::cos(pv), std::sin(pv), 0.0);
        EXPECT_GT(glm::dot(s->normal(0, pv, 1.5), radial), 0.9) << "side";
        EXPECT_LT(s->normal(0, pv, 0.3).z, -0.5) << "bottom";
        EXPECT_GT(s->normal(0, pv, 2.7).z, 0.5) << "top";
        // At the poles the normal is the limit from inside: straight down and up.
        EXPECT_LT(s->normal(0, pv, 0.0).z, -0.99) << "bottom pole";
        EXPECT_GT(s->normal(0, pv, 3.0).z, 0.99) << "top pole";
    }
    // The reversed profile flips it.
    const ParametricSurfacePtr r =
        makeSurfaceOfRevolution({{0.0, 2.0}, {1.0, 1.95}, {1.0, 0.05}, {0.0, 0.0}});
    EXPECT_LT(glm::dot(r->normal(0, 0.0, 1.5), DVec3(1, 0, 0)), -0.9);
}

TEST(SurfaceOfRevolution, IntervalEnclosesSampledPoints) {
    const ParametricSurfacePtr s = makeSurfaceOfRevolution(vase());
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> unit(0.0, 1.0), logWidth(-7.0, 0.7);
    for (int trial = 0; trial < 300; ++trial) {
        const double wphi = std::pow(10.0, logWidth(rng)),
                     ws = std::min(5.0, std::pow(10.0, logWidth(rng)));
        const double phi0 = unit(rng) * (kTwoPi - std::min(wphi, kTwoPi));
        // Some ranges start or end on a knot or at the domain's ends.
        double s0 = trial % 4 == 0 ? std::floor(unit(rng) * 5.0) : unit(rng) * (5.0 - ws);
        s0 = std::min(s0, 5.0 - ws);
        const num::Interval P(phi0, phi0 + wphi),
            S(s0, trial % 6 == 0 ? std::ceil(s0 + ws) : s0 + ws);
        const Point3<num::Interval> box = s->evaluate(0, P, S);
        for (int k = 0; k < 60; ++k) {
            const double pv = std::min(P.lo + unit(rng) * P.width(), P.hi);
            const double sv =
                k == 0 ? S.lo : (k == 1 ? S.hi : std::min(S.lo + unit(rng) * S.width(), S.hi));
            const DVec3 p = s->point(0, pv, sv);
            for (int a = 0; a < 3; ++a)
                ASSERT_TRUE(axis(box, a).contains(p[a]))
                    << "trial " << trial << " axis " << a << " s in [" << S.lo << ", " << S.hi
                    << "]";
        }
    }
    // Small ranges give small boxes.
    const Point3<num::Interval> small =
        s->evaluate(0, num::Interval(1.0, 1.001), num::Interval(2.3, 2.301));
    for (int a = 0; a < 3; ++a) EXPECT_LT(axis(small, a).width(), 5e-3);
}

TEST(SurfaceOfRevolution, BadProfilesAreErrors) {
    auto error = [](std::vector<glm::dvec2> profile) {
        return test::errorMessage([&] { makeSurfaceOfRevolution(std::move(profile)); });
    };
    std::string m = error({{1.0, 0.0}});
    EXPECT_TRUE(contains(m, "at least 2 points")) << m;
    m = error({});
    EXPECT_TRUE(contains(m, "at least 2 points")) << m;
    m = error({{1.0, 0.0}, {-0.5, 1.0}, {1.0, 2.0}});
    EXPECT_TRUE(contains(m, "profile point 1")) << m;
    EXPECT_TRUE(contains(m, "negative radius")) << m;
    m = error({{1.0, 0.0}, {1.0, std::nan("")}});
    EXPECT_TRUE(contains(m, "profile point 1")) << m;
    EXPECT_TRUE(contains(m, "not finite")) << m;
    m = error({{num::kInf, 0.0}, {1.0, 1.0}});
    EXPECT_TRUE(contains(m, "profile point 0")) << m;
    m = error({{1.0, 0.0}, {1.0, 1.0}, {1.0, 1.0}, {0.5, 2.0}});
    EXPECT_TRUE(contains(m, "profile points 1 and 2 are equal")) << m;
    m = error({{0.0, 0.0}, {0.0, 1.0}});
    EXPECT_TRUE(contains(m, "on the axis")) << m;
}

}  // namespace
}  // namespace strahl
