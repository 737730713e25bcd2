// Pins generated camera rays to the textbook formulas (docs/camera.md).

#include "strahl/camera/camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/camera/tile_rays.h"
#include "strahl/core/error.h"

namespace strahl {
namespace {

constexpr float kTol = 1e-5f;

void expectNear(const Vec3& a, const Vec3& b, float tol = kTol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// An oblique frame, so no formula passes by accident of axis alignment.
CameraFrame obliqueFrame() {
    return CameraFrame::fromBackUp(Vec3(1.0f, 2.0f, 3.0f), Vec3(1.0f, 0.5f, 2.0f),
                                   Vec3(0.2f, 1.0f, -0.1f));
}

TEST(CameraFrame, IsOrthonormalAndRightHanded) {
    const CameraFrame f = obliqueFrame();
    EXPECT_NEAR(glm::length(f.u), 1.0f, kTol);
    EXPECT_NEAR(glm::length(f.v), 1.0f, kTol);
    EXPECT_NEAR(glm::length(f.w), 1.0f, kTol);
    EXPECT_NEAR(glm::dot(f.u, f.v), 0.0f, kTol);
    EXPECT_NEAR(glm::dot(f.v, f.w), 0.0f, kTol);
    EXPECT_NEAR(glm::dot(f.u, f.w), 0.0f, kTol);
    expectNear(glm::cross(f.v, f.w), f.u);  // u = v x w
    expectNear(f.w, glm::normalize(Vec3(1.0f, 0.5f, 2.0f)));
    // v lies in the plane of w and the up hint, on the hint's side.
    EXPECT_GT(glm::dot(f.v, Vec3(0.2f, 1.0f, -0.1f)), 0.0f);
    EXPECT_NEAR(glm::dot(glm::cross(Vec3(0.2f, 1.0f, -0.1f), f.w), f.v), 0.0f, kTol);
}

TEST(CameraFrame, LookAtPointsBackAwayFromTarget) {
    const CameraFrame f = CameraFrame::lookAt(Vec3(0, 0, 5), Vec3(0, 0, 0), Vec3(0, 1, 0));
    expectNear(f.w, Vec3(0, 0, 1));
    expectNear(f.u, Vec3(1, 0, 0));
    expectNear(f.v, Vec3(0, 1, 0));
}

TEST(CameraFrame, RejectsDegenerateInput) {
    EXPECT_THROW(CameraFrame::fromBackUp(Vec3(0), Vec3(0, 1, 0), Vec3(0, 2, 0)), Error);
    EXPECT_THROW(CameraFrame::fromBackUp(Vec3(0), Vec3(0), Vec3(0, 1, 0)), Error);
    EXPECT_THROW(CameraFrame::lookAt(Vec3(1), Vec3(1), Vec3(0, 1, 0)), Error);
}

TEST(Camera, OrthographicRaysFollowTheFormula) {
    const CameraFrame f = obliqueFrame();
    const ImageWindow win{-2.0f, 3.0f, -1.5f, 0.5f};
    const int nx = 7, ny = 5;
    const Camera cam(f, Projection::Orthographic, win, 1.0f, nx, ny);
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const float u = win.l + (win.r - win.l) * (float(i) + 0.5f) / float(nx);
            const float v = win.t + (win.b - win.t) * (float(j) + 0.5f) / float(ny);
            const Ray r = cam.generateRay(float(i) + 0.5f, float(j) + 0.5f);
            expectNear(r.origin, f.e + u * f.u + v * f.v);
            expectNear(r.dir, -f.w);
            EXPECT_EQ(r.tnear, 0.0f);
            EXPECT_TRUE(std::isinf(r.tfar));
        }
    }
}

TEST(Camera, PerspectiveRaysStartOnTheImagePlaneWithUnitDirections) {
    const CameraFrame f = obliqueFrame();
    const ImageWindow win{-1.0f, 1.5f, -0.75f, 1.0f};
    const float d = 2.5f;
    const int nx = 6, ny = 4;
    const Camera cam(f, Projection::Perspective, win, d, nx, ny);
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const float u = win.l + (win.r - win.l) * (float(i) + 0.5f) / float(nx);
            const float v = win.t + (win.b - win.t) * (float(j) + 0.5f) / float(ny);
            const Vec3 s = -d * f.w + u * f.u + v * f.v;
            const Ray r = cam.generateRay(float(i) + 0.5f, float(j) + 0.5f);
            expectNear(r.origin, f.e + s);
            expectNear(r.dir, glm::normalize(s));
            EXPECT_NEAR(glm::length(r.dir), 1.0f, kTol);
            // t is the Euclidean distance from the image plane point.
            expectNear(r.at(3.0f), f.e + s + 3.0f * glm::normalize(s), 1e-4f);
        }
    }
}

TEST(Camera, TopLeftPixelIsUpAndLeft) {
    const Camera cam(CameraFrame::lookAt(Vec3(0, 0, 5), Vec3(0), Vec3(0, 1, 0)),
                     Projection::Perspective, ImageWindow{}, 1.0f, 2, 2);
    const Ray r = cam.generateRay(0.5f, 0.5f);
    EXPECT_LT(r.dir.x, 0.0f);  // left: -u
    EXPECT_GT(r.dir.y, 0.0f);  // top row: +v
    EXPECT_LT(r.dir.z, 0.0f);  // forward: -w
}

TEST(Camera, WindowFromVerticalFieldOfView) {
    const float d = 2.0f, fov = glm::radians(60.0f);
    const ImageWindow w = Camera::windowFromFov(fov, d, 800, 400);
    EXPECT_NEAR(w.t, d * std::tan(fov / 2), kTol);
    EXPECT_NEAR(w.b, -w.t, kTol);
    EXPECT_NEAR(w.r, w.t * 2.0f, kTol);
    EXPECT_NEAR(w.l, -w.r, kTol);
}

TEST(Camera, RejectsInvalidWindowSizeAndFocalDistance) {
    const CameraFrame f;
    EXPECT_THROW(Camera(f, Projection::Orthographic, ImageWindow{0.5f, 1, -1, 1}, 1, 4, 4), Error);
    EXPECT_THROW(Camera(f, Projection::Orthographic, ImageWindow{-1, 1, 0.1f, 1}, 1, 4, 4), Error);
    EXPECT_THROW(Camera(f, Projection::Perspective, ImageWindow{}, 0.0f, 4, 4), Error);
    EXPECT_THROW(Camera(f, Projection::Perspective, ImageWindow{}, 1.0f, 0, 4), Error);
}

TEST(Camera, WorldToCameraMapsTheFrameToTheAxes) {
    const CameraFrame f = obliqueFrame();
    const Camera cam(f, Projection::Perspective, ImageWindow{}, 1.0f, 4, 4);
    const Mat4 m = cam.worldToCamera();
    expectNear(Vec3(m * Vec4(f.e, 1.0f)), Vec3(0.0f));
    expectNear(Vec3(m * Vec4(f.e + f.u, 1.0f)), Vec3(1, 0, 0));
    expectNear(Vec3(m * Vec4(f.e + f.v, 1.0f)), Vec3(0, 1, 0));
    expectNear(Vec3(m * Vec4(f.e + f.w, 1.0f)), Vec3(0, 0, 1));
}

TEST(TileRayGenerator, OneSampleGoesThroughPixelCentres) {
    const Camera cam(obliqueFrame(), Projection::Perspective, ImageWindow{}, 1.0f, 9, 7);
    const TileRayGenerator gen(cam, 42, 1);
    SampleRng rng;
    const Ray r = gen.sampleRay(3, 5, 0, rng);
    const Ray expected = cam.generateRay(3.5f, 5.5f);
    expectNear(r.origin, expected.origin);
    expectNear(r.dir, expected.dir);
}

TEST(TileRayGenerator, JitterIsDeterministicAndInsideThePixel) {
    const Camera cam(CameraFrame{}, Projection::Orthographic, ImageWindow{}, 1.0f, 8, 8);
    const TileRayGenerator gen(cam, 7, 4);
    SampleRng a, b;
    for (int s = 0; s < 4; ++s) {
        const Ray r1 = gen.sampleRay(2, 6, s, a);
        const Ray r2 = gen.sampleRay(2, 6, s, b);
        EXPECT_EQ(r1.origin, r2.origin);
        // Orthographic, window [-1,1]^2 over 8 pixels: pixel 2 spans u in [-0.5,-0.25].
        EXPECT_GE(r1.origin.x, -0.5f);
        EXPECT_LE(r1.origin.x, -0.25f);
        // Row 6 from the top spans v in [-0.75, -0.5].
        EXPECT_GE(r1.origin.y, -0.75f);
        EXPECT_LE(r1.origin.y, -0.5f);
    }
}

template <int N>
void checkPacketLayout() {
    const Camera cam(CameraFrame{}, Projection::Perspective, ImageWindow{}, 1.0f, 10, 10);
    const TileRayGenerator gen(cam, 0, 1);
    CameraPacket<N> packet;
    const PixelRect tile{8, 4, 10, 10};  // 2 pixels wide: half the lanes are outside
    const int active = gen.fillPacket(tile, 8, 4, 0, packet);
    EXPECT_EQ(active, 2 * (N / 4));
    for (int lane = 0; lane < N; ++lane) {
        const bool inside = packet.px[lane] < tile.x1 && packet.py[lane] < tile.y1;
        EXPECT_EQ(packet.valid[lane], inside ? -1 : 0);
        if (inside) {
            const Ray expected = cam.generateRay(float(packet.px[lane]) + 0.5f,
                                                 float(packet.py[lane]) + 0.5f);
            expectNear(packet.rays.ray(lane).dir, expected.dir);
        }
    }
}

TEST(TileRayGenerator, Packets16CoverFourByFourBlocks) { checkPacketLayout<16>(); }
TEST(TileRayGenerator, Packets8CoverFourByTwoBlocks) { checkPacketLayout<8>(); }

}  // namespace
}  // namespace strahl
