// Instance arrays (docs/scene-format.md, "Instance arrays"): one instance shape
// placing its group once per line of a placement file or per scattered point,
// flattened like any instance; and the exact message of each bad input.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "strahl/core/error.h"
#include "strahl/core/transform.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

const std::string kGroups =
    R"("groups": [{"name": "leaf", "shapes": [{"type": "mesh",
        "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [0, 1, 2]}]}])";

// A scene in `dir` whose one shape is an instance of "leaf" with `array` keys.
SceneDesc sceneWithArray(const fs::path& dir, const std::string& array) {
    const std::string text = "{" + kGroups + R"(, "shapes": [{"type": "instance", "group": "leaf", )" +
                             array + "}]}";
    return parseSceneText(text, dir / "scene.json");
}

std::string arrayError(const fs::path& dir, const std::string& array) {
    return test::errorMessage([&] { sceneWithArray(dir, array); });
}

TEST(InstanceArray, PlacementFileLinesBecomeInstancesInOrder) {
    const fs::path dir = test::scratchDir("instance-array-file");
    test::writeFile(dir / "forest.txt",
                    "# x y z [yaw [scale]] or a 3x4 matrix\n"
                    "1 0 0\n"
                    "\n"
                    "0 2 0 90   # a comment after a placement\n"
                    "0 0 3 0 2\n"
                    "1 0 0 10  0 1 0 20  0 0 1 30\n");
    const SceneDesc desc = sceneWithArray(
        dir, R"("placements": "forest.txt", "transform": [{"translate": [0, 100, 0]}])");
    ASSERT_EQ(desc.shapes[0].placements.size(), 4u);
    const World world = buildWorld(desc, BuildOptions{});
    ASSERT_EQ(world.instances.size(), 4u);
    ASSERT_EQ(world.prototypes.size(), 1u);
    const auto at = [&](size_t k, Vec3 p) { return transformPoint(world.instances[k].objectToWorld, p); };
    EXPECT_EQ(at(0, Vec3(0.0f)), Vec3(1, 100, 0));   // the array's transform applies after
    const Vec3 turned = at(1, Vec3(1, 0, 0));        // yaw 90: +x to -z
    EXPECT_NEAR(turned.x, 0.0f, 1e-6f);
    EXPECT_NEAR(turned.y, 102.0f, 1e-6f);
    EXPECT_NEAR(turned.z, -1.0f, 1e-6f);
    EXPECT_EQ(at(2, Vec3(1, 1, 1)), Vec3(2, 102, 5));  // scale 2, then (0, 0, 3)
    EXPECT_EQ(at(3, Vec3(0.0f)), Vec3(10, 120, 30));
    EXPECT_EQ(world.instancedTriangleCount(), 4u);
}

TEST(InstanceArray, ScatterIsDeterministicAndStaysInItsRectangle) {
    const fs::path dir = test::scratchDir("instance-array-scatter");
    const std::string scatter =
        R"("scatter": {"count": 500, "seed": 42, "min": [-10, -5], "max": [10, 5],
                       "height": 2, "yaw": [0, 360], "scale": [0.5, 1.5]})";
    const SceneDesc a = sceneWithArray(dir, scatter), b = sceneWithArray(dir, scatter);
    ASSERT_EQ(a.shapes[0].placements.size(), 500u);
    EXPECT_EQ(a.shapes[0].placements, b.shapes[0].placements);
    float minScale = 10.0f, maxScale = 0.0f;
    for (const Mat4& m : a.shapes[0].placements) {
        const Vec3 p = transformPoint(m, Vec3(0.0f));
        EXPECT_GE(p.x, -10.0f);
        EXPECT_LE(p.x, 10.0f);
        EXPECT_GE(p.z, -5.0f);
        EXPECT_LE(p.z, 5.0f);
        EXPECT_EQ(p.y, 2.0f);
        const float scale = glm::length(Vec3(m[1]));  // the y axis: untouched by the yaw
        minScale = std::min(minScale, scale);
        maxScale = std::max(maxScale, scale);
    }
    EXPECT_GE(minScale, 0.5f);
    EXPECT_LE(maxScale, 1.5f);
    EXPECT_LT(minScale, 0.6f);  // 500 draws cover the range
    EXPECT_GT(maxScale, 1.4f);
    const SceneDesc other = sceneWithArray(
        dir, R"("scatter": {"count": 500, "seed": 43, "min": [-10, -5], "max": [10, 5]})");
    EXPECT_NE(other.shapes[0].placements, a.shapes[0].placements);
}

TEST(InstanceArray, ArraysInsideGroupsMultiply) {
    const fs::path dir = test::scratchDir("instance-array-nested");
    const std::string text = R"({"groups": [
        {"name": "leaf", "shapes": [{"type": "mesh",
            "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [0, 1, 2]}]},
        {"name": "row", "shapes": [{"type": "instance", "group": "leaf",
            "scatter": {"count": 30, "min": [0, 0], "max": [1, 1]}}]}],
      "shapes": [{"type": "instance", "group": "row",
                  "scatter": {"count": 20, "min": [0, 0], "max": [100, 100]}}]})";
    const World world = buildWorld(parseSceneText(text, dir / "scene.json"), BuildOptions{});
    EXPECT_EQ(world.instances.size(), 600u);
    EXPECT_EQ(world.prototypes.size(), 1u);
    EXPECT_EQ(world.instancedTriangleCount(), 600u);
}

TEST(InstanceArray, TooManyPlacementsAreRefusedBeforeAllocating) {
    const fs::path dir = test::scratchDir("instance-array-limit");
    // 4,000 rows of 5,000 leaves: 2 * 10^7 > 2^24 instances, refused when
    // counted, before the flat list is allocated.
    const std::string text = R"({"groups": [
        {"name": "leaf", "shapes": [{"type": "mesh",
            "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [0, 1, 2]}]},
        {"name": "row", "shapes": [{"type": "instance", "group": "leaf",
            "scatter": {"count": 5000, "min": [0, 0], "max": [1, 1]}}]}],
      "shapes": [{"type": "instance", "group": "row",
                  "scatter": {"count": 4000, "min": [0, 0], "max": [100, 100]}}]})";
    const SceneDesc desc = parseSceneText(text, dir / "scene.json");
    EXPECT_EQ(test::errorMessage([&] { buildWorld(desc, BuildOptions{}); }),
              "scene.json: the groups place more than 16777216 instances (the limit, 2^24)");
    // One array alone cannot ask for more either (checked when parsed).
    EXPECT_THAT(arrayError(dir, R"("scatter": {"count": 16777217, "min": [0, 0], "max": [1, 1]})"),
                HasSubstr("/shapes/0/scatter/count"));
}

TEST(InstanceArray, BadPlacementFilesNameFileAndLine) {
    const fs::path dir = test::scratchDir("instance-array-bad");
    const struct {
        const char* text;
        const char* message;
    } cases[] = {
        {"1 2\n", "p.txt:1: 2 numbers; a placement is x y z [yaw [scale]] or 12 matrix entries"},
        {"1 2 3\n1 2 x\n", "p.txt:2: 'x' is not a number"},
        {"1 2 3 0 0\n", "p.txt:1: the scale 0 is not positive"},
        {"1 2 3 0 -1\n", "p.txt:1: the scale -1 is not positive"},
        {"0 0 0 0  0 0 0 0  0 0 1 0\n", "p.txt:1: the matrix is not invertible"},
        {"1 2 3 4 5 6 7 8 9 10 11 12 13\n", "p.txt:1: more than 12 numbers"},
        {"1 nan 3\n", "p.txt:1: number 2 is not finite"},
        {"# nothing\n\n", "p.txt: no placements in the file"},
    };
    for (const auto& c : cases) {
        test::writeFile(dir / "p.txt", c.text);
        const std::string message = arrayError(dir, R"("placements": "p.txt")");
        EXPECT_THAT(message, HasSubstr("scene.json: /shapes/0/placements: ")) << c.text;
        EXPECT_THAT(message, HasSubstr(c.message)) << c.text;
    }
    EXPECT_THAT(arrayError(dir, R"("placements": "missing.txt")"),
                HasSubstr("/shapes/0/placements"));
    EXPECT_THAT(arrayError(dir, R"("placements": "p.txt", "scatter": {"count": 1, "min": [0, 0], "max": [1, 1]})"),
                HasSubstr("give 'placements' or 'scatter', not both"));
    EXPECT_THAT(arrayError(dir, R"("scatter": {"count": 0, "min": [0, 0], "max": [1, 1]})"),
                HasSubstr("at least one placement"));
    EXPECT_THAT(arrayError(dir, R"("scatter": {"count": 3, "min": [0, 0], "max": [-1, 1]})"),
                HasSubstr("/shapes/0/scatter/max: must not be below 'min'"));
    EXPECT_THAT(arrayError(dir, R"("scatter": {"count": 3, "min": [0, 0], "max": [1, 1], "scale": [0, 1]})"),
                HasSubstr("/shapes/0/scatter/scale: expected [from, to] with 0 < from <= to"));
    EXPECT_THAT(arrayError(dir, R"("scatter": {"count": 3, "min": [0, 0], "max": [1, 1], "density": 2})"),
                HasSubstr("density"));
}

}  // namespace
}  // namespace strahl
