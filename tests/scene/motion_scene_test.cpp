// Motion in the scene file: an instance's "motion" keyframes and the camera's
// "shutter" reach the world and the camera; keyframes compose with the
// transforms of the groups around them.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "strahl/core/error.h"
#include "strahl/core/transform.h"
#include "strahl/scene/scene_builder.h"
#include "test_support.h"

namespace strahl {
namespace {

const char* kMotionScene = R"({
  "camera": {"eye": [0, 0, 6], "shutter": [0.25, 0.75]},
  "groups": [
    {"name": "ball", "shapes": [{"type": "implicit", "surface": {"type": "sphere", "radius": 0.5}}]},
    {"name": "pair", "shapes": [{"type": "instance", "group": "ball", "transform": [{"translate": [0, 2, 0]}]},
                                {"type": "instance", "group": "ball"}]}
  ],
  "shapes": [
    {"type": "instance", "group": "pair", "motion": [[{"translate": [-1, 0, 0]}], [{"translate": [1, 0, 0]}],
                                                     [{"translate": [1, 0, 3]}]]},
    {"type": "instance", "group": "ball", "transform": [{"translate": [0, -3, 0]}]}
  ]
})";

TEST(MotionScene, KeyframesAndShutterReachTheWorldAndTheCamera) {
    const SceneDesc desc =
        parseSceneText(kMotionScene, test::scratchDir("motion-scene") / "scene.json");
    ASSERT_EQ(desc.shapes[0].motion.size(), 3u);
    EXPECT_FLOAT_EQ(desc.camera.shutter.open, 0.25f);
    EXPECT_FLOAT_EQ(desc.camera.shutter.close, 0.75f);

    const BuiltScene built = buildScene(desc, BuildOptions{});
    const World& world = built.world;
    ASSERT_EQ(world.instances.size(), 3u);
    EXPECT_TRUE(world.hasMotion());
    // The pair's two balls move; the nested one's keyframes carry its own
    // translation after the motion's.
    EXPECT_TRUE(world.instances[0].moves());
    EXPECT_TRUE(world.instances[1].moves());
    EXPECT_FALSE(world.instances[2].moves());
    const Vec3 nestedAtEnd = transformPoint(world.instances[0].motion[2], Vec3(0.0f));
    EXPECT_EQ(nestedAtEnd, Vec3(1, 2, 3));
    EXPECT_EQ(world.instances[0].objectToWorld, world.instances[0].motion[0]);
    // The world's bounds hold the whole motion.
    EXPECT_LE(world.bounds().min.x, -1.5f);
    EXPECT_GE(world.bounds().max.z, 3.5f);

    const Camera camera = buildCamera(built.camera, 32, 32);
    EXPECT_FLOAT_EQ(camera.shutter().timeAt(0.0f), 0.25f);
    EXPECT_FLOAT_EQ(camera.shutter().timeAt(1.0f), 0.75f);
}

TEST(MotionScene, AMovingShapeBecomesAMovingInstanceOfItsOwnGroup) {
    const std::string text = R"({
      "materials": [{"name": "red", "color": [0.8, 0.1, 0.1]}],
      "shapes": [{"type": "mesh", "name": "tri", "material": "red", "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                  "indices": [0, 1, 2], "motion": [[{"translate": [0, 0, 0]}], [{"translate": [0, 0, -1]}]]},
                 {"type": "implicit", "surface": {"type": "sphere", "radius": 0.5}}]})";
    const SceneDesc desc = parseSceneText(text, test::scratchDir("motion-shape") / "scene.json");
    ASSERT_EQ(desc.groups.size(), 1u);
    EXPECT_EQ(desc.groups[0].name, "tri (moving)");
    ASSERT_EQ(desc.groups[0].shapes.size(), 1u);
    EXPECT_EQ(desc.groups[0].shapes[0].material, "red");
    EXPECT_TRUE(desc.groups[0].shapes[0].motion.empty());
    EXPECT_EQ(desc.shapes[0].kind, ShapeKind::Instance);
    EXPECT_EQ(desc.shapes[0].motion.size(), 2u);
    EXPECT_EQ(desc.shapes[1].kind, ShapeKind::Implicit);
    const World world = buildWorld(desc, BuildOptions{});
    ASSERT_EQ(world.instances.size(), 1u);
    EXPECT_TRUE(world.instances[0].moves());
    EXPECT_EQ(world.prototypes[0].shapes[0].mesh.triangleCount(), 1u);
}

TEST(MotionScene, TransformAndMotionAreExclusive) {
    const std::string text = R"({
      "groups": [{"name": "ball", "shapes": [{"type": "implicit", "surface": {"type": "sphere", "radius": 0.5}}]}],
      "shapes": [{"type": "instance", "group": "ball", "transform": [{"translate": [0, 1, 0]}],
                  "motion": [[{"translate": [0, 0, 0]}], [{"translate": [1, 0, 0]}]]}]})";
    try {
        parseSceneText(text, test::scratchDir("motion-exclusive") / "scene.json");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_TRUE(test::contains(e.what(), "/shapes/0: give 'transform' (at rest) or 'motion' (keyframes), not both"))
            << e.what();
    }
}

TEST(MotionScene, ACameraWithoutShutterSeesTheWholeFrame) {
    const SceneDesc desc = parseSceneText(R"({"shapes": [{"type": "implicit", "surface": {"type": "sphere"}}]})",
                                          test::scratchDir("motion-default") / "scene.json");
    EXPECT_EQ(desc.camera.shutter.open, 0.0f);
    EXPECT_EQ(desc.camera.shutter.close, 1.0f);
    EXPECT_FALSE(buildScene(desc, BuildOptions{}).world.hasMotion());
}

}  // namespace
}  // namespace strahl

namespace strahl {
namespace {

TEST(MotionScene, DeformingInlineMeshes) {
    const std::string text = R"({
      "shapes": [{"type": "mesh", "name": "tri", "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [0, 1, 2],
                  "normals": "smooth", "transform": [{"translate": [0, 0, 2]}],
                  "deform": [[[0, 0, 1], [1, 0, 1], [0, 1, 1]], [[0, 0, 0], [2, 0, 0], [0, 2, 0]]]}]})";
    const SceneDesc desc = parseSceneText(text, test::scratchDir("deform") / "scene.json");
    EXPECT_EQ(desc.shapes[0].inlineMesh.keyframeCount(), 3u);
    const World world = buildWorld(desc, BuildOptions{});
    const TriangleMesh& mesh = world.shapes.at(0).mesh;
    ASSERT_TRUE(mesh.deforms());
    EXPECT_EQ(mesh.laterPositions[1][1], Vec3(2, 0, 2));  // moved by the transform
    EXPECT_EQ(mesh.laterNormals.size(), 2u);              // smooth normals at every keyframe
    EXPECT_EQ(mesh.positionAt(1, 0.25f), Vec3(1, 0, 2.5f));
    EXPECT_TRUE(world.hasMotion());
    const auto error = [&](const std::string& shape) {
        return test::errorMessage([&] {
            parseSceneText(R"({"shapes": [)" + shape + "]}", test::scratchDir("deform") / "scene.json");
        });
    };
    const std::string tri = R"({"type": "mesh", "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [0, 1, 2], )";
    EXPECT_TRUE(test::contains(error(tri + R"("deform": [[[0, 0, 0], [1, 0, 0]]]})"),
                               "/shapes/0/deform/0: expected 3 positions (as many as 'positions'), got 2"));
    EXPECT_TRUE(test::contains(error(tri + R"("deform": []})"), "/shapes/0/deform: expected an array of 1 to 128 keyframes of the positions (after 'positions'), got 0"));
    EXPECT_TRUE(test::contains(error(tri + R"("deform": [[[0, 0, 0], [1, 0, 0], [0, 1, "x"]]]})"), "/shapes/0/deform/0/2"));
    EXPECT_TRUE(test::contains(error(tri + R"("normals": [[0, 0, 1], [0, 0, 1], [0, 0, 1]], "deform": [[[0, 0, 0], [1, 0, 0], [0, 1, 0]]]})"),
                               "/shapes/0/normals: a deforming mesh's normals follow it"));
    EXPECT_TRUE(test::contains(error(R"({"type": "mesh", "file": "a.obj", "deform": []})"),
                               "only for inline meshes (with 'positions'), not with 'file'"));
}

}  // namespace
}  // namespace strahl
