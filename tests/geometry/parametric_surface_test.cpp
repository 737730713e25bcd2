// Parametric surfaces: the built-ins' formulas and partials, the adaptive
// grid, the tessellation's error, normals and crack-freeness, and the direct
// Newton mode's hits against closed forms (docs/parametric-surfaces.md).

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <map>
#include <random>

#include "ray_probes.h"
#include "sanitizers/sanitized.h"
#include "strahl/geometry/parametric_builtins.h"
#include "strahl/geometry/parametric_formula.h"
#include "strahl/geometry/parametric_grid.h"
#include "strahl/geometry/parametric_shape.h"
#include "strahl/geometry/parametric_tessellation.h"
#include "test_support.h"

namespace strahl {
namespace {

constexpr double kPi = num::kPiD;

double relativeError(const DVec3& a, const DVec3& b) {
    return glm::length(a - b) / std::max(1.0, glm::length(b));
}

struct NamedSurface {
    std::string name;
    ParametricSurfacePtr surface;
};

std::vector<NamedSurface> builtins() {
    ParamDomain torusDomain{0.0, 2 * kPi, 0.0, 2 * kPi, true, true};
    return {
        {"sphere", makeParametricSphere(1.5)},
        {"torus", makeParametricTorus(1.0, 0.3)},
        {"cylinder", makeParametricCylinder(0.5, -1.0, 2.0)},
        {"cone", makeParametricCone(1.0, 2.0)},
        {"mobius", makeMobiusStrip(1.0, 0.4)},
        {"formula", makeParametricFormula({"(R + r*cos(v))*cos(u)", "(R + r*cos(v))*sin(u)", "r*sin(v)"},
                                          torusDomain, {{"R", 1.0}, {"r", 0.3}})},
    };
}

TEST(ParametricSphere, PartialsAndNormalAreTheIssueFormulas) {
    const double r = 1.7;
    const ParametricSurfacePtr sphere = makeParametricSphere(r);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> rho(0.0, kPi), phi(0.0, 2 * kPi);
    for (int i = 0; i < 1000; ++i) {
        const double a = rho(rng), b = phi(rng);
        const SurfacePoint s = sphere->partials(0, a, b);
        const DVec3 f = r * DVec3(std::sin(a) * std::cos(b), std::sin(a) * std::sin(b), std::cos(a));
        const DVec3 fRho = r * DVec3(std::cos(a) * std::cos(b), std::cos(a) * std::sin(b), -std::sin(a));
        const DVec3 fPhi = r * DVec3(-std::sin(a) * std::sin(b), std::sin(a) * std::cos(b), 0.0);
        const DVec3 n = r * r * std::sin(a) *
                        DVec3(std::sin(a) * std::cos(b), std::sin(a) * std::sin(b), std::cos(a));
        EXPECT_LT(relativeError(s.p, f), 1e-14);
        EXPECT_LT(relativeError(s.dpdu, fRho), 1e-14);
        EXPECT_LT(relativeError(s.dpdv, fPhi), 1e-14);
        EXPECT_LT(relativeError(glm::cross(s.dpdu, s.dpdv), n), 1e-13);
        EXPECT_LT(relativeError(sphere->normal(0, a, b), glm::normalize(f)), 1e-9);
    }
}

TEST(ParametricSphere, NormalAtThePolesIsTheLimit) {
    const ParametricSurfacePtr sphere = makeParametricSphere(2.0);
    for (const double phi : {0.0, 1.0, 3.0, 2 * kPi}) {
        EXPECT_LT(glm::length(sphere->normal(0, 0.0, phi) - DVec3(0, 0, 1)), 1e-5);
        EXPECT_LT(glm::length(sphere->normal(0, kPi, phi) - DVec3(0, 0, -1)), 1e-5);
    }
}

TEST(ParametricBuiltins, HandWrittenPartialsMatchAutomaticDifferentiation) {
    std::mt19937 rng(11);
    for (const NamedSurface& s : builtins()) {
        const ParamDomain& d = s.surface->domain();
        std::uniform_real_distribution<double> u(d.u0, d.u1), v(d.v0, d.v1);
        for (int i = 0; i < 500; ++i) {
            const double a = u(rng), b = v(rng);
            const SurfacePoint hand = s.surface->partials(0, a, b);
            const SurfacePoint automatic = s.surface->automaticPartials(0, a, b);
            EXPECT_LT(relativeError(hand.p, automatic.p), 1e-13) << s.name;
            EXPECT_LT(relativeError(hand.dpdu, automatic.dpdu), 1e-13) << s.name;
            EXPECT_LT(relativeError(hand.dpdv, automatic.dpdv), 1e-13) << s.name;
        }
    }
}

TEST(ParametricBuiltins, IntervalEvaluationEnclosesThePoints) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const NamedSurface& s : builtins()) {
        const ParamDomain& d = s.surface->domain();
        for (int i = 0; i < 200; ++i) {
            double ua = d.u0 + unit(rng) * d.width(), ub = d.u0 + unit(rng) * d.width();
            double va = d.v0 + unit(rng) * d.height(), vb = d.v0 + unit(rng) * d.height();
            if (ua > ub) std::swap(ua, ub);
            if (va > vb) std::swap(va, vb);
            const Point3<num::Interval> box = s.surface->evaluate(0, num::Interval(ua, ub), num::Interval(va, vb));
            for (int k = 0; k < 20; ++k) {
                const DVec3 p = s.surface->point(0, ua + unit(rng) * (ub - ua), va + unit(rng) * (vb - va));
                EXPECT_TRUE(box.x.lo <= p.x && p.x <= box.x.hi && box.y.lo <= p.y && p.y <= box.y.hi &&
                            box.z.lo <= p.z && p.z <= box.z.hi)
                    << s.name;
            }
        }
    }
}

TEST(ParametricBuiltins, MobiusSeamIsTwisted) {
    const ParametricSurfacePtr m = makeMobiusStrip(1.0, 0.4);
    EXPECT_TRUE(m->domain().twistedU);
    for (const double s : {-0.4, -0.1, 0.0, 0.25, 0.4})
        EXPECT_LT(glm::length(m->point(0, 2 * kPi, s) - m->point(0, 0.0, -s)), 1e-14);
}

TEST(ParametricBuiltins, BadParametersAreNamed) {
    EXPECT_TRUE(test::contains(test::errorMessage([] { makeParametricSphere(-1.0); }), "radius"));
    EXPECT_TRUE(test::contains(test::errorMessage([] { makeParametricTorus(1.0, 2.0); }), "minor_radius"));
    EXPECT_TRUE(test::contains(test::errorMessage([] { makeParametricCylinder(1.0, 2.0, 1.0); }), "z_min"));
    EXPECT_TRUE(test::contains(test::errorMessage([] { makeParametricCone(1.0, NAN); }), "height"));
    EXPECT_TRUE(test::contains(test::errorMessage([] { makeMobiusStrip(1.0, 1.5); }), "half_width"));
}

TEST(ParametricFormula, ErrorsNameTheCoordinateAndThePlace) {
    const ParamDomain unit;
    EXPECT_TRUE(test::contains(test::errorMessage([&] { makeParametricFormula({"u", "v +", "0"}, unit, {}); }),
                               "y: column"));
    // 1/u is infinite on the border u = 0.
    EXPECT_TRUE(test::contains(test::errorMessage([&] { makeParametricFormula({"1/u", "v", "0"}, unit, {}); }),
                               "not finite at (u, v) = (0,"));
    const ParamDomain inverted{1.0, 0.0, 0.0, 1.0};
    EXPECT_TRUE(test::contains(
        test::errorMessage([&] { makeParametricFormula({"u", "v", "0"}, inverted, {}); }), "empty or inverted"));
    const ParamDomain empty{0.0, 1.0, 0.5, 0.5};
    EXPECT_TRUE(test::contains(
        test::errorMessage([&] { makeParametricFormula({"u", "v", "0"}, empty, {}); }), "empty or inverted"));
}

// ---- grid and tessellation ---------------------------------------------------

Tessellation tessellateUniform(const ParametricSurface& s, int segments,
                               ParametricNormals normals = ParametricNormals::Exact) {
    ParametricGridOptions options;
    options.initialSegmentsU = options.initialSegmentsV = segments;
    return tessellateParametric(s, buildParametricGrid(s, options), normals);
}

// Largest distance from the sphere of radius r over the triangles' centroids
// and edge midpoints (where a flat triangle is farthest from the surface).
double sphereChordError(const TriangleMesh& mesh, double r) {
    double worst = 0.0;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const DVec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
            c(mesh.positions[mesh.indices[3 * t + 2]]);
        for (const DVec3& x : {(a + b + c) / 3.0, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (a + c)})
            worst = std::max(worst, r - glm::length(x));
    }
    return worst;
}

TEST(ParametricTessellation, ErrorFallsFourfoldPerHalvingOfTheEdgeLength) {
    const ParametricSurfacePtr sphere = makeParametricSphere(1.0);
    double previous = 0.0;
    for (const int segments : {8, 16, 32, 64, 128}) {
        const double error = sphereChordError(tessellateUniform(*sphere, segments).mesh, 1.0);
        if (previous > 0.0) {
            const double ratio = previous / error;
            // Second order: ~4 per halving; the float positions add nothing at this size.
            EXPECT_GT(ratio, 3.5) << segments;
            EXPECT_LT(ratio, 4.5) << segments;
        }
        previous = error;
    }
}

TEST(ParametricTessellation, AdaptiveGridMeetsItsChordBound) {
    for (const NamedSurface& s : builtins()) {
        ParametricGridOptions options;
        options.initialSegmentsU = options.initialSegmentsV = 2;
        options.maxChordError = 1e-3;
        const ParametricGrid grid = buildParametricGrid(*s.surface, options);
        EXPECT_FALSE(grid.capped) << s.name;
        const PatchGrid& g = grid.patches[0];
        // Midpoint deviation of every grid line's intervals.
        for (size_t j = 0; j < g.v.size(); ++j)
            for (size_t i = 0; i + 1 < g.u.size(); ++i) {
                const DVec3 a = s.surface->point(0, g.u[i], g.v[j]), b = s.surface->point(0, g.u[i + 1], g.v[j]);
                const DVec3 m = s.surface->point(0, 0.5 * (g.u[i] + g.u[i + 1]), g.v[j]);
                EXPECT_LE(glm::length(m - 0.5 * (a + b)), 1e-3) << s.name;
            }
    }
}

TEST(ParametricTessellation, AdaptiveGridRefinesOnlyWhereCurved) {
    // A cylinder is straight along z: one interval suffices there, while φ needs many.
    const ParametricSurfacePtr cylinder = makeParametricCylinder(1.0, 0.0, 10.0);
    ParametricGridOptions options;
    options.initialSegmentsU = options.initialSegmentsV = 1;
    options.maxChordError = 1e-3;
    const PatchGrid g = buildParametricGrid(*cylinder, options).patches[0];
    EXPECT_EQ(g.v.size(), 2u);
    EXPECT_GT(g.u.size(), 32u);
    // An edge-length bound then cuts the long direction too.
    options.maxEdgeLength = [](const DVec3&) { return 0.5; };
    EXPECT_GE(buildParametricGrid(*cylinder, options).patches[0].v.size(), 21u);
}

// Counts, over triangle edges keyed by their end positions, those not shared
// by exactly two triangles: 0 for a closed surface without cracks.
size_t borderEdges(const TriangleMesh& mesh) {
    std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> uses;
    auto key = [&](uint32_t i) {
        const Vec3& p = mesh.positions[i];
        return std::array<float, 3>{p.x, p.y, p.z};
    };
    for (size_t t = 0; t < mesh.triangleCount(); ++t)
        for (int e = 0; e < 3; ++e) {
            auto a = key(mesh.indices[3 * t + e]), b = key(mesh.indices[3 * t + (e + 1) % 3]);
            if (b < a) std::swap(a, b);
            ++uses[{a, b}];
        }
    size_t open = 0;
    for (const auto& [edge, count] : uses) open += count != 2;
    return open;
}

TEST(ParametricTessellation, ClosedSurfacesHaveNoCracksAtSeamsAndPoles) {
    for (const auto& surface : {makeParametricSphere(1.0), makeParametricTorus(2.0, 0.5)}) {
        EXPECT_EQ(borderEdges(tessellateUniform(*surface, 12).mesh), 0u) << surface->describe();
        ParametricGridOptions options;
        options.initialSegmentsU = options.initialSegmentsV = 3;
        options.maxChordError = 1e-3;
        const Tessellation adaptive =
            tessellateParametric(*surface, buildParametricGrid(*surface, options), ParametricNormals::Exact);
        EXPECT_EQ(borderEdges(adaptive.mesh), 0u) << surface->describe();
    }
}

TEST(ParametricTessellation, MobiusStripIsOneBandAcrossItsTwistedSeam) {
    // Its only border is the single edge loop of the strip's rim: 2 × segments edges.
    const ParametricSurfacePtr m = makeMobiusStrip(1.0, 0.3);
    const Tessellation t = tessellateUniform(*m, 16);
    EXPECT_EQ(borderEdges(t.mesh), 2u * 16u);
}

TEST(ParametricTessellation, PolesCollapseWithoutDegenerateTriangles) {
    const Tessellation t = tessellateUniform(*makeParametricSphere(1.0), 8);
    // 8 × 8 cells, two triangles each, minus one per cell of the two pole rows.
    EXPECT_EQ(t.mesh.triangleCount(), 2u * 64u - 2u * 8u);
    for (size_t i = 0; i < t.mesh.triangleCount(); ++i) {
        const Vec3 a = t.mesh.positions[t.mesh.indices[3 * i]], b = t.mesh.positions[t.mesh.indices[3 * i + 1]],
                   c = t.mesh.positions[t.mesh.indices[3 * i + 2]];
        EXPECT_GT(glm::length(glm::cross(b - a, c - a)), 0.0f);
    }
}

TEST(ParametricTessellation, HitsMapBackToTheSurfaceWithItsExactNormal) {
    const ParametricSurfacePtr torus = makeParametricTorus(1.0, 0.4);
    const Mat4 toWorld = glm::scale(glm::translate(Mat4(1.0f), Vec3(1, 2, 3)), Vec3(2.0f, 1.0f, 1.0f));
    Tessellation t = tessellateUniform(*torus, 64);
    TriangleMesh mesh = t.mesh;
    mesh.transform(toWorld);
    const TessellatedSurface tess(torus, std::move(t), toWorld, ParametricNormals::Exact);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(glm::dmat4(toWorld))));
    for (int i = 0; i < 500; ++i) {
        const uint32_t prim = static_cast<uint32_t>(rng() % mesh.triangleCount());
        float b1 = unit(rng), b2 = unit(rng);
        if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
        const SurfaceInteraction si = tess.interaction(mesh, prim, b1, b2);
        const Vec2 uv = tess.parameters(mesh, prim, b1, b2);
        // The point on the surface at those parameters is within the chord error of the hit.
        const DVec3 onSurface = DVec3(glm::dmat4(toWorld) * glm::dvec4(torus->point(0, uv.x, uv.y), 1.0));
        EXPECT_LT(glm::length(onSurface - DVec3(si.p)), 0.01);
        const DVec3 exact = glm::normalize(normalMatrix * torus->normal(0, uv.x, uv.y));
        EXPECT_LT(glm::length(DVec3(si.Ns) - exact), 1e-5);
        EXPECT_GT(glm::dot(si.Ns, si.Ng), 0.9f);
    }
}

TEST(ParametricTessellation, InterpolatedNormalsAreAnOption) {
    const ParametricSurfacePtr sphere = makeParametricSphere(1.0);
    const Tessellation t = tessellateUniform(*sphere, 8, ParametricNormals::Interpolated);
    ASSERT_EQ(t.mesh.normals.size(), t.mesh.positions.size());
    for (size_t i = 0; i < t.mesh.positions.size(); ++i)
        EXPECT_LT(glm::length(t.mesh.normals[i] - glm::normalize(t.mesh.positions[i])), 1e-4f);
}

// ---- direct mode ---------------------------------------------------------------

// Nearest t > 0 of o + t·d on the sphere |x| = r, or -1.
double analyticSphere(const DVec3& o, const DVec3& d, double r) {
    const double b = glm::dot(o, d), c = glm::dot(o, o) - r * r, a = glm::dot(d, d);
    const double disc = b * b - a * c;
    if (disc < 0.0) return -1.0;
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    double t0 = q / a, t1 = c / q;
    if (t0 > t1) std::swap(t0, t1);
    return t0 > 0.0 ? t0 : (t1 > 0.0 ? t1 : -1.0);
}

TEST(ParametricDirect, SphereAgreesWithTheAnalyticSphere) {
    const double r = 1.3;
    const ParametricShape shape(makeParametricSphere(r), Mat4(1.0f), ParametricShapeOptions{});
    std::mt19937 rng(2024);
    int hits = 0, disagreements = 0;
    const int rays = test::fullOrSanitized(100000, 25000);  // slow under the sanitizers
    for (int i = 0; i < rays; ++i) {
        const Ray ray = rayTowards(rng, 4.0, 1.5);
        const double exact = analyticSphere(DVec3(ray.origin), DVec3(ray.dir), r);
        const Hit hit = nearestHit(shape, ray);
        if ((exact > 0.0) != hit.valid()) {
            ADD_FAILURE() << "ray " << i << ": analytic t " << exact << ", direct t " << hit.t
                          << ", closest approach / r "
                          << glm::length(glm::cross(DVec3(ray.origin), DVec3(ray.dir))) / r;
            ++disagreements;
            continue;
        }
        if (!hit.valid()) continue;
        ++hits;
        EXPECT_LT(std::abs(hit.t - exact) / exact, 1e-5) << "ray " << i;
    }
    EXPECT_GT(hits, rays * 3 / 10);
    EXPECT_EQ(disagreements, 0);
}

TEST(ParametricDirect, TransformedTorusHitsLieOnTheSurface) {
    // Placed in the world (rotated, scaled unevenly, moved), the direct mode's
    // hits still lie on the surface, at the ray's t, facing the ray.
    const ParametricSurfacePtr torus = makeParametricTorus(1.0, 0.35);
    const Mat4 toWorld = glm::rotate(glm::scale(glm::translate(Mat4(1.0f), Vec3(0.5f, -0.2f, 0.3f)),
                                                Vec3(1.2f, 0.8f, 1.0f)),
                                     0.7f, Vec3(1.0f, 0.3f, 0.0f));
    const ParametricShape shape(torus, toWorld, ParametricShapeOptions{});
    const glm::dmat4 toObject = glm::inverse(glm::dmat4(toWorld));
    std::mt19937 rng(99);
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
        const Ray ray = rayTowards(rng, 5.0, 1.2);
        const Hit hit = nearestHit(shape, ray);
        if (!hit.valid()) continue;
        ++hits;
        const SurfaceInteraction si = shape.interaction(ray, hit);
        EXPECT_LT(glm::length(si.p - ray.at(hit.t)), 1e-5f * std::max(1.0f, hit.t));
        // The point is on the torus: (sqrt(x²+y²) − R)² + z² = r² in object space.
        const DVec3 p = DVec3(toObject * glm::dvec4(DVec3(si.p), 1.0));
        const double ring = std::sqrt(p.x * p.x + p.y * p.y) - 1.0;
        EXPECT_NEAR(std::sqrt(ring * ring + p.z * p.z), 0.35, 1e-5);
        EXPECT_LT(glm::dot(si.Ng, ray.dir), 0.0f) << "a first hit from outside faces the ray";
    }
    EXPECT_GT(hits, 3000);
}

TEST(ParametricDirect, SpawnedRaysDoNotRehitTheirOwnSurface) {
    const ParametricShape shape(makeParametricTorus(1.0, 0.4), Mat4(1.0f), ParametricShapeOptions{});
    std::mt19937 rng(4);
    int spawned = 0;
    for (int i = 0; i < 5000; ++i) {
        const Ray ray = rayTowards(rng, 4.0, 1.0);
        const Hit hit = nearestHit(shape, ray);
        if (!hit.valid()) continue;
        const SurfaceInteraction si = shape.interaction(ray, hit);
        // Leaving on the outside, in the mirror direction: the torus is not
        // convex, so a real second hit is possible; a spurious one has t ≈ 0.
        const Vec3 dir = glm::reflect(ray.dir, si.Ng);
        const Hit again = nearestHit(shape, spawnRay(si.p, si.pError, si.Ng, dir));
        if (again.valid()) {
            EXPECT_GT(again.t, 1e-3f) << "ray " << i;
        }
        ++spawned;
    }
    EXPECT_GT(spawned, 1000);
}

}  // namespace
}  // namespace strahl
