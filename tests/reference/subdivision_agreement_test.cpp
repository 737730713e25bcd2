// Subdivision surfaces (geometry/subdivision_surface.h): Embree's native
// subdivision geometry and the naive tracer's reference — the limit surface
// refined by strahl's own Catmull-Clark code (catmull_clark.h) — find the
// same hits at the same face parameters: quads, triangles and pentagons,
// creases and corners, holes, every boundary mode, displacement, instances.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "strahl/accel/accel.h"
#include "strahl/core/packet.h"
#include "strahl/core/rng.h"
#include "strahl/geometry/subdivision_surface.h"
#include "test_scene_pieces.h"
#include "strahl/reference/naive_accel.h"

namespace strahl {
namespace {

// A cube whose top is a pyramid of four triangles to an apex and whose front
// face (y = −1) is a pentagon through an extra point: faces of 3, 4 and 5
// vertices.
SubdivisionCage mixedCage() {
    SubdivisionCage c = test::cubeCage();
    c.positions.emplace_back(0.0, 0.0, 1.6);   // 8: the apex
    c.positions.emplace_back(0.0, -1.0, 0.3);  // 9: on the front face
    c.faceSizes = {4, 3, 3, 3, 3, 5, 4, 4, 4};
    c.indices = {0, 2, 3, 1,  4, 5, 8,  5, 7, 8,  7, 6, 8,  6, 4, 8,  0, 1, 5, 9, 4,  2, 6, 7, 3,  0, 4, 6, 2,  1, 3, 7, 5};
    return c;
}

double waves(const DVec3& p, const DVec3&, const DVec2&) { return 0.05 * std::sin(6.0 * p.x) * std::cos(5.0 * p.y); }

std::vector<Ray> raysAt(int n, uint64_t seed, float radius, float target) {
    Pcg32 rng(seed, 7);
    std::vector<Ray> rays;
    for (int k = 0; k < n; ++k) {
        const float a = 2.0f * kPi * rng.nextFloat(), z = 2.0f * rng.nextFloat() - 1.0f;
        const float s = std::sqrt(1.0f - z * z);
        Ray r;
        r.origin = radius * Vec3(s * std::cos(a), s * std::sin(a), z);
        const Vec3 aim(target * (2.0f * rng.nextFloat() - 1.0f), target * (2.0f * rng.nextFloat() - 1.0f),
                       target * (2.0f * rng.nextFloat() - 1.0f));
        r.dir = glm::normalize(aim - r.origin);
        rays.push_back(r);
    }
    return rays;
}

struct SubdivisionHitAgreement {
    int hits = 0, misses = 0, disagreements = 0, paramDisagreements = 0;
    double maxTError = 0.0, maxParamError = 0.0;
};

SubdivisionHitAgreement compare(const Accel& embree, const Accel& naive,
                                const std::vector<Ray>& rays) {
    SubdivisionHitAgreement r;
    for (const Ray& ray : rays) {
        const Hit a = embree.intersect(ray), b = naive.intersect(ray);
        if (a.valid() != b.valid()) {
            ++r.disagreements;
            continue;
        }
        if (!a.valid()) {
            ++r.misses;
            continue;
        }
        ++r.hits;
        r.maxTError = std::max(r.maxTError, double(std::abs(a.t - b.t)));
        if (a.primID != b.primID) {
            ++r.paramDisagreements;
            continue;
        }
        const double du = std::abs(a.u - b.u), dv = std::abs(a.v - b.v);
        r.maxParamError = std::max({r.maxParamError, du, dv});
        if (glm::dot(a.Ng, b.Ng) <= 0.0f) ++r.paramDisagreements;
    }
    return r;
}

SubdivisionSurface makeSurface(SubdivisionCage cage, int levels, DisplacementFunction displacement = nullptr) {
    SubdivisionDesc desc;
    desc.name = "test";
    desc.cage = std::move(cage);
    desc.levels = levels;
    desc.displacement = std::move(displacement);
    desc.displacementText = "test";
    return SubdivisionSurface(std::move(desc));
}

SubdivisionHitAgreement agreementFor(SubdivisionCage cage, int levels, DisplacementFunction displacement = nullptr) {
    const SubdivisionSurface surface = makeSurface(std::move(cage), levels, std::move(displacement));
    const std::vector<ShapeRef> shapes = {ShapeRef{nullptr, &surface}};
    const auto embree = buildEmbreeAccel(shapes, AccelBuildOptions{});
    const auto naive = buildNaiveAccel(shapes);
    return compare(*embree, *naive, raysAt(3000, 11, 6.0f, 1.2f));
}

// Embree evaluates the limit surface at the points the reference refines to
// (measured: the same to 1e-7) and splits its grid cells along the same
// diagonal, so agreeing hits meet to float precision: t within 1e-4 (measured
// 3e-6). Rays grazing a silhouette may be a hit for one and a miss for the
// other: at most 0.2 %.
void expectHitForHit(const SubdivisionHitAgreement& a, double tTolerance = 1e-4,
                     double paramTolerance = 1e-4) {
    EXPECT_GT(a.hits, 500);
    EXPECT_LE(a.disagreements, 6);
    EXPECT_EQ(a.paramDisagreements, 0);
    EXPECT_LT(a.maxTError, tTolerance);
    EXPECT_LT(a.maxParamError, paramTolerance);
}

TEST(SubdivisionAgreement, QuadCageHitForHit) {
    for (int levels : {1, 3, 5}) {
        SCOPED_TRACE(levels);
        expectHitForHit(agreementFor(test::cubeCage(), levels));
    }
}

TEST(SubdivisionAgreement, TrianglesAndPentagonsInEmbreesEncoding) {
    // Non-quad faces report their sub-quad in u and v (catmull_clark.h):
    // the same t, and parameters within 1 % of a sub-quad.
    for (int levels : {2, 4}) {
        SCOPED_TRACE(levels);
        expectHitForHit(agreementFor(mixedCage(), levels), 1e-4, 1e-2);
    }
}

TEST(SubdivisionAgreement, SemiSharpCreasesAndCorners) {
    SubdivisionCage semi = test::cubeCage();
    semi.creaseEdges = {0, 2, 2, 3, 3, 1, 1, 0};
    semi.creaseWeights = {1.5f, 1.5f, 0.5f, 2.0f};
    expectHitForHit(agreementFor(semi, 4));
    SubdivisionCage corner = test::cubeCage();
    corner.cornerVertices = {7, 0};
    corner.cornerWeights = {INFINITY, INFINITY};
    expectHitForHit(agreementFor(corner, 4));
}

TEST(SubdivisionAgreement, InfinitelySharpCreasesConvergeToTheReference) {
    // Embree approximates the patches next to an infinitely sharp crease
    // (its adaptive evaluation stops at a depth tied to the tessellation),
    // so its grid points there differ from the exact limit — by less at
    // every level (measured t: 6e-3, 2e-3, 8e-4 at levels 4, 5, 6).
    SubdivisionCage creased = test::cubeCage();
    creased.creaseEdges = {0, 2, 2, 3, 3, 1, 1, 0};
    creased.creaseWeights = {INFINITY, INFINITY, INFINITY, INFINITY};
    const SubdivisionHitAgreement coarse = agreementFor(creased, 4),
                                  fine = agreementFor(creased, 6);
    EXPECT_LE(coarse.disagreements + fine.disagreements, 6);
    EXPECT_LT(coarse.maxTError, 2e-2);
    EXPECT_LT(fine.maxTError, 2e-3);
    EXPECT_LT(fine.maxTError, coarse.maxTError / 3.0);
}

TEST(SubdivisionAgreement, HolesInEveryBoundaryMode) {
    SubdivisionCage holed = test::cubeCage();
    holed.holes = {1};
    for (SubdivisionBoundary mode : {SubdivisionBoundary::Smooth, SubdivisionBoundary::PinCorners,
                                     SubdivisionBoundary::PinBoundary, SubdivisionBoundary::PinAll}) {
        SCOPED_TRACE(subdivisionBoundaryName(mode));
        holed.boundary = mode;
        expectHitForHit(agreementFor(holed, 3));
    }
}

TEST(SubdivisionAgreement, DisplacedSurfaces) {
    // Embree adds the reference's offset at each of its grid points.
    expectHitForHit(agreementFor(test::cubeCage(), 4, waves));
    // Non-quad faces: Embree's sub-quad grids are offset the same way; t
    // within 1e-3 (measured 5e-4).
    expectHitForHit(agreementFor(mixedCage(), 4, waves), 1e-3, 2e-2);
}

TEST(SubdivisionAgreement, InstancesAndPackets) {
    const SubdivisionSurface surface = makeSurface(mixedCage(), 3, waves);
    AccelScene scene;
    scene.prototypes.push_back({ShapeRef{nullptr, &surface}});
    const Mat4 place = glm::rotate(glm::translate(Mat4(1.0f), Vec3(0.2f, -0.1f, 0.3f)), 0.7f, Vec3(1, 2, 3));
    scene.instances.emplace_back(0, place);
    const auto embree = buildEmbreeAccel(scene, AccelBuildOptions{});
    const auto naive = buildNaiveAccel(scene);
    const std::vector<Ray> rays = raysAt(1600, 3, 6.0f, 1.2f);
    const SubdivisionHitAgreement a = compare(*embree, *naive, rays);
    expectHitForHit(a, 1e-3, 2e-2);
    // 16-wide packets find what single rays find.
    for (size_t first = 0; first + 16 <= rays.size(); first += 16) {
        RayHitPacket16 packet;
        alignas(64) int valid[16];  // Embree reads the mask with aligned loads
        for (int i = 0; i < 16; ++i) {
            packet.setRay(i, rays[first + i]);
            valid[i] = -1;
        }
        embree->intersect16(valid, packet, RayCoherence::Incoherent);
        for (int i = 0; i < 16; ++i) {
            const Hit single = embree->intersect(rays[first + i]);
            const Hit lane = packet.hit(i);
            ASSERT_EQ(lane.valid(), single.valid());
            if (single.valid()) {
                EXPECT_EQ(lane.primID, single.primID);
                EXPECT_NEAR(lane.t, single.t, 1e-5f * single.t);
            }
        }
    }
}

TEST(SubdivisionAgreement, EmbreeHitsTheAnalyticLimitPoint) {
    // The limit of the cube's face centre (catmull_clark_test.cpp derives
    // 68/81): a ray down the z axis meets it on both tracers.
    const SubdivisionSurface surface = makeSurface(test::cubeCage(), 3);
    const std::vector<ShapeRef> shapes = {ShapeRef{nullptr, &surface}};
    Ray down;
    down.origin = Vec3(0.0f, 0.0f, 5.0f);
    down.dir = Vec3(0.0f, 0.0f, -1.0f);
    for (const auto& accel : {buildEmbreeAccel(shapes, AccelBuildOptions{}), buildNaiveAccel(shapes)}) {
        const Hit hit = accel->intersect(down);
        ASSERT_TRUE(hit.valid());
        EXPECT_NEAR(5.0f - hit.t, 68.0f / 81.0f, 2e-6f);
    }
}

TEST(SubdivisionAgreement, SpawnedRaysLeaveTheSurface) {
    // From every hit, a ray back towards the origin (where nothing is) must
    // miss: the spawn offset clears the tessellation on both tracers.
    const SubdivisionSurface surface = makeSurface(mixedCage(), 4, waves);
    const std::vector<ShapeRef> shapes = {ShapeRef{nullptr, &surface}};
    for (const auto& accel : {buildEmbreeAccel(shapes, AccelBuildOptions{}), buildNaiveAccel(shapes)}) {
        int hits = 0;
        for (const Ray& ray : raysAt(1500, 5, 6.0f, 1.2f)) {
            const Hit hit = accel->intersect(ray);
            if (!hit.valid()) continue;
            ++hits;
            const SurfaceInteraction si = surface.interaction(ray, hit);
            EXPECT_GT(glm::dot(si.Ns, si.Ng), 0.0f);
            EXPECT_NEAR(glm::length(si.Ns), 1.0f, 1e-5f);
            const Vec3 back = -ray.dir;
            Ray spawned;
            spawned.origin = offsetRayOrigin(si.p, si.pError, si.Ng, back);
            spawned.dir = back;
            EXPECT_FALSE(accel->occluded(spawned)) << "re-hit from t = " << hit.t;
        }
        EXPECT_GT(hits, 500);
    }
}

}  // namespace
}  // namespace strahl
