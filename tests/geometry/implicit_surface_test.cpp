// Implicit surfaces: the built-ins' formulas and gradients, the root finder
// against closed-form answers, and the ImplicitShape's hits, normals and
// tolerances (docs/implicit-surfaces.md).

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <iomanip>
#include <random>

#include "strahl/geometry/implicit_builtins.h"
#include "strahl/geometry/implicit_csg.h"
#include "strahl/geometry/implicit_formula.h"
#include "strahl/geometry/implicit_root_finder.h"
#include "strahl/geometry/implicit_shape.h"
#include "ray_probes.h"
#include "test_support.h"

namespace strahl {
namespace {

// Every built-in (and CSG, formula) with a point scale for sampling.
struct Named {
    std::string name;
    ImplicitSurfacePtr surface;
    double extent;
};

std::vector<Named> allSurfaces() {
    QuadricCoefficients cone;
    cone.xx = 1;
    cone.yy = 1;
    cone.zz = -0.5;
    return {
        {"sphere", makeImplicitSphere(1.3), 2.0},
        {"quadric", makeImplicitQuadric(cone), 2.0},
        {"torus", makeImplicitTorus(1.0, 0.3), 1.5},
        {"superellipsoid", makeSuperellipsoid(DVec3(1, 0.7, 0.5), 0.5, 0.8), 1.2},
        {"blobs", makeBlobs({{DVec3(0.3, 0, 0), 1.0, 1.0}, {DVec3(-0.4, 0.2, 0), 0.8, 1.5}}, 0.4),
         1.5},
        {"gyroid", makePeriodicSurface(PeriodicSurface::Gyroid, 1.5, 0.1, 0.0), 2.0},
        {"gyroid_sheet", makePeriodicSurface(PeriodicSurface::Gyroid, 1.5, 0.0, 0.2), 2.0},
        {"schwarz_p", makePeriodicSurface(PeriodicSurface::SchwarzP, 2.0, 0.3, 0.0), 2.0},
        {"schwarz_d", makePeriodicSurface(PeriodicSurface::SchwarzD, 2.0, 0.0, 0.0), 2.0},
        {"neovius", makePeriodicSurface(PeriodicSurface::Neovius, 2.0, 0.5, 0.0), 2.0},
    };
}

TEST(ImplicitSurface, SphereGradientIsTwoX) {
    const auto sphere = makeImplicitSphere(2.0);
    std::mt19937 rng(1);
    for (int i = 0; i < 1000; ++i) {
        const DVec3 x = randomPoint(rng, 3.0);
        EXPECT_DOUBLE_EQ(sphere->value(x), glm::dot(x, x) - 4.0);
        const DVec3 g = sphere->gradient(x), a = sphere->automaticGradient(x);
        for (int k = 0; k < 3; ++k) {
            EXPECT_DOUBLE_EQ(g[k], 2.0 * x[k]);
            EXPECT_DOUBLE_EQ(a[k], 2.0 * x[k]);
        }
    }
}

TEST(ImplicitSurface, AutomaticGradientMatchesAnalyticForEveryBuiltin) {
    std::mt19937 rng(2);
    for (const Named& s : allSurfaces()) {
        double worst = 0.0;
        for (int i = 0; i < 2000; ++i) {
            const DVec3 x = randomPoint(rng, s.extent);
            const DVec3 analytic = s.surface->gradient(x);
            const DVec3 automatic = s.surface->automaticGradient(x);
            const double scale = std::max(1.0, glm::length(analytic));
            worst = std::max(worst, glm::length(analytic - automatic) / scale);
        }
        EXPECT_LT(worst, 1e-9) << s.name;
    }
}

TEST(ImplicitSurface, IntervalRangeContainsSampledValues) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const Named& s : allSurfaces()) {
        for (int box = 0; box < 200; ++box) {
            const DVec3 a = randomPoint(rng, s.extent), b = randomPoint(rng, s.extent);
            const DVec3 lo = glm::min(a, b), hi = glm::max(a, b);
            const num::Interval range = s.surface->range(IntervalBox{
                num::Interval(lo.x, hi.x), num::Interval(lo.y, hi.y), num::Interval(lo.z, hi.z)});
            for (int i = 0; i < 20; ++i) {
                const DVec3 p = lo + DVec3(u(rng), u(rng), u(rng)) * (hi - lo);
                const double v = s.surface->value(p);
                EXPECT_TRUE(range.lo <= v && v <= range.hi) << s.name << " value " << v;
            }
        }
    }
}

// Nearest root of |o + t d|² = r², t > tmin, by geometry: the ray's closest
// approach to the centre is at t_c = −(o·d)/|d|², at distance h, and the
// roots are t_c ∓ √(r² − h²)/|d|. Accurate to ~1e-12 for the rays used here.
// (Not long double: x87 precision is not something a test should depend on.)
std::optional<double> analyticSphere(const DVec3& o, const DVec3& d, double r, double tmin) {
    const double dd = glm::dot(d, d);
    const double tc = -glm::dot(o, d) / dd;
    const DVec3 closest = o + tc * d;
    const double h2 = glm::dot(closest, closest);
    if (h2 > r * r) return std::nullopt;
    const double half = std::sqrt((r - std::sqrt(h2)) * (r + std::sqrt(h2)) / dd);
    for (double t : {tc - half, tc + half})
        if (t > tmin) return t;
    return std::nullopt;
}

// 10^5 random rays, from outside, from inside and grazing, against the
// closed-form sphere and the same sphere as a formula (generic root finder).
TEST(ImplicitShape, SphereAgreesWithAnalyticSphere) {
    const double r = 1.0;
    const ImplicitShape closedForm(makeImplicitSphere(r), Mat4(1.0f), {});
    ImplicitShapeOptions options;
    options.box = Bounds3{Vec3(-1.5f), Vec3(1.5f)};
    options.cellsPerAxis = 1;
    const ImplicitShape generic(makeFormulaSurface("x^2 + y^2 + z^2 - 1", {}), Mat4(1.0f), options);
    ASSERT_EQ(closedForm.primitiveCount(), 1u);
    ASSERT_EQ(generic.primitiveCount(), 1u);

    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int hits = 0, grazing = 0;
    for (int i = 0; i < 100000; ++i) {
        Ray ray;
        const int kind = i % 3;
        if (kind == 0) {  // from outside, aimed near the sphere
            ray = rayTowards(rng, 4.0, 1.0);
        } else if (kind == 1) {  // from inside
            ray.origin = Vec3(randomPoint(rng, 0.5));
            ray.dir = Vec3(randomDirection(rng));
        } else {  // grazing: passing within 1e-3 of the silhouette
            const DVec3 n = randomDirection(rng);
            Vec3 b1, b2;
            orthonormalBasis(Vec3(n), b1, b2);
            const double offset = r * (1.0 - 1e-3 * u(rng));
            ray.origin = Vec3(n) * static_cast<float>(offset) - b1 * 3.0f;
            ray.dir = b1;
        }
        const auto expected = analyticSphere(DVec3(ray.origin), DVec3(ray.dir), r, 0.0);
        for (const ImplicitShape* shape : {&closedForm, &generic}) {
            Hit hit;
            const bool found = shape->intersect(ray, 0, hit);
            ASSERT_EQ(found, expected.has_value()) << "ray " << i << " kind " << kind;
            if (!found) continue;
            const double t = static_cast<double>(*expected);
            ASSERT_NEAR(hit.t, t, 1e-5 * std::max(1.0, t))
                << "ray " << i << " kind " << kind << (shape == &generic ? " generic" : " closed")
                << std::hexfloat << " origin " << ray.origin.x << " " << ray.origin.y << " "
                << ray.origin.z << " dir " << ray.dir.x << " " << ray.dir.y << " " << ray.dir.z;
            const SurfaceInteraction si = shape->interaction(ray, hit);
            const Vec3 exact = Vec3(glm::normalize(DVec3(ray.origin) + t * DVec3(ray.dir)));
            ASSERT_LT(glm::length(si.Ng - exact), 1e-5f) << "ray " << i;
            ASSERT_LT(glm::length(si.p - exact * float(r)), 1e-5f) << "ray " << i;
        }
        hits += expected.has_value();
        grazing += kind == 2;
    }
    EXPECT_GT(hits, 60000);
    EXPECT_GT(grazing, 30000);
}

// A sheet 2e-5 thick: every ray that crosses it is reported.
TEST(ImplicitShape, ThinShellIsNotMissed) {
    ImplicitShapeOptions options;
    options.box = Bounds3{Vec3(-1.5f), Vec3(1.5f)};
    const ImplicitShape shell(makeFormulaSurface("abs(x^2 + y^2 + z^2 - 1) - 1e-5", {}),
                              Mat4(1.0f), options);
    std::mt19937 rng(5);
    int tested = 0;
    for (int i = 0; i < 5000; ++i) {
        const Ray ray = rayTowards(rng, 3.0, 0.9);
        // The shell's outer face is the sphere |x|² = 1 + 1e-5.
        const auto expected =
            analyticSphere(DVec3(ray.origin), DVec3(ray.dir), std::sqrt(1.0 + 1e-5), 0.0);
        if (!expected) continue;
        ++tested;
        const float nearest = nearestHit(shell, ray).t;
        ASSERT_NEAR(nearest, static_cast<double>(*expected), 1e-5) << "ray " << i;
    }
    EXPECT_GT(tested, 4000);
}

// The sphere at every scale from 1e-3 to 1e4, seen from up to 1e4 radii away.
TEST(ImplicitShape, ScaleSweep) {
    std::mt19937 rng(6);
    for (double r : {1e-3, 1e-1, 1.0, 1e2, 1e4}) {
        const ImplicitShape sphere(makeImplicitSphere(r), Mat4(1.0f), {});
        ImplicitShapeOptions options;
        options.box = Bounds3{Vec3(float(-1.5 * r)), Vec3(float(1.5 * r))};
        options.cellsPerAxis = 1;
        const ImplicitShape formula(
            makeFormulaSurface("x^2 + y^2 + z^2 - r^2", {{"r", r}}), Mat4(1.0f), options);
        for (double distance : {3.0, 100.0, 1e4}) {
            for (int i = 0; i < 300; ++i) {
                const Ray ray = rayTowards(rng, distance * r, 0.5 * r);
                const auto expected = analyticSphere(DVec3(ray.origin), DVec3(ray.dir), r, 0.0);
                ASSERT_TRUE(expected) << "r " << r << " distance " << distance;
                for (const ImplicitShape* shape : {&sphere, &formula}) {
                    Hit hit;
                    ASSERT_TRUE(shape->intersect(ray, 0, hit)) << "r " << r << " d " << distance;
                    const double t = static_cast<double>(*expected);
                    ASSERT_NEAR(hit.t, t, 1e-5 * t) << "r " << r << " distance " << distance;
                    // The point is as accurate as its float coordinates allow, and
                    // its error bound is honest.
                    const SurfaceInteraction si = shape->interaction(ray, hit);
                    EXPECT_LE(std::abs(glm::length(DVec3(si.p)) - r),
                              glm::length(DVec3(si.pError)) + 1e-6 * r)
                        << "r " << r << " distance " << distance;
                }
            }
        }
    }
}

// Rays spawned from a hit with the hit's error bound never find the surface
// they leave again, for the closed form and the generic root finder alike.
TEST(ImplicitShape, SpawnedRaysDoNotReintersect) {
    ImplicitShapeOptions options;
    const ImplicitShape torus(makeImplicitTorus(1.0, 0.4), Mat4(1.0f), options);
    std::mt19937 rng(7);
    int checked = 0;
    for (int i = 0; i < 3000; ++i) {
        const Ray ray = rayTowards(rng, 4.0, 1.2);
        const Hit best = nearestHit(torus, ray);
        if (!(best.t < kInfinity)) continue;
        const SurfaceInteraction si = torus.interaction(ray, best);
        // Reflect: the new ray leaves the surface on the side it came from.
        const Vec3 n = glm::dot(si.Ng, ray.dir) < 0 ? si.Ng : -si.Ng;
        const Vec3 reflected = glm::reflect(ray.dir, n);
        const Ray spawned = spawnRay(si.p, si.pError, si.Ng, reflected);
        for (uint32_t prim = 0; prim < torus.primitiveCount(); ++prim) {
            Hit again;
            if (torus.intersect(spawned, prim, again)) {
                ASSERT_GT(again.t, 1e-3f) << "ray " << i << " re-hit its own surface";
            }
        }
        ++checked;
    }
    EXPECT_GT(checked, 1000);
}

TEST(ImplicitShape, VanishingGradientGivesAFiniteNormal) {
    // The apex of the double cone x² + y² − z² = 0 has ∇f = 0.
    QuadricCoefficients cone;
    cone.xx = 1;
    cone.yy = 1;
    cone.zz = -1;
    ImplicitShapeOptions options;
    options.box = Bounds3{Vec3(-1.0f), Vec3(1.0f)};
    const ImplicitShape shape(makeImplicitQuadric(cone), Mat4(1.0f), options);
    Ray ray;
    ray.origin = Vec3(0.0f, 0.0f, 0.0f) - Vec3(1.0f, 0.0f, 0.0f);
    ray.dir = Vec3(1.0f, 0.0f, 0.0f);
    Hit hit;
    ASSERT_TRUE(shape.intersect(ray, 0, hit));
    EXPECT_NEAR(hit.t, 1.0f, 1e-5f);
    const SurfaceInteraction si = shape.interaction(ray, hit);
    EXPECT_TRUE(isFinite(si.Ng));
    EXPECT_NEAR(glm::length(si.Ng), 1.0f, 1e-5f);
}

TEST(ImplicitShape, TransformMovesTheSurfaceAndItsNormals) {
    // A unit sphere scaled by (2, 1, 1) and moved to x = 10: an ellipsoid.
    Mat4 m(1.0f);
    m[0][0] = 2.0f;
    m[3] = Vec4(10.0f, 0.0f, 0.0f, 1.0f);
    const ImplicitShape shape(makeImplicitSphere(1.0), m, {});
    const Bounds3 b = shape.bounds();
    EXPECT_LE(b.min.x, 8.0f);
    EXPECT_GE(b.max.x, 12.0f);
    Ray ray;
    ray.origin = Vec3(0.0f, 0.0f, 0.0f);
    ray.dir = Vec3(1.0f, 0.0f, 0.0f);
    Hit hit;
    ASSERT_TRUE(shape.intersect(ray, 0, hit));
    EXPECT_NEAR(hit.t, 8.0f, 1e-5f);
    // Off-axis: at p = (2 sinθ cosφ, sinθ sinφ, cosθ) on the ellipsoid
    // (x/2)² + y² + z² = 1 the normal is (p.x/4, p.y, p.z) normalised.
    const float theta = 0.8f, phi = 0.7f;
    const Vec3 p(2.0f * std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                 std::cos(theta));
    ray.origin = Vec3(10.0f + p.x, p.y, 5.0f);
    ray.dir = Vec3(0.0f, 0.0f, -1.0f);
    ASSERT_TRUE(shape.intersect(ray, 0, hit));
    EXPECT_NEAR(hit.t, 5.0f - p.z, 1e-5f);
    const SurfaceInteraction si = shape.interaction(ray, hit);
    const Vec3 expected = glm::normalize(Vec3(p.x / 4.0f, p.y, p.z));
    EXPECT_LT(glm::length(si.Ng - expected), 1e-4f);
}

TEST(ImplicitShape, CellsCullEmptySpace) {
    const ImplicitShape torus(makeImplicitTorus(1.0, 0.1), Mat4(1.0f), {});
    // A thin torus touches a small fraction of the 32³ cells of its box.
    EXPECT_GT(torus.primitiveCount(), 100u);
    EXPECT_LT(torus.primitiveCount(), 32u * 32u * 32u / 4u);
}

TEST(ImplicitShape, BadInputIsAClearError) {
    using test::contains;
    using test::errorMessage;
    EXPECT_TRUE(contains(errorMessage([] { makeImplicitSphere(-1.0); }), "radius"));
    EXPECT_TRUE(contains(errorMessage([] { makeImplicitTorus(1.0, std::nan("")); }),
                         "minor_radius"));
    EXPECT_TRUE(contains(errorMessage([] {
                             ImplicitShape(makeFormulaSurface("x + y", {}), Mat4(1.0f), {});
                         }),
                         "give the shape a \"box\""));
    ImplicitShapeOptions far;
    far.box = Bounds3{Vec3(10.0f), Vec3(11.0f)};
    EXPECT_TRUE(contains(errorMessage([&] {
                             ImplicitShape(makeImplicitSphere(1.0), Mat4(1.0f), far);
                         }),
                         "no point inside"));
    EXPECT_TRUE(contains(errorMessage([] {
                             ImplicitShape(makeImplicitSphere(1.0), Mat4(0.0f), {});
                         }),
                         "singular"));
}

TEST(ImplicitCsg, UnionIntersectionDifferenceSmoothUnion) {
    const auto a = makeImplicitSphere(1.0);
    const auto b = makeTransformed(makeImplicitSphere(1.0),
                                   glm::translate(Mat4(1.0f), Vec3(1.0f, 0.0f, 0.0f)));
    const auto u = makeCsg(CsgOperation::Union, {a, b});
    const auto i = makeCsg(CsgOperation::Intersection, {a, b});
    const auto d = makeCsg(CsgOperation::Difference, {a, b});
    const auto s = makeCsg(CsgOperation::SmoothUnion, {a, b}, 0.5);
    const DVec3 onlyA(-0.5, 0, 0), both(0.5, 0, 0), onlyB(1.5, 0, 0), neither(0.5, 2, 0);
    EXPECT_LT(u->value(onlyA), 0);
    EXPECT_LT(u->value(onlyB), 0);
    EXPECT_GT(u->value(neither), 0);
    EXPECT_LT(i->value(both), 0);
    EXPECT_GT(i->value(onlyA), 0);
    EXPECT_LT(d->value(onlyA), 0);
    EXPECT_GT(d->value(both), 0);
    EXPECT_LE(s->value(both), u->value(both));
    EXPECT_GT(s->value(neither), 0);
    const Bounds3 ub = *u->bounds();
    EXPECT_LE(ub.min.x, -1.0f);
    EXPECT_GE(ub.max.x, 2.0f);
}

}  // namespace
}  // namespace strahl
