// Moving instances (core/motion.h) in the accelerators: Embree's
// multi-segment instance motion and the naive tracer's interpolation find the
// same hits at every ray time; a moving instance at time t is the instance at
// rest at keyframeAt(t); packets carry each lane's time.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/core/motion.h"
#include "strahl/core/rng.h"
#include "strahl/geometry/implicit_builtins.h"
#include "strahl/geometry/implicit_shape.h"
#include "strahl/reference/naive_accel.h"
#include "test_scene_pieces.h"

namespace strahl {
namespace {

// Prototype 0: an icosphere (triangles) with an implicit sphere beside it
// (user geometry). Instance 0 slides and spins through three keyframes,
// instance 1 grows through two, instance 2 stays at rest.
struct MovingScene {
    TriangleMesh ball = test::icosphere(2, Vec3(0.0f), 0.5f);
    ImplicitShape sphere{makeImplicitSphere(0.3), glm::translate(Mat4(1.0f), Vec3(0.9f, 0.0f, 0.0f)), {}};
    AccelScene scene;

    MovingScene() {
        const Mat4 I(1.0f);
        scene.prototypes = {{ShapeRef{&ball, nullptr}, ShapeRef{nullptr, &sphere}}};
        scene.instances.push_back(AccelInstance(0, I,
                                                {glm::translate(I, Vec3(-1.5f, 0.0f, 0.0f)),
                                                 glm::translate(I, Vec3(-0.5f, 0.4f, 0.0f)) *
                                                     glm::rotate(I, 0.6f, Vec3(0, 0, 1)),
                                                 glm::translate(I, Vec3(0.5f, 0.2f, 0.3f)) *
                                                     glm::rotate(I, 1.2f, Vec3(0, 0, 1))}));
        scene.instances.back().objectToWorld = scene.instances.back().motion[0];
        scene.instances.push_back(AccelInstance(0, I,
                                                {glm::translate(I, Vec3(0.0f, -1.4f, 0.0f)) * glm::scale(I, Vec3(0.5f)),
                                                 glm::translate(I, Vec3(0.0f, -1.4f, 0.0f)) * glm::scale(I, Vec3(1.1f))}));
        scene.instances.back().objectToWorld = scene.instances.back().motion[0];
        scene.instances.push_back(AccelInstance(0, glm::translate(I, Vec3(1.6f, 1.3f, -0.2f))));
    }

    // The same instances at rest where time `t` puts them.
    AccelScene frozenAt(float t) const {
        AccelScene frozen = scene;
        for (AccelInstance& i : frozen.instances) {
            i.objectToWorld = i.objectToWorldAt(t);
            i.motion.clear();
        }
        return frozen;
    }
};

// Rays from a shell around the scene towards it, each at a random time.
std::vector<Ray> movingSceneRays(int count, uint64_t seed) {
    Pcg32 rng(seed, 7);
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        const Vec3 target(4.0f * rng.nextFloat() - 2.0f, 3.6f * rng.nextFloat() - 1.8f, 1.4f * rng.nextFloat() - 0.7f);
        const float a = 6.2831853f * rng.nextFloat(), z = 2.0f * rng.nextFloat() - 1.0f;
        const float r = std::sqrt(1.0f - z * z);
        Ray ray;
        ray.origin = target + 8.0f * Vec3(r * std::cos(a), r * std::sin(a), z);
        ray.dir = target - ray.origin;
        ray.time = rng.nextFloat();
        rays.push_back(ray);
    }
    return rays;
}

TEST(MotionAgreement, EmbreeAndNaiveFindTheSameHitsAtEveryTime) {
    const MovingScene s;
    const auto embree = buildEmbreeAccel(s.scene, {});
    const auto naive = buildNaiveAccel(s.scene);
    int hits = 0, movingHits = 0, userHits = 0;
    for (const Ray& ray : movingSceneRays(4000, 3)) {
        const Hit a = embree->intersect(ray), b = naive->intersect(ray);
        ASSERT_EQ(a.valid(), b.valid()) << "time " << ray.time;
        EXPECT_EQ(embree->occluded(ray), a.valid());
        EXPECT_EQ(naive->occluded(ray), b.valid());
        if (!a.valid()) continue;
        ++hits;
        ASSERT_EQ(a.instID, b.instID) << "time " << ray.time << ", t " << a.t << " vs " << b.t;
        ASSERT_EQ(a.geomID, b.geomID);
        EXPECT_EQ(a.primID, b.primID);
        EXPECT_NEAR(a.t, b.t, 1e-5f * a.t);
        movingHits += a.instID != s.scene.instanceId(2);
        userHits += a.geomID == 1;
    }
    EXPECT_GT(hits, 1000);
    EXPECT_GT(movingHits, 500);
    EXPECT_GT(userHits, 100);
}

TEST(MotionAgreement, AMovingInstanceAtTimeTIsTheInstanceAtRestThere) {
    const MovingScene s;
    const auto moving = buildEmbreeAccel(s.scene, {});
    for (float t : {0.0f, 0.3f, 0.5f, 0.85f, 1.0f}) {
        SCOPED_TRACE(testing::Message() << "time " << t);
        const auto frozen = buildEmbreeAccel(s.frozenAt(t), {});
        int hits = 0;
        for (Ray ray : movingSceneRays(800, 5)) {
            ray.time = t;
            const Hit a = moving->intersect(ray);
            Ray still = ray;
            still.time = 0.0f;
            const Hit b = frozen->intersect(still);
            ASSERT_EQ(a.valid(), b.valid());
            if (!a.valid()) continue;
            ++hits;
            EXPECT_EQ(a.instID, b.instID);
            EXPECT_EQ(a.geomID, b.geomID);
            EXPECT_EQ(a.primID, b.primID);
            EXPECT_NEAR(a.t, b.t, 1e-5f * a.t);
        }
        EXPECT_GT(hits, 120);
    }
}

TEST(MotionAgreement, PacketLanesCarryTheirOwnTimes) {
    const MovingScene s;
    const auto embree = buildEmbreeAccel(s.scene, {});
    const std::vector<Ray> rays = movingSceneRays(16 * 40, 11);
    for (size_t first = 0; first < rays.size(); first += 16) {
        RayHitPacket16 packet;
        alignas(64) int valid[16];
        for (int lane = 0; lane < 16; ++lane) {
            packet.setRay(lane, rays[first + size_t(lane)]);
            valid[lane] = -1;
        }
        embree->intersect16(valid, packet, RayCoherence::Incoherent);
        for (int lane = 0; lane < 16; ++lane) {
            EXPECT_EQ(packet.ray(lane).time, rays[first + size_t(lane)].time);
            const Hit single = embree->intersect(rays[first + size_t(lane)]);
            const Hit packed = packet.hit(lane);
            ASSERT_EQ(packed.valid(), single.valid());
            if (!single.valid()) continue;
            EXPECT_EQ(packed.instID, single.instID);
            EXPECT_EQ(packed.primID, single.primID);
            EXPECT_NEAR(packed.t, single.t, 1e-6f * single.t);
        }
    }
}

TEST(MotionAgreement, BoundsHoldTheWholeMotion) {
    const MovingScene s;
    const auto embree = buildEmbreeAccel(s.scene, {});
    const auto naive = buildNaiveAccel(s.scene);
    Bounds3 swept;
    for (int k = 0; k <= 64; ++k) {
        const AccelScene frozen = s.frozenAt(float(k) / 64.0f);
        swept.expand(buildNaiveAccel(frozen)->bounds());
    }
    for (const Accel* accel : {embree.get(), naive.get()}) {
        const Bounds3 b = accel->bounds();
        EXPECT_LE(b.min.x, swept.min.x + 1e-5f);
        EXPECT_LE(b.min.y, swept.min.y + 1e-5f);
        EXPECT_GE(b.max.x, swept.max.x - 1e-5f);
        EXPECT_GE(b.max.z, swept.max.z - 1e-5f);
    }
}

}  // namespace
}  // namespace strahl
