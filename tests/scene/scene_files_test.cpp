// The parse/load boundary: parsing reads the scene file alone; the files it
// names (meshes, a glTF file's cameras, Bézier patch files, height images)
// are read when the scene is built, each once, and their errors name the
// place in the scene file as parse errors do (scene_desc.h, scene_builder.h).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "meshio/warning_capture.h"
#include "scene_test_helpers.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "strahl/scene/scene_document.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::naive;
using testing::HasSubstr;

// One triangle, one perspective camera looking down -z from (0, 0, 3), and an
// extension the loader ignores with a warning: one warning per read.
const std::string kGltf = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_example_ignored"],
  "scene": 0,
  "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 3]}],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36,
               "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]
})";

size_t count(const std::string& text, const std::string& part) {
    size_t n = 0;
    for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
}

TEST(SceneFiles, ParsingReadsNoFileTheSceneNames) {
    const fs::path dir = test::scratchDir("scene-files-parse");
    for (const char* name : {"cams.gltf", "mesh.obj", "patches.bpt", "heights.png"})
        test::writeFile(dir / name, "not what the name says\n");
    const std::string scene = R"({
      "camera": {"gltf": "cams.gltf"},
      "shapes": [
        {"type": "mesh", "file": "mesh.obj"},
        {"type": "parametric", "surface": {"type": "bezier", "file": "patches.bpt"}},
        {"type": "parametric", "surface": {"type": "heightfield", "image": "heights.png"}}
      ]})";
    const SceneDesc desc = parseSceneText(scene, dir / "scene.json");
    ASSERT_TRUE(desc.camera.gltf.has_value());
    EXPECT_EQ(desc.camera.gltf->file, dir / "cams.gltf");
    ASSERT_TRUE(desc.shapes[1].parametric.file.has_value());
    EXPECT_EQ(desc.shapes[1].parametric.surface, nullptr);
    EXPECT_EQ(desc.shapes[2].parametric.file->kind, ParametricFile::Kind::HeightImage);

    // Building reads them; the camera's file fails first, named by its place.
    EXPECT_THAT(test::errorMessage([&] { buildScene(desc, naive()); }),
                HasSubstr("scene.json: /camera/gltf: "));
}

TEST(SceneFiles, ErrorsOfFilesReadByTheBuilderNameTheCommandLinePatches) {
    const fs::path dir = test::scratchDir("scene-files-patches");
    test::writeFile(dir / "cams.gltf", kGltf);
    SceneDocument document = SceneDocument::fromText(
        R"({"camera": {"gltf": "cams.gltf"}, "shapes": [{"type": "mesh", "file": "cams.gltf"}]})",
        dir / "scene.json");
    document.apply(parseSetArgument("/camera/gltf_camera=4"));
    test::WarningCapture quiet;
    EXPECT_EQ(test::errorMessage([&] { buildScene(document.parse(), naive()); }),
              (dir / "scene.json").string() +
                  ": /camera/gltf_camera: must be between 0 and 0, got 4 (set by --set "
                  "/camera/gltf_camera=4)");
}

TEST(SceneFiles, AGltfFileGivingTheCameraAndMeshesIsReadOnce) {
    const fs::path dir = test::scratchDir("scene-files-once");
    test::writeFile(dir / "scene.gltf", kGltf);
    const SceneDesc desc = parseSceneText(R"({
      "camera": {"gltf": "scene.gltf"},
      "shapes": [{"type": "mesh", "file": "scene.gltf"},
                 {"type": "mesh", "file": "scene.gltf", "transform": [{"translate": [2, 0, 0]}]}]
    })", dir / "scene.json");
    test::WarningCapture warnings;
    const BuiltScene built = buildScene(desc, naive());
    EXPECT_EQ(count(warnings.text(), "ignoring the glTF extensions"), 1u) << warnings.text();
    EXPECT_FALSE(built.camera.gltf.has_value());
    EXPECT_EQ(built.camera.eye, Vec3(0.0f, 0.0f, 3.0f));
    ASSERT_EQ(built.world.shapes.size(), 2u);
    EXPECT_EQ(built.world.shapes[0].mesh.triangleCount(), 1u);
    EXPECT_EQ(built.world.shapes[1].mesh.triangleCount(), 1u);
    EXPECT_EQ(built.world.shapes[1].mesh.positions[0], Vec3(2.0f, 0.0f, 0.0f));
}

TEST(SceneFiles, AMeshFileNamedByManyShapesIsReadOnce) {
    const fs::path dir = test::scratchDir("scene-files-obj");
    test::writeFile(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\ncstype bezier\nf 1 2 3\n");
    const SceneDesc desc = parseSceneText(R"({"shapes": [
        {"type": "mesh", "file": "tri.obj"}, {"type": "mesh", "file": "tri.obj"},
        {"type": "mesh", "file": "tri.obj"}]})", dir / "scene.json");
    test::WarningCapture warnings;
    const World world = buildWorld(desc, naive());
    EXPECT_EQ(count(warnings.text(), "ignoring unsupported statement"), 1u) << warnings.text();
    ASSERT_EQ(world.shapes.size(), 3u);
    for (const SceneShape& shape : world.shapes) EXPECT_EQ(shape.mesh.triangleCount(), 1u);
}

TEST(SceneFiles, ACameraStillToBeReadIsNotACamera) {
    const fs::path dir = test::scratchDir("scene-files-camera");
    test::writeFile(dir / "cams.gltf", kGltf);
    const SceneDesc desc = parseSceneText(
        R"({"camera": {"gltf": "cams.gltf"}, "shapes": [{"type": "mesh", "file": "cams.gltf"}]})",
        dir / "scene.json");
    EXPECT_THAT(test::errorMessage([&] { buildCamera(desc.camera, 8, 8); }),
                HasSubstr("/camera/gltf: the camera is read from the glTF file when the scene is "
                          "built"));
}

}  // namespace
}  // namespace strahl
