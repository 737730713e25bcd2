// Pins generated camera rays to the textbook formulas (docs/camera.md).

#include "strahl/camera/camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "strahl/camera/tile_rays.h"
#include "strahl/core/error.h"
#include "strahl/core/sampling.h"

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

// Lens samples on a grid over [0, 1)^2 (cell centres), plus the corners of the
// square, which the concentric map sends to the rim of the disk.
std::vector<Vec2> lensSamples() {
    std::vector<Vec2> samples;
    constexpr int kGrid = 9;
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i)
            samples.emplace_back((float(i) + 0.5f) / kGrid, (float(j) + 0.5f) / kGrid);
    for (const Vec2 corner : {Vec2(0.0f), Vec2(0.0f, 0.999f), Vec2(0.999f, 0.0f), Vec2(0.999f)})
        samples.push_back(corner);
    return samples;
}

// Raster positions inside and on the edges of a 6x4 image.
const Vec2 kRasterPoints[] = {{0.5f, 0.5f}, {3.25f, 1.75f}, {0.0f, 4.0f}, {6.0f, 0.0f},
                              {5.9f, 3.1f}};

// Distance of point p from the line through the ray.
float distanceToLine(const Ray& r, const Vec3& p) {
    return glm::length(glm::cross(p - r.origin, r.dir)) / glm::length(r.dir);
}

// Depth of p in front of the camera: its distance from the lens plane along -w.
float depthOf(const CameraFrame& f, const Vec3& p) { return glm::dot(p - f.e, -f.w); }

void expectSameRay(const Ray& a, const Ray& b) {
    EXPECT_EQ(a.origin, b.origin);
    EXPECT_EQ(a.dir, b.dir);
    EXPECT_EQ(a.tnear, b.tnear);
    EXPECT_EQ(a.tfar, b.tfar);
}

TEST(ThinLens, ZeroApertureIsThePinholeBitForBit) {
    const CameraFrame f = obliqueFrame();
    const ImageWindow win{-1.0f, 1.5f, -0.75f, 1.0f};
    for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        const Camera plain(f, projection, win, 2.5f, 6, 4);
        const Camera defaulted(f, projection, win, 2.5f, 6, 4, ThinLens{});
        const Camera refocused(f, projection, win, 2.5f, 6, 4, ThinLens{0.0f, 7.0f});
        EXPECT_EQ(plain.apertureRadius(), 0.0f);
        EXPECT_EQ(plain.focusDistance(), 2.5f);
        for (const Vec2 p : kRasterPoints) {
            const Ray pinhole = plain.generateRay(p.x, p.y);
            expectSameRay(defaulted.generateRay(p.x, p.y), pinhole);
            expectSameRay(refocused.generateRay(p.x, p.y), pinhole);
            for (const Vec2 lens : lensSamples()) {
                expectSameRay(plain.generateRay(p.x, p.y, lens), pinhole);
                expectSameRay(refocused.generateRay(p.x, p.y, lens), pinhole);
            }
        }
    }
}

TEST(ThinLens, PerspectiveRaysOfARasterPointConvergeOnTheFocusPlane) {
    const CameraFrame f = obliqueFrame();
    const float d = 1.5f, focus = 4.0f, radius = 0.3f;
    const Camera cam(f, Projection::Perspective, ImageWindow{-1.0f, 1.5f, -0.75f, 1.0f}, d, 6, 4,
                     ThinLens{radius, focus});
    EXPECT_EQ(cam.apertureRadius(), radius);
    EXPECT_EQ(cam.focusDistance(), focus);
    for (const Vec2 p : kRasterPoints) {
        // Where the pinhole ray of (x, y) meets the focus plane.
        const Ray pinhole = cam.generateRay(p.x, p.y);
        const float tFocus = (focus - depthOf(f, pinhole.origin)) / glm::dot(pinhole.dir, -f.w);
        const Vec3 inFocus = pinhole.at(tFocus);
        ASSERT_NEAR(depthOf(f, inFocus), focus, 1e-4f);
        for (const Vec2 lens : lensSamples()) {
            const Ray r = cam.generateRay(p.x, p.y, lens);
            EXPECT_NEAR(glm::length(r.dir), 1.0f, kTol);
            EXPECT_EQ(r.tnear, 0.0f);
            EXPECT_TRUE(std::isinf(r.tfar));
            // Every ray passes through the in-focus point, in front of its origin ...
            EXPECT_LT(distanceToLine(r, inFocus), 1e-5f);
            EXPECT_GT(glm::dot(inFocus - r.origin, r.dir), 0.0f);
            // ... and starts on the image plane, as the pinhole ray does.
            EXPECT_NEAR(depthOf(f, r.origin), d, 1e-5f);
        }
    }
}

TEST(ThinLens, LensPointsAreTheConcentricDiskSamples) {
    const CameraFrame f = obliqueFrame();
    const float radius = 0.25f;
    const Camera cam(f, Projection::Perspective, ImageWindow{}, 1.0f, 6, 4,
                     ThinLens{radius, 3.0f});
    float largest = 0.0f;
    for (const Vec2 p : kRasterPoints) {
        for (const Vec2 lens : lensSamples()) {
            // Follow the ray back to the lens plane (depth 0).
            const Ray r = cam.generateRay(p.x, p.y, lens);
            const float t = -depthOf(f, r.origin) / glm::dot(r.dir, -f.w);
            const Vec3 onLens = r.at(t) - f.e;
            EXPECT_NEAR(glm::dot(onLens, f.w), 0.0f, 1e-5f);
            EXPECT_LE(glm::length(onLens), radius * (1.0f + 1e-5f));
            const Vec2 disk = radius * sampleConcentricDisk(lens);
            expectNear(onLens, disk.x * f.u + disk.y * f.v);
            largest = std::max(largest, glm::length(onLens));
        }
    }
    EXPECT_GT(largest, 0.99f * radius);  // the corners of [0, 1)^2 reach the rim
}

TEST(ThinLens, DefaultFocusIsTheFocalDistanceWhereAllRaysOfAPointStart) {
    const CameraFrame f = obliqueFrame();
    const float d = 2.0f;
    const Camera cam(f, Projection::Perspective, ImageWindow{}, d, 6, 4,
                     ThinLens{0.5f, std::nullopt});
    EXPECT_EQ(cam.focusDistance(), d);
    for (const Vec2 p : kRasterPoints) {
        const Ray pinhole = cam.generateRay(p.x, p.y);
        for (const Vec2 lens : lensSamples())
            expectNear(cam.generateRay(p.x, p.y, lens).origin, pinhole.origin);
    }
}

TEST(ThinLens, CircleOfConfusionGrowsAwayFromTheFocusPlane) {
    // At depth z the rays from the rim of a lens of radius R focused at depth f
    // are R |z - f| / f from the pinhole ray (docs/camera.md, "Thin lens").
    const CameraFrame f = CameraFrame::lookAt(Vec3(0, 0, 5), Vec3(0), Vec3(0, 1, 0));
    const float radius = 0.2f, focus = 5.0f;
    const Camera cam(f, Projection::Perspective, ImageWindow{}, 1.0f, 6, 4,
                     ThinLens{radius, focus});
    const Ray pinhole = cam.generateRay(2.5f, 1.5f);
    const Vec2 rim(1.0f - 1e-7f, 0.5f);  // the concentric map sends it to (1, 0)
    const Ray r = cam.generateRay(2.5f, 1.5f, rim);
    for (float z : {2.0f, 4.0f, 5.0f, 8.0f, 20.0f}) {
        const auto atDepth = [&](const Ray& ray) {
            return ray.at((z - depthOf(f, ray.origin)) / glm::dot(ray.dir, -f.w));
        };
        const float blur = glm::length(atDepth(r) - atDepth(pinhole));
        EXPECT_NEAR(blur, radius * std::abs(z - focus) / focus, 1e-4f) << "depth " << z;
    }
}

TEST(ThinLens, OrthographicLensIsCentredOnEachPinholeOrigin) {
    const CameraFrame f = obliqueFrame();
    const float radius = 0.2f, focus = 3.0f;
    const Camera cam(f, Projection::Orthographic, ImageWindow{-2.0f, 3.0f, -1.5f, 0.5f}, 1.0f, 6,
                     4, ThinLens{radius, focus});
    for (const Vec2 p : kRasterPoints) {
        const Ray pinhole = cam.generateRay(p.x, p.y);
        const Vec3 inFocus = pinhole.origin - focus * f.w;
        for (const Vec2 lens : lensSamples()) {
            const Ray r = cam.generateRay(p.x, p.y, lens);
            const Vec3 offset = r.origin - pinhole.origin;
            EXPECT_NEAR(glm::dot(offset, f.w), 0.0f, 1e-5f);  // still on the plane through e
            EXPECT_LE(glm::length(offset), radius * (1.0f + 1e-5f));
            const Vec2 disk = radius * sampleConcentricDisk(lens);
            expectNear(offset, disk.x * f.u + disk.y * f.v);
            EXPECT_NEAR(glm::length(r.dir), 1.0f, kTol);
            EXPECT_LT(distanceToLine(r, inFocus), 1e-5f);
            EXPECT_GT(glm::dot(inFocus - r.origin, r.dir), 0.0f);
        }
    }
}

TEST(ThinLens, RejectsInvalidApertureAndFocusDistance) {
    const CameraFrame f;
    const auto make = [&](ThinLens lens) {
        return Camera(f, Projection::Perspective, ImageWindow{}, 1.0f, 4, 4, lens);
    };
    EXPECT_THROW(make(ThinLens{-0.1f, std::nullopt}), Error);
    EXPECT_THROW(make(ThinLens{std::nanf(""), std::nullopt}), Error);
    EXPECT_THROW(make(ThinLens{kInfinity, std::nullopt}), Error);
    EXPECT_THROW(make(ThinLens{0.1f, 0.0f}), Error);
    EXPECT_THROW(make(ThinLens{0.1f, -2.0f}), Error);
    EXPECT_THROW(make(ThinLens{0.1f, kInfinity}), Error);
    EXPECT_THROW(make(ThinLens{0.0f, std::nanf("")}), Error);
    EXPECT_NO_THROW(make(ThinLens{0.1f, 0.5f}));  // focused in front of the image plane
    try {
        make(ThinLens{-1.0f, std::nullopt});
        FAIL() << "expected strahl::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("aperture"), std::string::npos) << e.what();
    }
}

TEST(TileRayGenerator, OneSampleGoesThroughPixelCentres) {
    const Camera cam(obliqueFrame(), Projection::Perspective, ImageWindow{}, 1.0f, 9, 7);
    const TileRayGenerator gen(cam, 42, 1);
    Sampler rng;
    const Ray r = gen.sampleRay(3, 5, 0, rng);
    const Ray expected = cam.generateRay(3.5f, 5.5f);
    expectNear(r.origin, expected.origin);
    expectNear(r.dir, expected.dir);
}

// The camera takes the first two pairs (filter offset, lens point) whether it
// draws them or, where their values would not be used (one sample per pixel,
// a pinhole), skips them: the integrator's dimensions start at pair 2 and are
// the same either way.
TEST(TileRayGenerator, TheIntegratorsDimensionsStartAfterTheCamerasTwoPairs) {
    const Camera pinhole(obliqueFrame(), Projection::Perspective, ImageWindow{}, 1.0f, 9, 7);
    ThinLens thin;
    thin.apertureRadius = 0.1f;
    const Camera lens(obliqueFrame(), Projection::Perspective, ImageWindow{}, 1.0f, 9, 7, thin);
    for (const Camera* cam : {&pinhole, &lens})
        for (int spp : {1, 4}) {
            const TileRayGenerator gen(*cam, 42, spp);
            Sampler sampler;
            gen.sampleRay(3, 5, 0, sampler);
            EXPECT_EQ(sampler.dimension(), 2u);
            Sampler reference(42, 3, 5, 0);
            reference.get2D();
            reference.get2D();
            EXPECT_EQ(sampler.get2D(), reference.get2D());
        }
}

TEST(TileRayGenerator, JitterIsDeterministicAndInsideThePixel) {
    const Camera cam(CameraFrame{}, Projection::Orthographic, ImageWindow{}, 1.0f, 8, 8);
    const TileRayGenerator gen(cam, 7, 4);
    Sampler a, b;
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

// A packet's lanes are bit for bit sampleRay's rays and samplers, whichever
// way the generator makes them (all the pinhole's rays at once; one lane at a
// time through the lens), and inactive lanes hold the default ray.
template <int N>
void checkPacketsEqualSampleRay() {
    ThinLens thin;
    thin.apertureRadius = 0.05f;
    const ImageWindow window{-1.3f, 0.7f, -0.4f, 0.9f};
    for (Projection projection : {Projection::Perspective, Projection::Orthographic})
        for (const ThinLens& lens : {ThinLens{}, thin})
            for (int spp : {1, 4}) {
                const Camera cam(obliqueFrame(), projection, window, 1.7f, 37, 23, lens);
                const TileRayGenerator gen(cam, 9, spp, PixelFilter::gaussian(1.5f, 0.5f));
                const PixelRect tile{32, 20, 37, 23};  // partial blocks on both edges
                const auto wanted = [](int x, int y) { return (x + 2 * y) % 5 != 0; };
                for (int s = 0; s < spp; ++s)
                    for (int by = tile.y0; by < tile.y1; by += CameraPacket<N>::kBlockHeight)
                        for (int bx = tile.x0; bx < tile.x1; bx += CameraPacket<N>::kBlockWidth) {
                            CameraPacket<N> packet;
                            gen.fillPacket(tile, bx, by, s, packet, wanted);
                            for (int lane = 0; lane < N; ++lane) {
                                const int x = packet.px[lane], y = packet.py[lane];
                                const bool active = x < tile.x1 && y < tile.y1 && wanted(x, y);
                                ASSERT_EQ(packet.valid[lane], active ? -1 : 0);
                                Sampler sampler;
                                const Ray expected = active ? gen.sampleRay(x, y, s, sampler) : Ray{};
                                const Ray ray = packet.rays.ray(lane);
                                EXPECT_EQ(ray.origin, expected.origin) << x << ", " << y;
                                EXPECT_EQ(ray.dir, expected.dir) << x << ", " << y;
                                EXPECT_EQ(ray.tnear, expected.tnear);
                                EXPECT_EQ(ray.tfar, expected.tfar);
                                EXPECT_EQ(ray.time, expected.time);
                                EXPECT_EQ(packet.rays.geomID[lane], kInvalidId);
                                if (active) {
                                    EXPECT_EQ(packet.sampler[lane].get2D(), sampler.get2D());
                                }
                            }
                        }
            }
}

TEST(TileRayGenerator, Packets16AreSampleRayBitForBit) { checkPacketsEqualSampleRay<16>(); }
TEST(TileRayGenerator, Packets8AreSampleRayBitForBit) { checkPacketsEqualSampleRay<8>(); }

}  // namespace
}  // namespace strahl
