// CurveSet (geometry/curve_set.h): strands to segments, bad input, and the
// reference intersector against closed forms — a straight round curve is an
// open cylinder, a linear one a capsule — plus interactions on the surface.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/geometry/curve_set.h"

namespace strahl {
namespace {

CurveSetDesc straight(CurveBasis basis, CurveType type, float radius) {
    CurveSetDesc desc;
    desc.name = "straight";
    desc.basis = basis;
    desc.type = type;
    const int n = curveBasisPoints(basis);
    for (int i = 0; i < n; ++i) desc.points.emplace_back(-1.0f + 2.0f * float(i) / float(n - 1), 0.0f, 0.0f, radius);
    desc.segments = {0};
    return desc;
}

Ray rayFrom(const Vec3& origin, const Vec3& dir) {
    Ray r;
    r.origin = origin;
    r.dir = dir;
    return r;
}

TEST(CurveSet, StrandsBecomeOverlappingSegments) {
    const std::vector<uint32_t> counts{4, 6};
    EXPECT_EQ(curveSegmentsOfStrands(counts, CurveBasis::BSpline, "s"), (std::vector<uint32_t>{0, 4, 5, 6}));
    EXPECT_EQ(curveSegmentsOfStrands(std::vector<uint32_t>{7}, CurveBasis::Bezier, "s"),
              (std::vector<uint32_t>{0, 3}));
    EXPECT_EQ(curveSegmentsOfStrands(std::vector<uint32_t>{3, 2}, CurveBasis::Linear, "s"),
              (std::vector<uint32_t>{0, 1, 3}));
    EXPECT_THROW(curveSegmentsOfStrands(std::vector<uint32_t>{3}, CurveBasis::CatmullRom, "s"), Error);
    EXPECT_THROW(curveSegmentsOfStrands(std::vector<uint32_t>{5}, CurveBasis::Bezier, "s"), Error);
}

TEST(CurveSet, BadInputIsRefusedWithTheCurvesName) {
    const auto refused = [](CurveSetDesc desc, const char* words) {
        try {
            CurveSet set(std::move(desc));
            ADD_FAILURE() << "accepted; expected: " << words;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("curves 'straight'"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
    };
    CurveSetDesc d = straight(CurveBasis::BSpline, CurveType::Round, 0.1f);
    d.segments.clear();
    refused(d, "no segments");
    d = straight(CurveBasis::BSpline, CurveType::Round, 0.1f);
    d.segments = {1};
    refused(d, "segment 0 starts at control point 1");
    d = straight(CurveBasis::BSpline, CurveType::Round, 0.1f);
    d.points[2].y = std::nanf("");
    refused(d, "control point 2 is not finite");
    d = straight(CurveBasis::BSpline, CurveType::Round, 0.1f);
    d.points[1].w = -0.5f;
    refused(d, "control point 1 has radius -0.5");
    d = straight(CurveBasis::CatmullRom, CurveType::Round, 0.1f);
    d.points[0].w = 3.0f;  // the tangent at p1 then drives the radius below 0
    refused(d, "negative radius");
    d = straight(CurveBasis::Bezier, CurveType::Flat, 0.1f);
    d.flatSegments = 0;
    refused(d, "flat_segments");
}

TEST(CurveSet, AStraightRoundCubicIsAnOpenCylinder) {
    for (CurveBasis basis : {CurveBasis::Bezier, CurveBasis::CatmullRom}) {
        const CurveSet set(straight(basis, CurveType::Round, 0.25f));
        const float x0 = basis == CurveBasis::Bezier ? -1.0f : -1.0f / 3.0f;  // Catmull-Rom runs p1 -> p2
        Hit hit;
        const Ray side = rayFrom(Vec3(0.1f, 0.1f, 5.0f), Vec3(0, 0, -1));
        ASSERT_TRUE(set.intersect(side, 0, hit)) << curveBasisName(basis);
        // z of the cylinder y² + z² = r² at y = 0.1.
        EXPECT_NEAR(hit.t, 5.0f - std::sqrt(0.0625f - 0.01f), 1e-5f);
        EXPECT_NEAR(hit.u, (0.1f - x0) / (-2.0f * x0), 1e-5f);
        const Vec3 n = glm::normalize(hit.Ng);
        EXPECT_NEAR(n.x, 0.0f, 1e-5f);
        EXPECT_NEAR(n.y, 0.1f / 0.25f, 1e-4f);
        // Open ends: a ray down the axis meets no wall.
        EXPECT_FALSE(set.intersect(rayFrom(Vec3(-5, 0, 0), Vec3(1, 0, 0)), 0, hit));
        // Beyond the segment's end there is nothing.
        EXPECT_FALSE(set.intersect(rayFrom(Vec3(x0 - 0.05f, 0, 5), Vec3(0, 0, -1)), 0, hit));
    }
}

TEST(CurveSet, ARoundLinearSegmentIsACapsuleAndJoinsItsNeighbour) {
    const CurveSet set(straight(CurveBasis::Linear, CurveType::Round, 0.25f));
    Hit hit;
    // Into the end cap, a sphere of radius 0.25 around (1, 0, 0).
    ASSERT_TRUE(set.intersect(rayFrom(Vec3(5, 0.1f, 0), Vec3(-1, 0, 0)), 0, hit));
    EXPECT_NEAR(hit.t, 4.0f - std::sqrt(0.0625f - 0.01f), 1e-5f);
    // A tapered segment: the cone touches both spheres.
    CurveSetDesc cone = straight(CurveBasis::Linear, CurveType::Round, 0.5f);
    cone.points[1].w = 0.1f;
    const CurveSet tapered(std::move(cone));
    ASSERT_TRUE(tapered.intersect(rayFrom(Vec3(0, 0, 5), Vec3(0, 0, -1)), 0, hit));
    // The cone is the envelope of the spheres (c(s), r(s)); its normal n has
    // n·x = −(r1 − r0)/L = 0.2. At x = 0: −1 + 2s + 0.2 r(s) = 0 with
    // r(s) = 0.5 − 0.4 s gives s = 0.9/1.92, and z = r(s)·√(1 − 0.2²).
    const float s = 0.9f / 1.92f, r = 0.5f - 0.4f * s;
    EXPECT_NEAR(hit.t, 5.0f - r * std::sqrt(0.96f), 1e-5f);
    EXPECT_NEAR(glm::normalize(hit.Ng).x, 0.2f, 1e-4f);

    CurveSetDesc strand = straight(CurveBasis::Linear, CurveType::Round, 0.2f);
    strand.points.emplace_back(2.0f, 1.0f, 0.0f, 0.2f);
    strand.segments = curveSegmentsOfStrands(std::vector<uint32_t>{3}, CurveBasis::Linear, "straight");
    const CurveSet joined(std::move(strand));
    EXPECT_FALSE(joined.hasLeftNeighbour(0));
    EXPECT_TRUE(joined.hasLeftNeighbour(1));
}

TEST(CurveSet, InteractionsLieOnTheSurfaceAndRunAlongTheStrand) {
    CurveSetDesc desc;
    desc.name = "arc";
    desc.basis = CurveBasis::BSpline;
    for (int i = 0; i < 7; ++i) {
        const float a = 0.4f * float(i);
        desc.points.emplace_back(2.0f * std::cos(a), 2.0f * std::sin(a), 0.0f, 0.1f);
    }
    desc.segments = curveSegmentsOfStrands(std::vector<uint32_t>{7}, desc.basis, desc.name);
    const CurveSet set(std::move(desc));
    float lastU = -1.0f;
    for (uint32_t prim = 0; prim < set.primitiveCount(); ++prim) {
        const Bounds3 b = set.primitiveBounds(prim);
        const Vec3 c = b.center();
        const Ray ray = rayFrom(Vec3(c.x, c.y, 4.0f), Vec3(0, 0, -1));
        Hit hit;
        if (!set.intersect(ray, prim, hit)) continue;
        hit.primID = prim;
        const SurfaceInteraction si = set.interaction(ray, hit);
        EXPECT_LE(glm::abs(glm::length(si.Ng) - 1.0f), 1e-5f);
        EXPECT_GT(si.Ng.z, 0.0f);  // faces the ray, outwards
        EXPECT_GE(si.p.x, b.min.x);
        EXPECT_LE(si.p.x, b.max.x);
        EXPECT_GT(si.uv.x, lastU);  // root to tip
        lastU = si.uv.x;
        // 0.1 (the radius) from the centre line, sampled finely.
        glm::dvec4 bz[4];
        set.bezierOf(prim, bz);
        double nearest = 1e9;
        for (int k = 0; k <= 4000; ++k) {
            const double u = k / 4000.0, w = 1.0 - u;
            const glm::dvec4 q = w * w * w * bz[0] + 3.0 * w * w * u * bz[1] + 3.0 * w * u * u * bz[2] + u * u * u * bz[3];
            nearest = std::min(nearest, glm::length(glm::dvec3(q) - glm::dvec3(si.p)));
        }
        EXPECT_NEAR(nearest, 0.1, 1e-5);
    }
    EXPECT_GT(lastU, 0.5f);
}

TEST(CurveSet, FlatRibbonsFaceTheRayAndIgnoreHitsAtTheirOwnOrigin) {
    const CurveSet set(straight(CurveBasis::Bezier, CurveType::Flat, 0.2f));
    const Ray ray = rayFrom(Vec3(0.3f, 0.1f, 5.0f), glm::normalize(Vec3(0.05f, 0.0f, -1.0f)));
    Hit hit;
    ASSERT_TRUE(set.intersect(ray, 0, hit));
    // n = normalize(C' × d) = +y is the v = −1 edge; y = 0.1 lies half way there.
    EXPECT_NEAR(hit.v, -0.5f, 0.02f);
    hit.primID = 0;
    const SurfaceInteraction si = set.interaction(ray, hit);
    EXPECT_LT(glm::dot(si.Ng, ray.dir), -0.99f);
    // Bent like a cylinder's normal half way out: towards +y by sin = 0.5.
    EXPECT_NEAR(si.Ns.y, 0.5f, 0.02f);
    // Hits nearer to the origin than 2r = 0.4 are ignored.
    EXPECT_FALSE(set.intersect(rayFrom(Vec3(0.3f, 0.1f, 0.3f), Vec3(0, 0, -1)), 0, hit));
    EXPECT_TRUE(set.intersect(rayFrom(Vec3(0.3f, 0.1f, 0.5f), Vec3(0, 0, -1)), 0, hit));
}

}  // namespace
}  // namespace strahl
