// Deforming meshes (TriangleMesh::laterPositions, docs/geometry.md "Motion
// blur"): Embree's vertex time steps and the naive tracer's interpolation
// (core/motion.h) find the same hits at every ray time, top level and inside
// a moving instance; a deforming mesh at time t is the mesh at rest at its
// interpolated positions; packets carry each lane's time; the interaction
// is taken where the ray's time puts the triangle.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/core/motion.h"
#include "strahl/core/rng.h"
#include "strahl/reference/naive_accel.h"
#include "test_scene_pieces.h"

namespace strahl {
namespace {

// An icosphere that squashes, bulges and slides through three keyframes.
TriangleMesh breathingBall() {
    TriangleMesh ball = test::icosphere(2, Vec3(0.0f), 0.6f);
    for (int k = 1; k <= 2; ++k) {
        std::vector<Vec3>& key = ball.laterPositions.emplace_back();
        for (const Vec3& p : ball.positions)
            key.push_back(k == 1 ? Vec3(1.3f * p.x + 0.4f, 0.8f * p.y, 0.6f * p.z)
                                 : Vec3(0.9f * p.x - 0.3f + 0.2f * p.z * p.z, p.y + 0.5f, 1.2f * p.z));
    }
    ball.computeVertexNormals();
    ball.reservePadding();
    return ball;
}

// The mesh at rest where time `t` puts it.
TriangleMesh frozenAt(const TriangleMesh& mesh, float t) {
    TriangleMesh still = mesh;
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) still.positions[v] = mesh.positionAt(v, t);
    still.laterPositions.clear();
    still.laterNormals.clear();
    still.normals.clear();
    still.reservePadding();
    return still;
}

std::vector<Ray> deformingMeshRays(int count, uint64_t seed) {
    Pcg32 rng(seed, 9);
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        const Vec3 target(2.0f * rng.nextFloat() - 1.0f, 2.0f * rng.nextFloat() - 0.8f, 1.4f * rng.nextFloat() - 0.7f);
        const float a = 6.2831853f * rng.nextFloat(), z = 2.0f * rng.nextFloat() - 1.0f;
        const float r = std::sqrt(1.0f - z * z);
        Ray ray;
        ray.origin = target + 6.0f * Vec3(r * std::cos(a), r * std::sin(a), z);
        ray.dir = target - ray.origin;
        ray.time = rng.nextFloat();
        rays.push_back(ray);
    }
    return rays;
}

void expectAgreement(const AccelScene& scene, int minHits) {
    const auto embree = buildEmbreeAccel(scene, {});
    const auto naive = buildNaiveAccel(scene);
    int hits = 0;
    for (const Ray& ray : deformingMeshRays(3000, 3)) {
        const Hit a = embree->intersect(ray), b = naive->intersect(ray);
        ASSERT_EQ(a.valid(), b.valid()) << "time " << ray.time;
        EXPECT_EQ(embree->occluded(ray), a.valid());
        EXPECT_EQ(naive->occluded(ray), b.valid());
        if (!a.valid()) continue;
        ++hits;
        EXPECT_EQ(a.primID, b.primID) << "time " << ray.time;
        EXPECT_NEAR(a.t, b.t, 1e-5f * a.t);
        // Barycentrics of the interpolated triangle: float rounding of the
        // interpolation (Embree's and core/motion.h's) reaches 1e-4.
        EXPECT_NEAR(a.u, b.u, 5e-4f);
        EXPECT_NEAR(a.v, b.v, 5e-4f);
    }
    EXPECT_GT(hits, minHits);
}

TEST(DeformingMeshAgreement, EmbreeAndNaiveFindTheSameHitsAtEveryTime) {
    const TriangleMesh ball = breathingBall();
    expectAgreement(AccelScene{{ShapeRef{&ball, nullptr}}, {}, {}}, 800);
}

TEST(DeformingMeshAgreement, InsideAMovingInstance) {
    const TriangleMesh ball = breathingBall();
    AccelScene scene;
    scene.prototypes = {{ShapeRef{&ball, nullptr}}};
    const Mat4 I(1.0f);
    scene.instances.push_back(AccelInstance(0, I, {glm::translate(I, Vec3(-0.3f, 0, 0)),
                                                   glm::rotate(glm::translate(I, Vec3(0.3f, 0.1f, 0)), 0.5f, Vec3(0, 0, 1))}));
    expectAgreement(scene, 600);
}

TEST(DeformingMeshAgreement, ADeformingMeshAtTimeTIsTheMeshAtRestThere) {
    const TriangleMesh ball = breathingBall();
    const std::vector<ShapeRef> moving{ShapeRef{&ball, nullptr}};
    const auto deforming = buildEmbreeAccel(moving, {});
    for (float t : {0.0f, 0.25f, 0.5f, 0.8f, 1.0f}) {
        SCOPED_TRACE(testing::Message() << "time " << t);
        const TriangleMesh still = frozenAt(ball, t);
        const std::vector<ShapeRef> frozen{ShapeRef{&still, nullptr}};
        const auto rest = buildEmbreeAccel(frozen, {});
        int hits = 0;
        for (Ray ray : deformingMeshRays(600, 5)) {
            ray.time = t;
            const Hit a = deforming->intersect(ray);
            Ray at = ray;
            at.time = 0.0f;
            const Hit b = rest->intersect(at);
            ASSERT_EQ(a.valid(), b.valid());
            if (!a.valid()) continue;
            ++hits;
            EXPECT_EQ(a.primID, b.primID);
            EXPECT_NEAR(a.t, b.t, 1e-5f * a.t);
            // The interaction is the still triangle's, normals interpolated.
            const SurfaceInteraction si = triangleInteraction(ball, a.primID, a.u, a.v, t);
            const SurfaceInteraction sj = triangleInteraction(still, b.primID, b.u, b.v);
            EXPECT_NEAR(glm::length(si.p - sj.p), 0.0f, 1e-5f);
            EXPECT_NEAR(glm::dot(si.Ng, sj.Ng), 1.0f, 1e-4f);
            EXPECT_NEAR(glm::length(si.Ns), 1.0f, 1e-5f);
        }
        EXPECT_GT(hits, 100);
    }
}

TEST(DeformingMeshAgreement, PacketLanesCarryTheirOwnTimes) {
    const TriangleMesh ball = breathingBall();
    const std::vector<ShapeRef> shapes{ShapeRef{&ball, nullptr}};
    const auto embree = buildEmbreeAccel(shapes, {});
    const std::vector<Ray> rays = deformingMeshRays(16 * 30, 11);
    for (size_t first = 0; first < rays.size(); first += 8) {
        RayHitPacket8 packet;
        alignas(32) int valid[8];
        for (int lane = 0; lane < 8; ++lane) {
            packet.setRay(lane, rays[first + size_t(lane)]);
            valid[lane] = -1;
        }
        embree->intersect8(valid, packet, RayCoherence::Incoherent);
        for (int lane = 0; lane < 8; ++lane) {
            const Hit single = embree->intersect(rays[first + size_t(lane)]);
            const Hit packed = packet.hit(lane);
            ASSERT_EQ(packed.valid(), single.valid());
            if (single.valid()) {
                EXPECT_NEAR(packed.t, single.t, 1e-6f * single.t);
            }
        }
    }
}

TEST(DeformingMeshAgreement, BoundsHoldEveryKeyframe) {
    const TriangleMesh ball = breathingBall();
    const std::vector<ShapeRef> shapes{ShapeRef{&ball, nullptr}};
    Bounds3 swept;
    for (int k = 0; k <= 32; ++k) swept.expand(frozenAt(ball, float(k) / 32.0f).bounds());
    for (const auto& accel : {buildEmbreeAccel(shapes, {}), buildNaiveAccel(shapes)}) {
        const Bounds3 b = accel->bounds();
        EXPECT_LE(b.min.x, swept.min.x);
        EXPECT_LE(b.min.z, swept.min.z);
        EXPECT_GE(b.max.x, swept.max.x);
        EXPECT_GE(b.max.y, swept.max.y);
    }
}

}  // namespace
}  // namespace strahl
