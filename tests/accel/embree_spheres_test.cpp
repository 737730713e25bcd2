// Embree's built-in spheres (the implicit sphere's benchmark baseline): hits,
// normals and occlusion agree with the analytic ray–sphere intersection in
// double on random rays, and the 8- and 16-wide packets agree with single rays.

#include "strahl/accel/embree_spheres.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/core/rng.h"

namespace strahl {
namespace {

// Three spheres apart from each other, so "nearest" is unambiguous.
const std::vector<Vec4> kSpheres = {
    {-1.5f, 0.0f, 0.0f, 1.0f}, {1.5f, 0.2f, -0.5f, 0.8f}, {0.0f, 1.8f, 1.0f, 0.5f}};

struct AnalyticHit {
    bool hit = false;
    bool grazing = false;  // the ray passes within float noise of a silhouette
    double t = 0.0;
    uint32_t primID = kInvalidId;
};

// The nearest root of |o + t·d − c|² = r² in (tnear, tfar) over all spheres, in double.
AnalyticHit analyticIntersect(const Ray& ray, const std::vector<Vec4>& spheres) {
    AnalyticHit best;
    best.t = ray.tfar;
    const glm::dvec3 o(ray.origin), d(ray.dir);
    for (size_t i = 0; i < spheres.size(); ++i) {
        const glm::dvec3 c(Vec3(spheres[i]));
        const double r = spheres[i].w;
        const double a = glm::dot(d, d), proj = glm::dot(c - o, d) / a;
        const glm::dvec3 perp = (c - o) - proj * d;
        const double margin = r * r - glm::dot(perp, perp);
        if (std::abs(margin) < 1e-3 * r * r) best.grazing = true;
        if (margin < 0.0) continue;
        const double half = std::sqrt(margin / a);
        for (double t : {proj - half, proj + half}) {
            if (t > ray.tnear && t < best.t) {
                best = AnalyticHit{true, best.grazing, t, static_cast<uint32_t>(i)};
                break;
            }
        }
    }
    return best;
}

Vec3 randomIn(Pcg32& rng, float extent) {
    return Vec3(rng.nextFloat(), rng.nextFloat(), rng.nextFloat()) * (2.0f * extent) - extent;
}

// A ray from a random point of the scene's neighbourhood (some start inside a
// sphere) towards a random point of the cluster, with an occasional short tfar.
Ray randomRay(Pcg32& rng) {
    Ray ray;
    ray.origin = randomIn(rng, 4.0f);
    ray.dir = glm::normalize(randomIn(rng, 2.0f) - ray.origin);
    if (rng.nextFloat() < 0.2f) ray.tfar = 1.0f + 3.0f * rng.nextFloat();
    return ray;
}

TEST(EmbreeSpheres, HitsAgreeWithTheAnalyticSphere) {
    const auto accel = buildEmbreeSphereAccel(kSpheres, {});
    Pcg32 rng(17, 3);
    int hits = 0, misses = 0;
    for (int i = 0; i < 20000; ++i) {
        const Ray ray = randomRay(rng);
        const AnalyticHit expected = analyticIntersect(ray, kSpheres);
        if (expected.grazing) continue;
        const Hit hit = accel->intersect(ray);
        ASSERT_EQ(hit.valid(), expected.hit) << "ray " << i;
        EXPECT_EQ(accel->occluded(ray), expected.hit) << "ray " << i;
        if (!expected.hit) {
            ++misses;
            continue;
        }
        ++hits;
        EXPECT_EQ(hit.geomID, 0u);
        ASSERT_EQ(hit.primID, expected.primID) << "ray " << i;
        EXPECT_NEAR(hit.t, expected.t, 1e-4 * (1.0 + expected.t)) << "ray " << i;
        // Ng is the outward radius at the hit point, whichever side the ray came from.
        const Vec3 outward = glm::normalize(ray.at(hit.t) - Vec3(kSpheres[hit.primID]));
        EXPECT_GT(glm::dot(glm::normalize(hit.Ng), outward), 0.9999f) << "ray " << i;
    }
    EXPECT_GT(hits, 5000);
    EXPECT_GT(misses, 1000);
}

TEST(EmbreeSpheres, ARayFromInsideHitsTheFarSide) {
    const auto accel = buildEmbreeSphereAccel(kSpheres, {});
    Ray ray;
    ray.origin = Vec3(-1.5f, 0.0f, 0.0f);  // centre of sphere 0
    ray.dir = Vec3(0.0f, -1.0f, 0.0f);
    const Hit hit = accel->intersect(ray);
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.primID, 0u);
    EXPECT_NEAR(hit.t, 1.0f, 1e-6f);
    EXPECT_LT(hit.Ng.y, 0.0f);  // outward
    ray.tfar = 0.99f;
    EXPECT_FALSE(accel->occluded(ray));
}

TEST(EmbreeSpheres, BoundsEncloseEverySphere) {
    const auto accel = buildEmbreeSphereAccel(kSpheres, {});
    const Bounds3 b = accel->bounds();
    EXPECT_FLOAT_EQ(b.min.x, -2.5f);
    EXPECT_FLOAT_EQ(b.max.x, 2.3f);
    EXPECT_FLOAT_EQ(b.max.y, 2.3f);
    EXPECT_FLOAT_EQ(b.min.z, -1.3f);
    EXPECT_GT(accel->memoryBytes(), 0u);
}

TEST(EmbreeSpheres, NoSpheresMeansNoHits) {
    const auto accel = buildEmbreeSphereAccel({}, {});
    EXPECT_FALSE(accel->intersect(Ray{}).valid());
    EXPECT_FALSE(accel->occluded(Ray{}));
}

TEST(EmbreeSpheres, RejectsBadSpheres) {
    const std::vector<Vec4> zeroRadius = {{0.0f, 0.0f, 0.0f, 0.0f}};
    EXPECT_THROW(buildEmbreeSphereAccel(zeroRadius, {}), Error);
    const std::vector<Vec4> notFinite = {{0.0f, std::nanf(""), 0.0f, 1.0f}};
    EXPECT_THROW(buildEmbreeSphereAccel(notFinite, {}), Error);
}

template <int N>
void expectSpherePacketsMatchSingleRays() {
    const auto accel = buildEmbreeSphereAccel(kSpheres, {});
    Pcg32 rng(23, 4);
    int hits = 0;
    for (int round = 0; round < 300; ++round) {
        RayHitPacket<N> packet;
        alignas(64) int valid[N];
        Ray rays[N];
        for (int lane = 0; lane < N; ++lane) {
            rays[lane] = randomRay(rng);
            packet.setRay(lane, rays[lane]);
            valid[lane] = lane % 5 == 3 ? 0 : -1;  // some inactive lanes
        }
        accel->intersectPacket(valid, packet, RayCoherence::Incoherent);
        for (int lane = 0; lane < N; ++lane) {
            if (!valid[lane]) {
                EXPECT_EQ(packet.geomID[lane], kInvalidId) << "inactive lanes are untouched";
                continue;
            }
            if (analyticIntersect(rays[lane], kSpheres).grazing) continue;
            const Hit single = accel->intersect(rays[lane]);
            const Hit fromPacket = packet.hit(lane);
            ASSERT_EQ(single.valid(), fromPacket.valid());
            if (!single.valid()) continue;
            ++hits;
            EXPECT_EQ(single.geomID, fromPacket.geomID);
            EXPECT_EQ(single.primID, fromPacket.primID);
            EXPECT_NEAR(single.t, fromPacket.t, 1e-5f * (1.0f + single.t));
            EXPECT_GT(glm::dot(glm::normalize(single.Ng), glm::normalize(fromPacket.Ng)), 0.9999f);
        }
    }
    EXPECT_GT(hits, 20 * N);  // the test exercised real hits
}

TEST(EmbreeSpheres, Packets16MatchSingleRays) { expectSpherePacketsMatchSingleRays<16>(); }
TEST(EmbreeSpheres, Packets8MatchSingleRays) { expectSpherePacketsMatchSingleRays<8>(); }

}  // namespace
}  // namespace strahl
