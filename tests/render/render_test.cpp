// The render loop: radiometry of the direct integrator against closed forms,
// shadows, packet widths, and determinism across thread counts and tile sizes.

#include "strahl/render/renderer.h"

#include <gtest/gtest.h>

#include "strahl/core/error.h"

namespace strahl {
namespace {

// A 20 x 20 floor quad at y = 0 (albedo rho) with an optional small occluder.
World floorWorld(float rho, bool occluder) {
    World world;
    world.materials.push_back(Material::diffuse("floor", Color(rho)));
    SceneShape floor;
    floor.mesh.positions = {{-10, 0, -10}, {10, 0, -10}, {10, 0, 10}, {-10, 0, 10}};
    floor.mesh.indices = {0, 2, 1, 0, 3, 2};
    floor.materialOfSlot = {0};
    world.shapes.push_back(std::move(floor));
    if (occluder) {
        SceneShape blocker;
        blocker.mesh.positions = {{-0.5f, 1, -0.5f}, {0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}, {-0.5f, 1, 0.5f}};
        blocker.mesh.indices = {0, 1, 2, 0, 2, 3};
        blocker.materialOfSlot = {0};
        world.shapes.push_back(std::move(blocker));
    }
    std::vector<const TriangleMesh*> meshes;
    for (SceneShape& g : world.shapes) {
        g.mesh.reservePadding();
        meshes.push_back(&g.mesh);
    }
    world.accel = buildEmbreeAccel(meshes, {});
    world.prepareLights();
    return world;
}

PointLight pointLight(const Vec3& position, const Color& intensity) {
    PointLight light;
    light.position = position;
    light.intensity = intensity;
    return light;
}

DirectionalLight directionalLight(const Vec3& direction, const Color& irradiance) {
    DirectionalLight light;
    light.direction = direction;
    light.irradiance = irradiance;
    return light;
}

// Orthographic camera 5 units above the floor looking straight down; with an
// odd resolution the centre pixel's ray hits the origin exactly.
Camera downCamera(int n) {
    const CameraFrame frame = CameraFrame::fromBackUp(Vec3(0, 5, 0), Vec3(0, 1, 0), Vec3(0, 0, -1));
    return Camera(frame, Projection::Orthographic, ImageWindow{-0.2f, 0.2f, -0.2f, 0.2f}, 1.0f, n, n);
}

Color centrePixel(const Film& film) {
    const std::vector<float> rgb = film.resolveBeauty();
    const int w = film.crop().width(), h = film.crop().height();
    const size_t i = 3 * (size_t(h / 2) * size_t(w) + size_t(w / 2));
    return Color(rgb[i], rgb[i + 1], rgb[i + 2]);
}

Color renderCentre(const World& world, const std::string& integrator) {
    Film film(5, 5, PixelRect{0, 0, 5, 5}, {});
    renderImage(world, downCamera(5), *makeIntegrator(integrator, world), film, RenderOptions{});
    return centrePixel(film);
}

TEST(DirectIntegrator, PointLightFollowsTheInverseSquareLaw) {
    World world = floorWorld(0.5f, false);
    const float I = 8.0f, h = 2.0f;
    world.lights.push_back(pointLight(Vec3(0, h, 0), Color(I)));
    world.prepareLights();
    const Color L = renderCentre(world, "direct");
    // L = rho/pi * I/h^2 * cos(0)
    EXPECT_NEAR(L.x, 0.5f / kPi * I / (h * h), 1e-5f);
}

TEST(DirectIntegrator, DirectionalLightFollowsLambertsCosineLaw) {
    World world = floorWorld(0.6f, false);
    const Vec3 dir = glm::normalize(Vec3(1, -1, 0));  // 45 degrees
    world.lights.push_back(directionalLight(dir, Color(2.0f)));
    world.prepareLights();
    const Color L = renderCentre(world, "direct");
    EXPECT_NEAR(L.y, 0.6f / kPi * 2.0f * std::cos(kPi / 4), 1e-5f);
}

TEST(DirectIntegrator, OccluderCastsAHardShadow) {
    World world = floorWorld(0.5f, true);
    world.lights.push_back(pointLight(Vec3(0, 3, 0), Color(5.0f)));
    world.prepareLights();
    // From above, the camera sees the occluder's top at y = 1, lit from 2 units.
    EXPECT_NEAR(renderCentre(world, "direct").x, 0.5f / kPi * 5.0f / 4.0f, 1e-5f);
    // From between occluder and floor, it sees the floor in the occluder's shadow.
    Film film(5, 5, PixelRect{0, 0, 5, 5}, {});
    const Camera under(CameraFrame::fromBackUp(Vec3(0, 0.5f, 0), Vec3(0, 1, 0), Vec3(0, 0, -1)),
                       Projection::Orthographic, ImageWindow{-0.2f, 0.2f, -0.2f, 0.2f}, 1.0f, 5, 5);
    renderImage(world, under, *makeIntegrator("direct", world), film, RenderOptions{});
    EXPECT_EQ(centrePixel(film).x, 0.0f);
}

TEST(DirectIntegrator, GrazingLightDoesNotProduceShadowAcne) {
    // A light just above a large floor: every pixel the light reaches must be lit.
    World world = floorWorld(0.5f, false);
    world.lights.push_back(pointLight(Vec3(0, 0.01f, 0), Color(1.0f)));
    world.prepareLights();
    Film film(33, 33, PixelRect{0, 0, 33, 33}, {});
    const Camera cam(CameraFrame::fromBackUp(Vec3(0, 5, 0), Vec3(0, 1, 0), Vec3(0, 0, -1)),
                     Projection::Orthographic, ImageWindow{-8, 8, -8, 8}, 1.0f, 33, 33);
    renderImage(world, cam, *makeIntegrator("direct", world), film, RenderOptions{});
    for (float v : film.resolveBeauty()) EXPECT_GT(v, 0.0f);
}

TEST(DebugIntegrators, EyelightNormalAndDepthOfAFacingPlane) {
    World world = floorWorld(0.5f, false);
    EXPECT_NEAR(renderCentre(world, "eyelight").x, 1.0f, 1e-6f);  // |N.D| = 1
    const Color n = renderCentre(world, "normal");
    EXPECT_NEAR(n.y, 1.0f, 1e-6f);  // N = (0,1,0) -> (0.5, 1, 0.5)
    EXPECT_NEAR(n.x, 0.5f, 1e-6f);
    const float diagonal = glm::length(world.bounds().diagonal());
    EXPECT_NEAR(renderCentre(world, "depth").x, 5.0f / diagonal, 1e-5f);
    EXPECT_GT(maxComponent(renderCentre(world, "primid")), 0.1f);
    EXPECT_THROW(makeIntegrator("phong", world), Error);
}

TEST(Renderer, AovsDescribeTheFirstHit) {
    World world = floorWorld(0.25f, false);
    Film film(5, 5, PixelRect{0, 0, 5, 5}, {AovKind::Normal, AovKind::Depth, AovKind::Albedo});
    renderImage(world, downCamera(5), *makeIntegrator("eyelight", world), film, RenderOptions{});
    EXPECT_NEAR(film.resolveAov(AovKind::Depth)[12], 5.0f, 1e-5f);
    EXPECT_NEAR(film.resolveAov(AovKind::Normal)[3 * 12 + 1], 1.0f, 1e-6f);
    EXPECT_NEAR(film.resolveAov(AovKind::Albedo)[3 * 12], 0.25f, 1e-6f);
}

// A small scene with several triangles, lights, jittered samples and misses.
World richWorld() {
    World world = floorWorld(0.5f, true);
    world.lights.emplace_back(pointLight(Vec3(1, 3, 1), Color(5.0f)));
    world.lights.emplace_back(directionalLight(glm::normalize(Vec3(-1, -2, 0)), Color(0.5f)));
    world.background = Color(0.1f, 0.2f, 0.3f);
    world.prepareLights();
    return world;
}

Film renderRich(const World& world, int threads, int tile, PacketMode mode) {
    const Camera cam(CameraFrame::lookAt(Vec3(3, 4, 6), Vec3(0), Vec3(0, 1, 0)),
                     Projection::Perspective, Camera::windowFromFov(0.8f, 1.0f, 61, 47), 1.0f, 61, 47);
    Film film(61, 47, PixelRect{0, 0, 61, 47}, {AovKind::Normal, AovKind::Depth});
    RenderOptions options;
    options.threads = threads;
    options.tileSize = tile;
    options.spp = 3;
    options.seed = 9;
    options.packets = mode;
    renderImage(world, cam, *makeIntegrator("direct", world), film, options);
    return film;
}

TEST(Renderer, IdenticalForAnyThreadCountAndTileSize) {
    const World world = richWorld();
    const Film one = renderRich(world, 1, 32, PacketMode::Auto);
    const Film two = renderRich(world, 2, 32, PacketMode::Auto);
    const Film tiles = renderRich(world, 2, 8, PacketMode::Auto);
    EXPECT_EQ(one.resolveBeauty(), two.resolveBeauty());
    EXPECT_EQ(one.resolveBeauty(), tiles.resolveBeauty());
    EXPECT_EQ(one.resolveAov(AovKind::Depth), two.resolveAov(AovKind::Depth));
}

TEST(Renderer, PacketWidthsAndSingleRaysAgree) {
    const World world = richWorld();
    const std::vector<float> p16 = renderRich(world, 2, 32, PacketMode::Packet16).resolveBeauty();
    const std::vector<float> p8 = renderRich(world, 2, 32, PacketMode::Packet8).resolveBeauty();
    const std::vector<float> single = renderRich(world, 2, 32, PacketMode::Single).resolveBeauty();
    ASSERT_EQ(p16.size(), single.size());
    int differing = 0;
    for (size_t i = 0; i < p16.size(); ++i) {
        // Embree's packet and single-ray kernels may round u, v differently in
        // the last bit; the shaded values must still agree closely.
        EXPECT_NEAR(p16[i], single[i], 1e-4f) << "channel " << i;
        EXPECT_NEAR(p8[i], single[i], 1e-4f) << "channel " << i;
        differing += p16[i] != single[i];
    }
    EXPECT_LT(differing, int(p16.size()) / 100);
}

TEST(Renderer, CropRendersOnlyItsWindowWithTheSamePixels) {
    const World world = richWorld();
    const Film full = renderRich(world, 2, 32, PacketMode::Auto);
    const Camera cam(CameraFrame::lookAt(Vec3(3, 4, 6), Vec3(0), Vec3(0, 1, 0)),
                     Projection::Perspective, Camera::windowFromFov(0.8f, 1.0f, 61, 47), 1.0f, 61, 47);
    Film crop(61, 47, PixelRect{10, 5, 30, 20}, {});
    RenderOptions options;
    options.spp = 3;
    options.seed = 9;
    const RenderStats stats = renderImage(world, cam, *makeIntegrator("direct", world), crop, options);
    EXPECT_EQ(stats.cameraRays, 20u * 15u * 3u);
    const std::vector<float> a = full.resolveBeauty(), b = crop.resolveBeauty();
    for (int y = 5; y < 20; ++y)
        for (int x = 10; x < 30; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(a[3 * (size_t(y) * 61 + size_t(x)) + size_t(c)],
                          b[3 * (size_t(y - 5) * 20 + size_t(x - 10)) + size_t(c)]);
}

}  // namespace
}  // namespace strahl
