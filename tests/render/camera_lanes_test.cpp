// Integrator::shadeCameraLanes, the renderer's way to shade a camera packet at
// once: every lane it shades must get exactly what shadeCameraSample (shade()
// or miss() of that lane alone) gives, bit for bit, so an image does not
// depend on which of the two shaded a pixel. Checked on every camera packet of
// a scene with all the cases: flat meshes at the top level and inside
// instances and misses (shaded at once), a smooth mesh and an implicit surface
// inside instances (left to shade()).

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "strahl/camera/tile_rays.h"
#include "strahl/integrator/camera_sample.h"
#include "strahl/integrator/integrator.h"
#include "strahl/scene/scene_builder.h"
#include "test_support.h"

namespace strahl {
namespace {

SceneDesc lanesScene() {
    // instances.json's floor, charms (mesh + implicit torus) and row groups,
    // plus at the top level a smooth-shaded pyramid and a flat panel tilted
    // so that its normal has no exact components (the floor's is exact in any
    // rounding).
    SceneDesc desc = parseSceneFile(test::sourceDir() / "scenes/regression/instances.json");
    const SceneDesc smooth = parseSceneText(R"({"shapes": [
        {"type": "mesh", "name": "smooth pyramid", "normals": "smooth",
         "positions": [[-2.2, 0, 1.2], [-1.4, 0, 1.2], [-1.4, 0, 2.0], [-2.2, 0, 2.0], [-1.8, 0.9, 1.6]],
         "indices": [0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4]},
        {"type": "mesh", "name": "tilted flat panel",
         "positions": [[1.3, 0.1, 1.1], [2.4, 0.3, 1.5], [2.1, 1.3, 1.9], [1.2, 1.0, 1.3]],
         "indices": [0, 1, 2, 0, 2, 3]}]})",
                                            desc.file);
    desc.shapes.push_back(smooth.shapes[0]);
    desc.shapes.push_back(smooth.shapes[1]);
    return desc;
}

struct LaneCounts {
    int shaded = 0, left = 0, misses = 0;
};

template <int N>
LaneCounts checkEveryPacket(const World& world, const Camera& camera, const Integrator& integrator) {
    LaneCounts counts;
    const TileRayGenerator generator(camera, 7, 1);
    const PixelRect image{0, 0, camera.width(), camera.height()};
    for (CameraPacket<N>& packet : generator.tilePackets<N>(image, 0)) {
        world.accel->intersectPacket(packet.valid, packet.rays, RayCoherence::Coherent);
        Color radiance[N];
        const uint32_t shaded =
            integrator.shadeCameraLanes(world, CameraLanes::of(packet.rays, packet.valid), radiance);
        for (int lane = 0; lane < N; ++lane) {
            if (!packet.valid[lane]) {
                EXPECT_EQ(shaded & (1u << lane), 0u) << "a lane that was not traced was shaded";
                continue;
            }
            if (!(shaded & (1u << lane))) {
                ++counts.left;
                continue;
            }
            ++counts.shaded;
            Ray ray = packet.rays.ray(lane);
            ray.tfar = kInfinity;
            const Hit hit = packet.rays.hit(lane);
            counts.misses += !hit.valid();
            ShadingStats stats;
            const CameraSample one = shadeCameraSample(world, integrator, ray, hit,
                                                       packet.sampler[lane], stats, false);
            EXPECT_EQ(std::memcmp(&one.radiance, &radiance[lane], sizeof(Color)), 0)
                << integrator.name() << ", pixel (" << packet.px[lane] << ", " << packet.py[lane]
                << "): " << radiance[lane].x << " at once, " << one.radiance.x << " alone";
        }
    }
    return counts;
}

TEST(CameraLanes, EyelightAndNormalShadeLanesAsShadeDoesBitForBit) {
    const SceneDesc desc = lanesScene();
    const BuiltScene scene = buildScene(desc, BuildOptions{});
    const Camera camera = buildCamera(scene.camera, 96, 72);
    for (const char* name : {"eyelight", "normal"}) {
        const auto integrator = makeIntegrator(name, scene.world);
        for (const LaneCounts counts : {checkEveryPacket<8>(scene.world, camera, *integrator),
                                        checkEveryPacket<16>(scene.world, camera, *integrator)}) {
            // The flat meshes and the misses at once; the smooth pyramid
            // and the implicit tori left to shade().
            EXPECT_GT(counts.shaded - counts.misses, 1000) << name;
            EXPECT_GT(counts.misses, 0) << name;
            EXPECT_GT(counts.left, 200) << name;
        }
    }
}

TEST(CameraLanes, IntegratorsThatNeedTheSurfaceShadeNoLaneAtOnce) {
    const SceneDesc desc = lanesScene();
    const BuiltScene scene = buildScene(desc, BuildOptions{});
    const Camera camera = buildCamera(scene.camera, 96, 72);
    for (const char* name : {"depth", "primid", "direct", "path", "ao"}) {
        const auto integrator = makeIntegrator(name, scene.world);
        const LaneCounts counts = checkEveryPacket<8>(scene.world, camera, *integrator);
        EXPECT_EQ(counts.shaded, 0) << name;
        EXPECT_EQ(counts.left, 96 * 72) << name;
    }
}

}  // namespace
}  // namespace strahl
