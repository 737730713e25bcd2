// Curves (geometry/curve_set.h): Embree's native curve geometry and the naive
// tracer's reference intersector — two independent implementations of the
// same surfaces — find the same hits, for every type and basis (oriented
// ribbons: the cubic ones), through instances too.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "strahl/accel/accel.h"
#include "strahl/core/rng.h"
#include "strahl/geometry/curve_set.h"
#include "strahl/reference/naive_accel.h"
#include "sanitizers/sanitized.h"

namespace strahl {
namespace {

// Three wavy strands of 9 control points along x, radius tapering from 0.06
// to 0.03, and one strand whose radius grows.
CurveSetDesc wavyStrands(CurveBasis basis, CurveType type) {
    CurveSetDesc desc;
    desc.name = "wavy";
    desc.basis = basis;
    desc.type = type;
    std::vector<uint32_t> counts;
    for (int s = 0; s < 4; ++s) {
        // Bézier strands need 3k + 1 points.
        const int n = basis == CurveBasis::Bezier ? 10 : 9;
        for (int i = 0; i < n; ++i) {
            const float x = -2.0f + 4.0f * float(i) / float(n - 1);
            const float y = -0.9f + 0.6f * float(s) + 0.15f * std::sin(2.0f * x + float(s));
            const float z = 0.3f * std::cos(1.5f * x + float(s));
            float r = 0.06f - 0.03f * float(i) / float(n - 1);
            if (s == 3) r = 0.02f + 0.05f * float(i) / float(n - 1);
            desc.points.emplace_back(x, y, z, r);
            // Oriented ribbons: a normal across x that twists along the strand.
            const float twist = 0.8f * x + float(s);
            if (type == CurveType::Oriented) desc.normals.emplace_back(0.0f, std::sin(twist), std::cos(twist));
        }
        counts.push_back(static_cast<uint32_t>(n));
    }
    desc.segments = curveSegmentsOfStrands(counts, basis, desc.name);
    return desc;
}

// Rays from a sphere of radius 6 around the strands, aimed at random points
// of the strands' box.
std::vector<Ray> raysAtStrands(int n, uint64_t seed) {
    Pcg32 rng(seed, 5);
    std::vector<Ray> rays;
    for (int k = 0; k < n; ++k) {
        const float a = 2.0f * kPi * rng.nextFloat(), z = 2.0f * rng.nextFloat() - 1.0f;
        const float s = std::sqrt(1.0f - z * z);
        Ray r;
        r.origin = 6.0f * Vec3(s * std::cos(a), s * std::sin(a), z);
        const Vec3 target(4.2f * rng.nextFloat() - 2.1f, 2.4f * rng.nextFloat() - 1.2f, 0.8f * rng.nextFloat() - 0.4f);
        r.dir = glm::normalize(target - r.origin);
        rays.push_back(r);
    }
    return rays;
}

struct CurveHitAgreement {
    int hits = 0, disagreements = 0;
};

// Hits are compared where both tracers see the curve; a ray grazing a
// silhouette may be a hit for one and a miss for the other (Embree works in
// float), and flat ribbons that overlap on screen may swap which piece is
// nearer: those are counted and bounded instead. Agreeing hits meet to 1e-4
// (measured: 3e-6).
CurveHitAgreement compare(const Accel& embree, const Accel& naive, const std::vector<Ray>& rays, float tTolerance) {
    CurveHitAgreement result;
    for (const Ray& ray : rays) {
        const Hit a = embree.intersect(ray), b = naive.intersect(ray);
        if (a.valid() != b.valid()) {
            ++result.disagreements;
            continue;
        }
        EXPECT_EQ(embree.occluded(ray), a.valid());
        EXPECT_EQ(naive.occluded(ray), b.valid());
        if (!a.valid()) continue;
        ++result.hits;
        if (std::abs(a.t - b.t) > tTolerance) {
            ++result.disagreements;
            continue;
        }
        EXPECT_EQ(a.geomID, b.geomID);
        // Where two segments meet, either may own the hit.
        EXPECT_LE(std::abs(int(a.primID) - int(b.primID)), 1) << "t " << a.t;
        if (std::abs(a.v) < 0.9f && std::abs(a.u - 0.5f) < 0.45f && a.primID == b.primID) {
            const Vec3 na = glm::normalize(a.Ng), nb = glm::normalize(b.Ng);
            EXPECT_GT(glm::dot(na, nb), 0.99f) << "u " << a.u << " " << b.u;
        }
    }
    return result;
}

struct Case {
    CurveBasis basis;
    CurveType type;
};

class CurveAgreement : public ::testing::TestWithParam<Case> {};

TEST_P(CurveAgreement, EmbreeAndTheReferenceIntersectorFindTheSameHits) {
    const CurveSet curves(wavyStrands(GetParam().basis, GetParam().type));
    const std::vector<ShapeRef> shapes{ShapeRef{nullptr, &curves, nullptr}};
    const auto embree = buildEmbreeAccel(std::span<const ShapeRef>(shapes), {});
    const auto naive = buildNaiveAccel(std::span<const ShapeRef>(shapes));
    // A third of the rays under the sanitizers, where the reference
    // intersector's double-precision root finding is 20x slower.
    const int rays = test::fullOrSanitized(3000, 1000);
    const CurveHitAgreement r = compare(*embree, *naive, raysAtStrands(rays, 11), 1e-4f);
    EXPECT_GT(r.hits, rays / 10);
    // Silhouette grazes and float round-off: at most 1 % of the hits.
    EXPECT_LE(r.disagreements, r.hits / 100) << r.hits << " hits";
}

TEST_P(CurveAgreement, InstancesAgreeToo) {
    const CurveSet curves(wavyStrands(GetParam().basis, GetParam().type));
    AccelScene scene;
    scene.prototypes.push_back({ShapeRef{nullptr, &curves, nullptr}});
    const Mat4 turn = glm::rotate(Mat4(1.0f), 0.7f, Vec3(0.3f, 1.0f, 0.2f));
    scene.instances.push_back(AccelInstance{0, glm::scale(turn, Vec3(0.8f))});
    const auto embree = buildEmbreeAccel(scene, {});
    const auto naive = buildNaiveAccel(scene);
    const int rays = test::fullOrSanitized(2500, 800);
    const CurveHitAgreement r = compare(*embree, *naive, raysAtStrands(rays, 12), 1e-4f);
    EXPECT_GT(r.hits, rays / 25);
    EXPECT_LE(r.disagreements, r.hits / 100) << r.hits << " hits";
}

INSTANTIATE_TEST_SUITE_P(
    TypesAndBases, CurveAgreement,
    ::testing::Values(Case{CurveBasis::Linear, CurveType::Round}, Case{CurveBasis::Bezier, CurveType::Round},
                      Case{CurveBasis::BSpline, CurveType::Round}, Case{CurveBasis::CatmullRom, CurveType::Round},
                      Case{CurveBasis::Linear, CurveType::Flat}, Case{CurveBasis::Bezier, CurveType::Flat},
                      Case{CurveBasis::BSpline, CurveType::Flat}, Case{CurveBasis::CatmullRom, CurveType::Flat},
                      Case{CurveBasis::Bezier, CurveType::Oriented}, Case{CurveBasis::BSpline, CurveType::Oriented},
                      Case{CurveBasis::CatmullRom, CurveType::Oriented}),
    [](const ::testing::TestParamInfo<Case>& param) {
        return std::string(curveTypeName(param.param.type)) + "_" + curveBasisName(param.param.basis);
    });

}  // namespace
}  // namespace strahl
