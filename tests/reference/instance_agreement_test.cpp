// Instancing, checked three ways over one scene: two prototypes (an icosphere
// with an implicit sphere beside it, and a warped quad) placed by instances
// with rotations, non-uniform and mirroring scales, plus a top-level quad.
//  - Embree against the naive tracer on the instanced scene: the same hit
//    (instID, geomID, primID) and t.
//  - The instanced scene against the same geometry "baked": every instance's
//    shapes copied and transformed to world space as top-level shapes. Same
//    hits, t equal to float rounding of the two transforms, and the object-space
//    Ng of an instance hit, mapped by the normal matrix, parallel to the baked
//    world-space Ng.
//  - Packets against single rays, instID included.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/core/error.h"
#include "strahl/core/transform.h"
#include "strahl/geometry/implicit_builtins.h"
#include "strahl/geometry/implicit_shape.h"
#include "strahl/reference/naive_accel.h"

#include "test_scene_pieces.h"

namespace strahl {
namespace {

const Mat4 kSphereOffset = glm::translate(Mat4(1.0f), Vec3(0.9f, 0.0f, 0.0f));

std::vector<Mat4> ballPlacements() {
    const Mat4 I(1.0f);
    return {
        glm::translate(I, Vec3(-1.5f, 0.8f, 0.0f)),
        glm::translate(I, Vec3(1.2f, 1.0f, 0.2f)) * glm::rotate(I, 0.7f, Vec3(0.3f, 1.0f, 0.2f)) *
            glm::scale(I, Vec3(0.6f, 0.9f, 0.5f)),
        // Mirroring: the winding flips, the normal matrix keeps normals outward.
        glm::translate(I, Vec3(-0.8f, -1.2f, 0.4f)) * glm::scale(I, Vec3(-0.7f, 0.7f, 0.7f)),
        glm::translate(I, Vec3(1.0f, -1.0f, -0.3f)) * glm::rotate(I, 2.0f, Vec3(0.0f, 0.0f, 1.0f)) *
            glm::scale(I, Vec3(0.5f)),
    };
}

const Mat4 kBackdropPlacement = glm::rotate(Mat4(1.0f), 0.1f, Vec3(1.0f, 0.0f, 0.0f)) *
                                glm::scale(Mat4(1.0f), Vec3(1.2f, 1.2f, 1.0f));

struct Scenes {
    // Prototype 0: icosphere + implicit sphere; prototype 1: the backdrop.
    TriangleMesh ball = test::icosphere(2, Vec3(0.0f), 0.5f);
    ImplicitShape sphere{makeImplicitSphere(0.3), kSphereOffset, {}};
    TriangleMesh backdrop = test::warpedBackdrop();
    TriangleMesh topQuad;
    AccelScene instanced;

    // The baked scene: top quad, then per instance its shapes in world space.
    std::vector<std::unique_ptr<TriangleMesh>> bakedMeshes;
    std::vector<std::unique_ptr<ImplicitShape>> bakedSpheres;
    AccelScene baked;
    // baked geomID -> (instID, geomID within the prototype) of the instanced scene
    std::vector<std::pair<uint32_t, uint32_t>> origin;

    Scenes() {
        topQuad = test::unitQuad(0.0f);
        topQuad.transform(glm::translate(Mat4(1.0f), Vec3(0.0f, 0.0f, 1.2f)) *
                          glm::scale(Mat4(1.0f), Vec3(0.3f)));
        instanced.shapes = {ShapeRef{&topQuad, nullptr}};
        instanced.prototypes = {{ShapeRef{&ball, nullptr}, ShapeRef{nullptr, &sphere}},
                                {ShapeRef{&backdrop, nullptr}}};
        for (const Mat4& m : ballPlacements()) instanced.instances.push_back({0, m});
        instanced.instances.push_back({1, kBackdropPlacement});

        baked.shapes = {ShapeRef{&topQuad, nullptr}};
        origin = {{kInvalidId, 0}};
        for (size_t k = 0; k < instanced.instances.size(); ++k) {
            const AccelInstance& inst = instanced.instances[k];
            const uint32_t instID = instanced.instanceId(k);
            if (inst.prototype == 0) {
                bakedMeshes.push_back(std::make_unique<TriangleMesh>(ball));
                bakedMeshes.back()->transform(inst.objectToWorld);
                bakedMeshes.back()->reservePadding();
                baked.shapes.push_back({bakedMeshes.back().get(), nullptr});
                origin.push_back({instID, 0});
                bakedSpheres.push_back(std::make_unique<ImplicitShape>(
                    makeImplicitSphere(0.3), inst.objectToWorld * kSphereOffset,
                    ImplicitShapeOptions{}));
                baked.shapes.push_back({nullptr, bakedSpheres.back().get()});
                origin.push_back({instID, 1});
            } else {
                bakedMeshes.push_back(std::make_unique<TriangleMesh>(backdrop));
                bakedMeshes.back()->transform(inst.objectToWorld);
                bakedMeshes.back()->reservePadding();
                baked.shapes.push_back({bakedMeshes.back().get(), nullptr});
                origin.push_back({instID, 0});
            }
        }
    }

    const Mat4* toWorld(uint32_t instID) const {
        if (instID == kInvalidId) return nullptr;
        return &instanced.instances[instID - instanced.shapes.size()].objectToWorld;
    }
};

std::vector<Ray> instanceRays(int count, uint64_t seed) {
    test::RayFan fan;
    fan.stream = 23;
    fan.zLift = 0.5f;
    fan.targetMin = Vec3(-2.5f, -2.2f, -1.0f);
    fan.targetMax = Vec3(2.5f, 2.2f, 1.0f);
    fan.scaleDirection = true;
    return test::raysFromShell(count, seed, fan);
}

TEST(InstanceAgreement, EmbreeAndNaiveFindTheSameHitsThroughInstances) {
    const Scenes s;
    const auto embree = buildEmbreeAccel(s.instanced, {});
    const auto naive = buildNaiveAccel(s.instanced);
    int instanceHits = 0, sphereHits = 0, topHits = 0, misses = 0;
    for (const Ray& ray : instanceRays(4000, 3)) {
        const Hit a = embree->intersect(ray), b = naive->intersect(ray);
        ASSERT_EQ(a.valid(), b.valid());
        EXPECT_EQ(embree->occluded(ray), a.valid());
        EXPECT_EQ(naive->occluded(ray), b.valid());
        if (!a.valid()) {
            ++misses;
            continue;
        }
        ASSERT_EQ(a.instID, b.instID) << "t " << a.t << " vs " << b.t;
        ASSERT_EQ(a.geomID, b.geomID);
        EXPECT_EQ(a.primID, b.primID);
        EXPECT_NEAR(a.t, b.t, 1e-5f * a.t);
        EXPECT_GT(glm::dot(a.Ng, b.Ng), 0.0f);
        if (a.instID == kInvalidId) {
            ++topHits;
        } else {
            ++instanceHits;
            sphereHits += a.instID < s.instanced.instanceId(4) && a.geomID == 1;
        }
    }
    EXPECT_GT(instanceHits, 1500);
    EXPECT_GT(sphereHits, 100);
    EXPECT_GT(topHits, 5);
    EXPECT_GT(misses, 50);
}

TEST(InstanceAgreement, InstancedSceneMatchesTheBakedScene) {
    const Scenes s;
    for (bool useNaive : {false, true}) {
        SCOPED_TRACE(useNaive ? "naive" : "embree");
        const auto instanced = useNaive ? buildNaiveAccel(s.instanced)
                                        : buildEmbreeAccel(s.instanced, {});
        const auto baked = useNaive ? buildNaiveAccel(s.baked) : buildEmbreeAccel(s.baked, {});
        int compared = 0, differ = 0;
        for (const Ray& ray : instanceRays(3000, 5)) {
            const Hit a = instanced->intersect(ray), b = baked->intersect(ray);
            if (a.valid() != b.valid()) {
                // A ray grazing a silhouette may go either way after the two
                // differently rounded transforms.
                ++differ;
                continue;
            }
            if (!a.valid()) continue;
            ++compared;
            ASSERT_LT(b.geomID, s.origin.size());
            const auto [instID, geomID] = s.origin[b.geomID];
            if (a.instID != instID || a.geomID != geomID || a.primID != b.primID) {
                ++differ;
                continue;
            }
            EXPECT_NEAR(a.t, b.t, 1e-4f * a.t);
            // The instance reports Ng in object space.
            Vec3 ng = a.Ng;
            if (const Mat4* m = s.toWorld(a.instID)) ng = normalMatrix(*m) * ng;
            EXPECT_GT(glm::dot(glm::normalize(ng), glm::normalize(b.Ng)), 0.9999f)
                << "instID " << a.instID << " geomID " << a.geomID;
        }
        EXPECT_GT(compared, 1500);
        EXPECT_LE(differ, 3) << "of " << compared;
    }
}

TEST(InstanceAgreement, PacketsReportTheInstance) {
    const Scenes s;
    const auto embree = buildEmbreeAccel(s.instanced, {});
    const std::vector<Ray> rays = instanceRays(8 * 60, 9);
    int instanceLanes = 0;
    for (size_t base = 0; base + 8 <= rays.size(); base += 8) {
        RayHitPacket8 packet;
        alignas(32) int valid[8];
        for (int lane = 0; lane < 8; ++lane) {
            valid[lane] = lane == 3 ? 0 : -1;
            packet.setRay(lane, rays[base + size_t(lane)]);
        }
        embree->intersect8(valid, packet, RayCoherence::Incoherent);
        for (int lane = 0; lane < 8; ++lane) {
            if (!valid[lane]) continue;
            const Hit single = embree->intersect(rays[base + size_t(lane)]);
            const Hit h = packet.hit(lane);
            ASSERT_EQ(h.valid(), single.valid());
            if (!h.valid()) continue;
            EXPECT_EQ(h.instID, single.instID);
            EXPECT_EQ(h.geomID, single.geomID);
            EXPECT_EQ(h.primID, single.primID);
            EXPECT_EQ(h.t, single.t);
            instanceLanes += h.instID != kInvalidId;
        }
    }
    EXPECT_GT(instanceLanes, 200);
}

TEST(InstanceAgreement, BoundsCoverEveryInstance) {
    const Scenes s;
    const auto embree = buildEmbreeAccel(s.instanced, {});
    const auto naive = buildNaiveAccel(s.instanced);
    const auto baked = buildEmbreeAccel(s.baked, {});
    for (const Accel* accel : {embree.get(), naive.get()}) {
        const Bounds3 b = accel->bounds(), expected = baked->bounds();
        for (int axis = 0; axis < 3; ++axis) {
            // Transformed prototype boxes are conservative, never smaller.
            EXPECT_LE(b.min[axis], expected.min[axis] + 1e-5f);
            EXPECT_GE(b.max[axis], expected.max[axis] - 1e-5f);
        }
    }
}

TEST(InstanceAgreement, APrototypeIndexOutOfRangeIsAnError) {
    const Scenes s;
    AccelScene broken = s.instanced;
    broken.instances.push_back({7, Mat4(1.0f)});
    EXPECT_THROW(buildEmbreeAccel(broken, {}), Error);
    EXPECT_THROW(buildNaiveAccel(broken), Error);
}

}  // namespace
}  // namespace strahl
