// Cameras from glTF files (docs/scene-format.md, "camera"): the placed cameras
// in hierarchy order with their world frames, picked by index or name from a
// scene file, and one clear message for each bad camera.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "scene_test_helpers.h"
#include "strahl/core/error.h"
#include "strahl/meshio/gltf_camera.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::expectNear;
using test::naive;
using testing::HasSubstr;

// Node 0 "rig": translated to (1, 2, 3), turned 90 degrees about +y, with the
// perspective camera "main" (yfov 0.5); its child node 1 "top" carries the
// orthographic camera 1, turned -90 degrees about +x (looking straight down).
const std::string kCameras = R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [
    {"name": "rig", "camera": 0, "translation": [1, 2, 3],
     "rotation": [0, 0.70710678, 0, 0.70710678], "children": [1]},
    {"name": "top", "camera": 1, "rotation": [-0.70710678, 0, 0, 0.70710678]}
  ],
  "cameras": [
    {"name": "main", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}},
    {"type": "orthographic", "orthographic": {"xmag": 4, "ymag": 3, "znear": 0, "zfar": 100}}
  ]
})";

const std::string kShapes = R"("shapes": [{"type": "mesh",
    "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [0, 1, 2]}])";

TEST(GltfCamera, PlacedCamerasComeWithTheirWorldFrames) {
    const fs::path dir = test::scratchDir("gltf-camera");
    test::writeFile(dir / "cams.gltf", kCameras);
    const std::vector<GltfCamera> cameras = loadGltfCameras(dir / "cams.gltf");
    ASSERT_EQ(cameras.size(), 2u);
    EXPECT_EQ(cameras[0].name, "main");
    EXPECT_FALSE(cameras[0].orthographic);
    expectNear(cameras[0].eye, Vec3(1, 2, 3));
    expectNear(cameras[0].back, Vec3(1, 0, 0));  // +z turned about +y
    expectNear(cameras[0].up, Vec3(0, 1, 0));
    EXPECT_NEAR(cameras[0].yfovDegrees, 28.6478898f, 1e-4f);
    EXPECT_EQ(cameras[1].name, "top");  // no camera name: the node's
    EXPECT_TRUE(cameras[1].orthographic);
    expectNear(cameras[1].eye, Vec3(1, 2, 3));
    expectNear(cameras[1].back, Vec3(0, 1, 0));  // looking down -y
    expectNear(cameras[1].up, Vec3(-1, 0, 0));   // the rig's turn applies to the child
    EXPECT_EQ(cameras[1].xmag, 4.0f);
    EXPECT_EQ(cameras[1].ymag, 3.0f);
}

TEST(GltfCamera, ASceneFilePicksOneByIndexOrName) {
    const fs::path dir = test::scratchDir("gltf-camera-scene");
    test::writeFile(dir / "cams.gltf", kCameras);
    const auto camera = [&](const std::string& keys) {
        const SceneDesc desc = parseSceneText(
            R"({"camera": {"gltf": "cams.gltf")" + keys + "}, " + kShapes + "}", dir / "scene.json");
        EXPECT_TRUE(desc.camera.gltf.has_value());  // read when the scene is built
        return buildScene(desc, naive()).camera;
    };
    const CameraDesc first = camera("");
    EXPECT_EQ(first.projection, Projection::Perspective);
    expectNear(first.eye, Vec3(1, 2, 3));
    ASSERT_TRUE(first.back.has_value());
    expectNear(*first.back, Vec3(1, 0, 0));
    EXPECT_NEAR(*first.fovYDegrees, 28.6478898f, 1e-4f);

    const CameraDesc top = camera(R"(, "gltf_camera": "top", "aperture_radius": 0.1)");
    EXPECT_EQ(top.projection, Projection::Orthographic);
    ASSERT_TRUE(top.window.has_value());
    EXPECT_EQ(top.window->l, -4.0f);
    EXPECT_EQ(top.window->t, 3.0f);
    EXPECT_EQ(top.apertureRadius, 0.1f);
    EXPECT_EQ(camera(R"(, "gltf_camera": 1)").projection, Projection::Orthographic);
}

TEST(GltfCamera, BadCamerasAndChoicesNameThePlace) {
    const fs::path dir = test::scratchDir("gltf-camera-bad");
    test::writeFile(dir / "cams.gltf", kCameras);
    const auto sceneError = [&](const std::string& camera) {
        return test::errorMessage([&] {
            buildScene(parseSceneText(R"({"camera": )" + camera + ", " + kShapes + "}",
                                      dir / "scene.json"),
                       naive());
        });
    };
    EXPECT_THAT(sceneError(R"({"gltf": "cams.gltf", "gltf_camera": 2})"),
                HasSubstr("scene.json: /camera/gltf_camera: "));
    EXPECT_THAT(sceneError(R"({"gltf": "cams.gltf", "gltf_camera": "side"})"),
                HasSubstr("no camera named 'side' (the file has: main, top)"));
    EXPECT_THAT(sceneError(R"({"gltf": "cams.gltf", "fov": 30})"), HasSubstr("fov"));
    EXPECT_THAT(sceneError(R"({"gltf": "missing.gltf"})"), HasSubstr("/camera/gltf"));

    const struct {
        std::string from, to, message;
    } edits[] = {
        {R"("yfov": 0.5)", R"("yfov": 0)", "cameras[0]: perspective.yfov 0 is not in (0, pi)"},
        {R"("xmag": 4)", R"("xmag": 0)", "cameras[1]: orthographic.xmag and ymag must not be zero"},
        {R"("camera": 1,)", R"("camera": 7,)", "nodes[1]: camera 7 does not exist (2 cameras)"},
        {R"("translation": [1, 2, 3],)", R"("scale": [0, 0, 0],)",
         "cameras[0]: the transform of the node placing it leaves no camera frame"},
        {R"("camera": 0, )", "", ""},  // rig without a camera: only "top" remains
    };
    for (const auto& e : edits) {
        std::string text = kCameras;
        text.replace(text.find(e.from), e.from.size(), e.to);
        test::writeFile(dir / "edited.gltf", text);
        if (e.message.empty()) {
            EXPECT_EQ(loadGltfCameras(dir / "edited.gltf").size(), 1u);
            continue;
        }
        EXPECT_THAT(test::errorMessage([&] { loadGltfCameras(dir / "edited.gltf"); }),
                    HasSubstr("edited.gltf: " + e.message));
    }
    std::string none = kCameras;
    none.replace(none.find(R"("camera": 0, )"), 13, "");
    none.replace(none.find(R"("camera": 1, )"), 13, "");
    test::writeFile(dir / "none.gltf", none);
    EXPECT_THAT(sceneError(R"({"gltf": "none.gltf"})"),
                HasSubstr("/camera/gltf: none.gltf places no camera in its scene"));
}

}  // namespace
}  // namespace strahl
