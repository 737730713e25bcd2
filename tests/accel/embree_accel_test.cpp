// The Embree accelerator: known hits, occlusion, and agreement between the
// single-ray and the 8- and 16-wide packet queries.

#include "strahl/accel/accel.h"

#include <gtest/gtest.h>

#include "strahl/core/rng.h"
#include "test_scene_pieces.h"

namespace strahl {
namespace {

TriangleMesh randomSoup(int triangles, uint64_t seed) {
    Pcg32 rng(seed, 1);
    TriangleMesh m;
    for (int t = 0; t < triangles; ++t) {
        const Vec3 c(rng.nextFloat() * 4 - 2, rng.nextFloat() * 4 - 2, rng.nextFloat() * 4 - 2);
        for (int k = 0; k < 3; ++k) {
            m.positions.push_back(c + 0.3f * Vec3(rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f,
                                                  rng.nextFloat() - 0.5f));
            m.indices.push_back(static_cast<uint32_t>(m.positions.size() - 1));
        }
    }
    m.reservePadding();
    return m;
}

TEST(EmbreeAccel, FindsTheNearestOfTwoQuadsWithStableIds) {
    const TriangleMesh front = test::unitQuad(0.0f), back = test::unitQuad(-1.0f);
    const TriangleMesh* meshes[] = {&back, &front};
    const auto accel = buildEmbreeAccel(meshes, {});
    Ray ray;
    ray.origin = Vec3(0.25f, 0.5f, 5.0f);
    ray.dir = Vec3(0, 0, -1);
    const Hit hit = accel->intersect(ray);
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.geomID, 1u);  // position in the span, not insertion luck
    EXPECT_EQ(hit.primID, 1u);  // the upper-left triangle (0, 2, 3)
    EXPECT_FLOAT_EQ(hit.t, 5.0f);
    EXPECT_GT(hit.Ng.z, 0.0f);

    ray.tfar = 4.5f;  // stops before the front quad
    EXPECT_FALSE(accel->intersect(ray).valid());
    EXPECT_FALSE(accel->occluded(ray));
    ray.tfar = 5.5f;
    EXPECT_TRUE(accel->occluded(ray));

    EXPECT_EQ(accel->bounds().min.z, -1.0f);
    EXPECT_GT(accel->memoryBytes(), 0u);
}

TEST(EmbreeAccel, UnpaddedMeshesAreCopiedNotRejected) {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.positions.shrink_to_fit();
    m.indices = {0, 1, 2};
    ASSERT_FALSE(m.isPadded());
    const TriangleMesh* meshes[] = {&m};
    const auto accel = buildEmbreeAccel(meshes, {});
    Ray ray;
    ray.origin = Vec3(0.2f, 0.2f, 1.0f);
    ray.dir = Vec3(0, 0, -1);
    EXPECT_TRUE(accel->intersect(ray).valid());
}

TEST(EmbreeAccel, ReportsBuildProgress) {
    const TriangleMesh soup = randomSoup(20000, 3);
    const TriangleMesh* meshes[] = {&soup};
    std::atomic<int> calls{0};
    std::atomic<bool> inRange{true};
    AccelBuildOptions options;
    options.progress = [&](double f) {
        ++calls;
        if (f < 0.0 || f > 1.0) inRange = false;
    };
    buildEmbreeAccel(meshes, options);
    EXPECT_GT(calls.load(), 0);
    EXPECT_TRUE(inRange.load());
}

template <int N>
void expectMeshPacketsMatchSingleRays() {
    const TriangleMesh soup = randomSoup(2000, 11);
    const TriangleMesh* meshes[] = {&soup};
    const auto accel = buildEmbreeAccel(meshes, {});
    Pcg32 rng(5, 2);
    int hits = 0;
    for (int round = 0; round < 200; ++round) {
        RayHitPacket<N> packet;
        alignas(64) int valid[N];
        Ray rays[N];
        for (int lane = 0; lane < N; ++lane) {
            rays[lane].origin = Vec3(rng.nextFloat() * 6 - 3, rng.nextFloat() * 6 - 3, 6.0f);
            rays[lane].dir = glm::normalize(Vec3(rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f, -1.0f));
            packet.setRay(lane, rays[lane]);
            valid[lane] = lane % 5 == 3 ? 0 : -1;  // some inactive lanes
        }
        if constexpr (N == 16)
            accel->intersect16(valid, packet, RayCoherence::Incoherent);
        else
            accel->intersect8(valid, packet, RayCoherence::Incoherent);
        for (int lane = 0; lane < N; ++lane) {
            if (!valid[lane]) {
                EXPECT_EQ(packet.geomID[lane], kInvalidId) << "inactive lanes are untouched";
                continue;
            }
            const Hit single = accel->intersect(rays[lane]);
            const Hit fromPacket = packet.hit(lane);
            ASSERT_EQ(single.valid(), fromPacket.valid());
            if (!single.valid()) continue;
            ++hits;
            EXPECT_EQ(single.primID, fromPacket.primID);
            EXPECT_FLOAT_EQ(single.t, fromPacket.t);
            EXPECT_NEAR(single.u, fromPacket.u, 1e-6f);
            EXPECT_NEAR(single.v, fromPacket.v, 1e-6f);
        }
    }
    EXPECT_GT(hits, 100);  // the test exercised real hits
}

TEST(EmbreeAccel, Packets16MatchSingleRays) { expectMeshPacketsMatchSingleRays<16>(); }
TEST(EmbreeAccel, Packets8MatchSingleRays) { expectMeshPacketsMatchSingleRays<8>(); }

TEST(EmbreeAccel, NativeWidthIsAPacketWidth) {
    const TriangleMesh q = test::unitQuad(0.0f);
    const TriangleMesh* meshes[] = {&q};
    const int w = buildEmbreeAccel(meshes, {})->nativePacketWidth();
    EXPECT_TRUE(w == 16 || w == 8 || w == 1);
}

}  // namespace
}  // namespace strahl
