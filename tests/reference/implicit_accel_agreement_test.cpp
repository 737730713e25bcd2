// Embree's BVH and the naive tracer over the same ShapeRefs with implicit
// shapes (torus, sphere, blobs, a gyroid sheet in a box, a formula) and a
// triangle mesh. Both ask the very same ImplicitShape::intersect, so on the
// implicit shapes they must agree exactly: t bit for bit, same geomID, same
// primID — except where a root lies on a face shared by two cells (cells
// overlap by the tolerance), where either cell may report it; then t must
// still be equal. (This lives in tests/reference because test_accel does not
// link the naive tracer.)

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/core/rng.h"
#include "strahl/geometry/implicit_builtins.h"
#include "strahl/geometry/implicit_formula.h"
#include "strahl/geometry/implicit_shape.h"
#include "strahl/reference/naive_accel.h"

#include "test_scene_pieces.h"

namespace strahl {
namespace {

ImplicitShapeOptions withCells(int cells, std::optional<Bounds3> box = std::nullopt) {
    ImplicitShapeOptions o;
    o.cellsPerAxis = cells;
    o.box = box;
    return o;
}

struct ImplicitShapesScene {
    ImplicitShape torus{makeImplicitTorus(1.0, 0.3),
                        glm::translate(Mat4(1.0f), Vec3(-1.2f, 0.3f, 0.0f)) *
                            glm::rotate(Mat4(1.0f), 0.9f, Vec3(1.0f, 0.2f, 0.1f)),
                        withCells(12)};
    TriangleMesh quad;
    ImplicitShape sphere{makeImplicitSphere(0.6), glm::translate(Mat4(1.0f), Vec3(1.4f, 1.0f, 0.3f)), {}};
    ImplicitShape blobs{makeBlobs({Blob{DVec3(0.0), 0.8, 1.0}, Blob{DVec3(0.5, 0.3, 0.0), 0.6, 1.0},
                                   Blob{DVec3(-0.2, 0.5, 0.3), 0.5, 0.8}},
                                  0.3),
                        glm::translate(Mat4(1.0f), Vec3(1.3f, -1.0f, 0.0f)), withCells(10)};
    // A gyroid sheet: many cells, many roots on shared cell faces.
    ImplicitShape gyroid{makePeriodicSurface(PeriodicSurface::Gyroid, 0.8, 0.0, 0.15),
                         glm::translate(Mat4(1.0f), Vec3(0.0f, 0.0f, -0.5f)),
                         withCells(16, Bounds3{Vec3(-0.7f), Vec3(0.7f)})};
    ImplicitShape formula{makeFormulaSurface("x^4 + y^4 + z^4 - r^4", {{"r", 0.45}}),
                          glm::translate(Mat4(1.0f), Vec3(-0.3f, 1.3f, 0.6f)),
                          withCells(8, Bounds3{Vec3(-1.0f), Vec3(1.0f)})};
    std::vector<ShapeRef> refs;

    ImplicitShapesScene() {
        quad = test::warpedBackdrop();
        refs = {ShapeRef{nullptr, &torus},  ShapeRef{&quad, nullptr},   ShapeRef{nullptr, &sphere},
                ShapeRef{nullptr, &blobs},  ShapeRef{nullptr, &gyroid}, ShapeRef{nullptr, &formula}};
    }
};

std::vector<Ray> implicitShapeRays(int count, uint64_t seed) {
    test::RayFan fan;
    fan.stream = 11;
    fan.zLift = 0.5f;
    fan.targetMin = Vec3(-2.2f, -2.0f, -1.0f);
    fan.targetMax = Vec3(2.2f, 2.0f, 1.2f);
    return test::raysFromShell(count, seed, fan);
}

TEST(ImplicitAccelAgreement, NaiveAndEmbreeFindTheSameHits) {
    const ImplicitShapesScene scene;
    const auto embree = buildEmbreeAccel(std::span<const ShapeRef>(scene.refs), {});
    const auto naive = buildNaiveAccel(scene.refs);
    ASSERT_GT(scene.gyroid.primitiveCount(), 200u);

    int hits[6] = {0, 0, 0, 0, 0, 0};
    int misses = 0, sharedFace = 0, uDiffers = 0;
    for (const Ray& ray : implicitShapeRays(3000, 101)) {
        const Hit a = embree->intersect(ray), b = naive->intersect(ray);
        ASSERT_EQ(a.valid(), b.valid());
        EXPECT_EQ(embree->occluded(ray), a.valid());
        EXPECT_EQ(naive->occluded(ray), b.valid());
        if (!a.valid()) {
            ++misses;
            continue;
        }
        ASSERT_EQ(a.geomID, b.geomID) << "t " << a.t << " vs " << b.t;
        ++hits[a.geomID];
        if (scene.refs[a.geomID].mesh) {
            // Embree's triangle kernel and the watertight test: float rounding apart.
            EXPECT_EQ(a.primID, b.primID);
            EXPECT_NEAR(a.t, b.t, 1e-5f * a.t);
            EXPECT_GT(glm::dot(a.Ng, b.Ng), 0.0f);
            continue;
        }
        EXPECT_EQ(a.t, b.t) << "geomID " << a.geomID << " primIDs " << a.primID << ", " << b.primID;
        if (a.primID != b.primID) {
            // Both cells hold the root: it is on (within the tolerance of) their shared face.
            ++sharedFace;
            continue;
        }
        EXPECT_EQ(a.Ng, b.Ng);
        EXPECT_EQ(a.v, b.v);
        // u carries the root's t-uncertainty. The generic root finder searches
        // (tnear, min(cell exit, tfar)), and tfar depends on the order the
        // tracer visited other cells in, so the bisection path — and the error
        // estimate, not the float t — may differ in the last digits (~1e-15).
        EXPECT_NEAR(a.u, b.u, 1e-9f) << "geomID " << a.geomID;
        uDiffers += a.u != b.u;
    }
    for (int g = 0; g < 6; ++g) EXPECT_GT(hits[g], 40) << "geomID " << g;
    EXPECT_GT(misses, 20);
    // Shared-face ties are the exception, not the rule.
    EXPECT_LT(sharedFace, 30);
    EXPECT_LT(uDiffers, 100);
}

TEST(ImplicitAccelAgreement, NaivePacketsMatchEmbreePackets) {
    const ImplicitShapesScene scene;
    const auto embree = buildEmbreeAccel(std::span<const ShapeRef>(scene.refs), {});
    const auto naive = buildNaiveAccel(scene.refs);
    const std::vector<Ray> rays = implicitShapeRays(16 * 40, 7);
    int compared = 0;
    for (size_t base = 0; base + 16 <= rays.size(); base += 16) {
        RayHitPacket16 a, b;
        alignas(64) int valid[16];
        for (int lane = 0; lane < 16; ++lane) {
            valid[lane] = (lane * 7 + int(base)) % 5 == 0 ? 0 : -1;
            a.setRay(lane, rays[base + size_t(lane)]);
            b.setRay(lane, rays[base + size_t(lane)]);
        }
        embree->intersect16(valid, a, RayCoherence::Incoherent);
        naive->intersect16(valid, b, RayCoherence::Incoherent);
        for (int lane = 0; lane < 16; ++lane) {
            if (!valid[lane]) {
                EXPECT_EQ(a.geomID[lane], kInvalidId);
                EXPECT_EQ(b.geomID[lane], kInvalidId);
                continue;
            }
            const Hit ha = a.hit(lane), hb = b.hit(lane);
            ASSERT_EQ(ha.valid(), hb.valid());
            if (!ha.valid()) continue;
            ASSERT_EQ(ha.geomID, hb.geomID);
            if (scene.refs[ha.geomID].user) {
                ++compared;
                EXPECT_EQ(ha.t, hb.t);
            }
        }
    }
    EXPECT_GT(compared, 200);
}

}  // namespace
}  // namespace strahl
