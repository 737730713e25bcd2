// The Embree user-geometry callback contract (src/accel/embree_accel.cpp),
// exercised with implicit shapes — a torus cut into many cells (generic root
// finder) and a sphere (closed form, one cell) — and a directly intersected
// parametric cone (Newton's method on sub-patches), next to a triangle mesh:
//  - intersect8/16 with random valid masks agree exactly with single rays
//    (t, geomID, primID, Ng) on the implicit shapes;
//  - lanes with valid = 0 are not touched at all (every field keeps its
//    sentinel), and a miss writes nothing but leaves tfar alone;
//  - a hit's instID is kInvalidId (no instancing);
//  - hits only inside (tnear, tfar): a tfar short of the hit misses, a tnear
//    past it finds the next one;
//  - occluded() agrees with intersect().

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/core/rng.h"
#include "strahl/geometry/implicit_builtins.h"
#include "strahl/geometry/implicit_shape.h"
#include "strahl/geometry/parametric_builtins.h"
#include "strahl/geometry/parametric_shape.h"

#include "test_scene_pieces.h"

namespace strahl {
namespace {

constexpr uint32_t kSentinelId = 0xDEADBEEFu;
constexpr float kSentinel = 12345.0f;

Mat4 torusToWorld() {
    return glm::translate(Mat4(1.0f), Vec3(-0.6f, 0.2f, 0.0f)) *
           glm::rotate(Mat4(1.0f), 1.1f, Vec3(1.0f, 0.3f, 0.0f));
}

// geomID 0: torus (R 1, r 0.3), 1: triangle mesh (a tilted quad behind), 2: sphere,
// 3: parametric cone.
struct Scene {
    ImplicitShape torus;
    TriangleMesh quad;
    ImplicitShape sphere;
    ParametricShape cone;
    std::vector<ShapeRef> refs;

    Scene()
        : torus(makeImplicitTorus(1.0, 0.3), torusToWorld(),
                [] {
                    ImplicitShapeOptions o;
                    o.cellsPerAxis = 12;
                    return o;
                }()),
          sphere(makeImplicitSphere(0.7), glm::translate(Mat4(1.0f), Vec3(1.2f, -0.3f, 0.5f)), {}),
          cone(makeParametricCone(0.45, 0.8),
               glm::rotate(glm::translate(Mat4(1.0f), Vec3(0.4f, 0.7f, 0.4f)), 0.8f, Vec3(1, 0, 0)),
               {}) {
        quad = test::warpedBackdrop();
        refs = {ShapeRef{nullptr, &torus}, ShapeRef{&quad, nullptr}, ShapeRef{nullptr, &sphere},
                ShapeRef{nullptr, &cone}};
    }
};

// Rays from around the scene towards points near the shapes, most of which
// hit something.
std::vector<Ray> randomRays(int count, uint64_t seed) {
    test::RayFan fan;
    fan.stream = 7;
    fan.zLift = 1.0f;  // in front of the backdrop
    fan.targetMin = Vec3(-1.8f, -1.3f, -1.0f);
    fan.targetMax = Vec3(2.0f, 1.3f, 1.2f);
    fan.scaleDirection = true;
    return test::raysFromShell(count, seed, fan);
}

template <int N>
void fillWithSentinels(RayHitPacket<N>& p, int lane) {
    p.org_x[lane] = p.org_y[lane] = p.org_z[lane] = kSentinel;
    p.dir_x[lane] = p.dir_y[lane] = p.dir_z[lane] = kSentinel;
    p.tnear[lane] = p.tfar[lane] = p.time[lane] = kSentinel;
    p.Ng_x[lane] = p.Ng_y[lane] = p.Ng_z[lane] = kSentinel;
    p.u[lane] = p.v[lane] = kSentinel;
    p.mask[lane] = p.id[lane] = p.flags[lane] = kSentinelId;
    p.primID[lane] = p.geomID[lane] = p.instID[lane] = kSentinelId;
}

template <int N>
bool laneUnchanged(const RayHitPacket<N>& a, const RayHitPacket<N>& b, int lane) {
    const float* fa[] = {a.org_x, a.org_y, a.org_z, a.tnear, a.dir_x, a.dir_y, a.dir_z,
                         a.time,  a.tfar,  a.Ng_x,  a.Ng_y,  a.Ng_z,  a.u,     a.v};
    const float* fb[] = {b.org_x, b.org_y, b.org_z, b.tnear, b.dir_x, b.dir_y, b.dir_z,
                         b.time,  b.tfar,  b.Ng_x,  b.Ng_y,  b.Ng_z,  b.u,     b.v};
    for (size_t k = 0; k < std::size(fa); ++k)
        if (std::memcmp(&fa[k][lane], &fb[k][lane], sizeof(float)) != 0) return false;
    const uint32_t* ua[] = {a.mask, a.id, a.flags, a.primID, a.geomID, a.instID};
    const uint32_t* ub[] = {b.mask, b.id, b.flags, b.primID, b.geomID, b.instID};
    for (size_t k = 0; k < std::size(ua); ++k)
        if (ua[k][lane] != ub[k][lane]) return false;
    return true;
}

bool sameDirection(const Vec3& a, const Vec3& b) {
    const float la = glm::length(a), lb = glm::length(b);
    return la > 0.0f && lb > 0.0f && glm::dot(a, b) >= (1.0f - 1e-6f) * la * lb;
}

template <int N>
void expectPacketsMatchSingleRays(uint64_t seed) {
    const Scene scene;
    const auto accel = buildEmbreeAccel(std::span<const ShapeRef>(scene.refs), {});
    const std::vector<Ray> rays = randomRays(N * 150, seed);
    Pcg32 maskRng(seed, 3);
    int implicitHits = 0, meshHits = 0, misses = 0, inactive = 0;
    int hitsPerGeom[4] = {0, 0, 0, 0};
    for (size_t base = 0; base + N <= rays.size(); base += N) {
        RayHitPacket<N> packet;
        alignas(64) int valid[N];
        for (int lane = 0; lane < N; ++lane) {
            valid[lane] = maskRng.nextFloat() < 0.3f ? 0 : -1;
            if (valid[lane]) {
                packet.setRay(lane, rays[base + size_t(lane)]);
                // Hit fields other than geomID start as sentinels: a hit must
                // overwrite them, a miss must leave them.
                packet.primID[lane] = packet.instID[lane] = kSentinelId;
                packet.u[lane] = packet.v[lane] = kSentinel;
                packet.Ng_x[lane] = packet.Ng_y[lane] = packet.Ng_z[lane] = kSentinel;
            } else {
                fillWithSentinels(packet, lane);
            }
        }
        const RayHitPacket<N> before = packet;
        accel->intersectPacket(valid, packet, RayCoherence::Incoherent);

        for (int lane = 0; lane < N; ++lane) {
            if (!valid[lane]) {
                ++inactive;
                EXPECT_TRUE(laneUnchanged(before, packet, lane)) << "inactive lane " << lane;
                continue;
            }
            const Ray& ray = rays[base + size_t(lane)];
            const Hit single = accel->intersect(ray);
            const Hit fromPacket = packet.hit(lane);
            ASSERT_EQ(single.valid(), fromPacket.valid()) << "lane " << lane;
            EXPECT_EQ(accel->occluded(ray), single.valid());
            if (!single.valid()) {
                ++misses;
                EXPECT_EQ(packet.tfar[lane], ray.tfar) << "a miss leaves tfar";
                EXPECT_EQ(packet.primID[lane], kSentinelId) << "a miss writes nothing";
                EXPECT_EQ(packet.instID[lane], kSentinelId) << "a miss writes nothing";
                continue;
            }
            ++hitsPerGeom[single.geomID];
            EXPECT_EQ(packet.instID[lane], kInvalidId) << "no instancing";
            EXPECT_EQ(single.geomID, fromPacket.geomID);
            EXPECT_GT(fromPacket.t, ray.tnear);
            EXPECT_LT(fromPacket.t, ray.tfar);
            if (scene.refs[single.geomID].user) {
                // Same UserShape::intersect, same answer, bit for bit.
                ++implicitHits;
                EXPECT_EQ(single.t, fromPacket.t);
                EXPECT_EQ(single.primID, fromPacket.primID);
                EXPECT_EQ(single.Ng, fromPacket.Ng);
                EXPECT_EQ(single.u, fromPacket.u);
                EXPECT_TRUE(sameDirection(single.Ng, fromPacket.Ng));
            } else {
                // Embree's packet and single-ray triangle kernels may round
                // differently in the last bit.
                ++meshHits;
                EXPECT_FLOAT_EQ(single.t, fromPacket.t);
                EXPECT_EQ(single.primID, fromPacket.primID);
                EXPECT_TRUE(sameDirection(single.Ng, fromPacket.Ng));
            }
        }
    }
    // The test exercised every kind of lane.
    EXPECT_GT(hitsPerGeom[0], 100);  // torus
    EXPECT_GT(hitsPerGeom[1], 50);   // quad
    EXPECT_GT(hitsPerGeom[2], 50);   // sphere
    EXPECT_GT(hitsPerGeom[3], 30);   // cone
    EXPECT_GT(misses, 5);
    EXPECT_GT(inactive, 100);
    EXPECT_GT(implicitHits, meshHits / 4);
}

TEST(UserGeometryPackets, Intersect8MatchesSingleRays) { expectPacketsMatchSingleRays<8>(17); }
TEST(UserGeometryPackets, Intersect16MatchesSingleRays) { expectPacketsMatchSingleRays<16>(29); }

TEST(UserGeometryPackets, AllLanesInactiveTouchesNothing) {
    const Scene scene;
    const auto accel = buildEmbreeAccel(std::span<const ShapeRef>(scene.refs), {});
    RayHitPacket16 packet;
    alignas(64) int valid[16] = {};
    for (int lane = 0; lane < 16; ++lane) fillWithSentinels(packet, lane);
    const RayHitPacket16 before = packet;
    accel->intersect16(valid, packet, RayCoherence::Coherent);
    for (int lane = 0; lane < 16; ++lane) EXPECT_TRUE(laneUnchanged(before, packet, lane)) << lane;
}

TEST(UserGeometryPackets, HitsOnlyInsideTheOpenInterval) {
    const Scene scene;
    const auto accel = buildEmbreeAccel(std::span<const ShapeRef>(scene.refs), {});
    int implicitChecked = 0, behind = 0;
    for (Ray ray : randomRays(1500, 41)) {
        const Hit hit = accel->intersect(ray);
        if (!hit.valid() || !scene.refs[hit.geomID].user) continue;
        ++implicitChecked;

        // tfar short of the hit: a miss (nothing is nearer than the nearest hit).
        Ray shorter = ray;
        shorter.tfar = hit.t * (1.0f - 1e-4f);
        EXPECT_FALSE(accel->intersect(shorter).valid());
        EXPECT_FALSE(accel->occluded(shorter));
        // tfar just past it: the same hit, and occluded.
        Ray longer = ray;
        longer.tfar = hit.t * (1.0f + 1e-4f);
        const Hit again = accel->intersect(longer);
        ASSERT_TRUE(again.valid());
        EXPECT_EQ(again.geomID, hit.geomID);
        EXPECT_EQ(again.t, hit.t);
        EXPECT_TRUE(accel->occluded(longer));

        // tnear past the hit: the next hit is strictly farther, or none.
        Ray past = ray;
        past.tnear = hit.t * (1.0f + 1e-4f);
        const Hit next = accel->intersect(past);
        if (next.valid()) {
            ++behind;
            EXPECT_GT(next.t, past.tnear);
        }
        EXPECT_EQ(accel->occluded(past), next.valid());

        // The same in a packet: lane 0 short, lane 1 past, the rest inactive.
        RayHitPacket8 packet;
        alignas(32) int valid[8] = {-1, -1, 0, 0, 0, 0, 0, 0};
        packet.setRay(0, shorter);
        packet.setRay(1, past);
        for (int lane = 2; lane < 8; ++lane) fillWithSentinels(packet, lane);
        accel->intersect8(valid, packet, RayCoherence::Incoherent);
        EXPECT_EQ(packet.geomID[0], kInvalidId);
        EXPECT_EQ(packet.tfar[0], shorter.tfar);
        EXPECT_EQ(packet.hit(1).valid(), next.valid());
        if (next.valid()) {
            EXPECT_EQ(packet.hit(1).geomID, next.geomID);
            if (scene.refs[next.geomID].user) {
                EXPECT_EQ(packet.hit(1).t, next.t);
            }
        }
    }
    EXPECT_GT(implicitChecked, 400);
    EXPECT_GT(behind, 200);  // rays through the torus or sphere find a far side
}

TEST(UserGeometryPackets, KnownHitsOnTheSphereAndTorus) {
    const Scene scene;
    const auto accel = buildEmbreeAccel(std::span<const ShapeRef>(scene.refs), {});
    // Straight down the z axis through the sphere's centre (1.2, -0.3, 0.5), r 0.7.
    Ray ray;
    ray.origin = Vec3(1.2f, -0.3f, 5.0f);
    ray.dir = Vec3(0.0f, 0.0f, -2.0f);  // t in units of |dir| = 2
    Hit hit = accel->intersect(ray);
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.geomID, 2u);
    EXPECT_EQ(hit.primID, 0u);  // closed form: one cell
    EXPECT_NEAR(hit.t, (5.0f - 1.2f) / 2.0f, 1e-5f);
    EXPECT_TRUE(sameDirection(hit.Ng, Vec3(0, 0, 1)));
    // Through the sphere from inside: the far side, normal still outwards.
    ray.origin = Vec3(1.2f, -0.3f, 0.5f);
    hit = accel->intersect(ray);
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.geomID, 2u);
    EXPECT_NEAR(hit.t, 0.35f, 1e-5f);
    EXPECT_TRUE(sameDirection(hit.Ng, Vec3(0, 0, -1)));

    // The torus is cut into cells; its hits report the cell as primID.
    EXPECT_GT(scene.torus.primitiveCount(), 50u);
    int torusHits = 0;
    std::vector<bool> seen(scene.torus.primitiveCount(), false);
    const glm::dmat4 toObject = glm::inverse(glm::dmat4(torusToWorld()));
    for (const Ray& r : randomRays(2000, 5)) {
        const Hit h = accel->intersect(r);
        if (!h.valid() || h.geomID != 0) continue;
        ++torusHits;
        ASSERT_LT(h.primID, scene.torus.primitiveCount());
        seen[h.primID] = true;
        // The hit lies in its cell's box (up to the float rounding of o + t·d)...
        const Vec3 p = r.at(h.t);
        const Bounds3 cell = scene.torus.primitiveBounds(h.primID);
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_GE(p[axis], cell.min[axis] - 1e-4f);
            EXPECT_LE(p[axis], cell.max[axis] + 1e-4f);
        }
        // ... and on the torus: its distance from the tube's centre circle is r.
        const glm::dvec3 q = glm::dvec3(toObject * glm::dvec4(glm::dvec3(p), 1.0));
        const double rho = std::sqrt(q.x * q.x + q.y * q.y);
        EXPECT_NEAR(std::sqrt((rho - 1.0) * (rho - 1.0) + q.z * q.z), 0.3, 1e-4);
    }
    EXPECT_GT(torusHits, 300);
    EXPECT_GT(std::count(seen.begin(), seen.end(), true), 30) << "many cells are hit";
}

}  // namespace
}  // namespace strahl
