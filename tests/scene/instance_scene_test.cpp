// Groups and instances in scene files (docs/scene-format.md, "Groups and
// instances"): parsed, flattened into one level of instances with composed
// transforms, each reached group stored once, unreached groups not loaded; and
// the exact message of every class of bad input — unknown and duplicate names,
// empty groups, cycles, nesting too deep, too many instances.

#include <gtest/gtest.h>

#include <string>

#include "scene_test_helpers.h"
#include "strahl/core/error.h"
#include "strahl/core/transform.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

using test::contains;
using test::kTriangleShape;
using test::parseError;
using test::parseJson;

const std::string kSphere =
    R"({"type": "implicit", "surface": {"type": "sphere", "radius": 0.5}})";

// "leaf": a triangle. "pair": a sphere of its own and two leaves at x = ±1.
// "unused": never placed. Top level: pair at y = 0 and y = 5, a leaf at z = 3.
const std::string kNested = R"({
  "groups": [
    { "name": "pair", "shapes": [ )" + kSphere + R"(,
        { "type": "instance", "group": "leaf", "transform": [ { "translate": [-1, 0, 0] } ] },
        { "type": "instance", "group": "leaf", "transform": [ { "translate": [1, 0, 0] } ] } ] },
    { "name": "leaf", "shapes": [ )" + kTriangleShape + R"( ] },
    { "name": "unused", "shapes": [ )" + kTriangleShape + R"( ] }
  ],
  "shapes": [
    { "type": "instance", "name": "low", "group": "pair" },
    { "type": "instance", "group": "pair", "transform": [ { "translate": [0, 5, 0] } ] },
    { "type": "instance", "group": "leaf", "transform": [ { "scale": 2 }, { "translate": [0, 0, 3] } ] },
    )" + kTriangleShape + R"(
  ]
})";

TEST(InstanceScene, ParsesGroupsAndInstanceShapes) {
    const SceneDesc desc = parseJson(kNested);
    ASSERT_EQ(desc.groups.size(), 3u);
    EXPECT_EQ(desc.groups[0].name, "pair");
    EXPECT_EQ(desc.groups[0].where, "/groups/0");
    ASSERT_EQ(desc.groups[0].shapes.size(), 3u);
    EXPECT_EQ(desc.groups[0].shapes[0].kind, ShapeKind::Implicit);
    EXPECT_EQ(desc.groups[0].shapes[1].kind, ShapeKind::Instance);
    EXPECT_EQ(desc.groups[0].shapes[1].group, 1u);  // "leaf", defined after "pair"
    EXPECT_EQ(desc.groups[0].shapes[1].where, "/groups/0/shapes/1");
    ASSERT_EQ(desc.shapes.size(), 4u);
    EXPECT_EQ(desc.shapes[0].kind, ShapeKind::Instance);
    EXPECT_EQ(desc.shapes[0].name, "low");
    EXPECT_EQ(desc.shapes[1].name, "/shapes/1");
    EXPECT_EQ(desc.shapes[2].group, 1u);
    EXPECT_EQ(transformPoint(desc.shapes[2].transform, Vec3(1, 1, 1)), Vec3(2, 2, 5));
}

TEST(InstanceScene, NestedGroupsAreFlattenedWithComposedTransforms) {
    const World world = buildWorld(parseJson(kNested), BuildOptions{});
    ASSERT_EQ(world.shapes.size(), 1u);  // the top-level triangle
    // "pair" (own shapes: the sphere) and "leaf"; "unused" is not built.
    ASSERT_EQ(world.prototypes.size(), 2u);
    EXPECT_EQ(world.prototypes[0].name, "pair");
    EXPECT_EQ(world.prototypes[1].name, "leaf");
    ASSERT_EQ(world.prototypes[0].shapes.size(), 1u);
    EXPECT_NE(world.prototypes[0].shapes[0].user, nullptr);
    ASSERT_EQ(world.prototypes[1].shapes.size(), 1u);
    EXPECT_EQ(world.prototypes[1].shapes[0].mesh.triangleCount(), 1u);

    // Depth first in scene order: pair's sphere, its two leaves; again at y = 5;
    // then the scaled leaf.
    ASSERT_EQ(world.instances.size(), 7u);
    const uint32_t expectedPrototype[] = {0, 1, 1, 0, 1, 1, 1};
    const Vec3 expectedOrigin[] = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, 5, 0},
                                   {-1, 5, 0}, {1, 5, 0}, {0, 0, 3}};
    for (size_t k = 0; k < 7; ++k) {
        SCOPED_TRACE(k);
        EXPECT_EQ(world.instances[k].prototype, expectedPrototype[k]);
        EXPECT_EQ(transformPoint(world.instances[k].objectToWorld, Vec3(0.0f)), expectedOrigin[k]);
        EXPECT_EQ(transformPoint(world.instances[k].worldToObject, expectedOrigin[k]), Vec3(0.0f));
    }
    EXPECT_EQ(transformPoint(world.instances[6].objectToWorld, Vec3(1, 0, 0)), Vec3(2, 0, 3));

    EXPECT_EQ(world.triangleCount(), 2u);           // stored: the top one and the leaf
    EXPECT_EQ(world.instancedTriangleCount(), 6u);  // rendered: 1 + 5 leaves
    const Bounds3 b = world.bounds();
    EXPECT_LE(b.max.y, 6.0f + 1e-4f);  // the upper leaves reach y = 5 + 1
    EXPECT_GE(b.max.y, 6.0f);
    EXPECT_LE(b.min.x, -1.0f);
    EXPECT_GE(b.max.z, 3.0f);
}

TEST(InstanceScene, ATopLevelSceneOfInstancesOnlyRenders) {
    const std::string text = R"({"groups": [{"name": "g", "shapes": [)" + kTriangleShape +
                             R"(]}], "shapes": [{"type": "instance", "group": "g"}]})";
    const World world = buildWorld(parseJson(text), BuildOptions{});
    EXPECT_TRUE(world.shapes.empty());
    ASSERT_EQ(world.instances.size(), 1u);
    Ray ray;
    ray.origin = Vec3(0.2f, 0.2f, 1.0f);
    ray.dir = Vec3(0.0f, 0.0f, -1.0f);
    const Hit hit = world.accel->intersect(ray);
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.instID, 0u);  // no top-level shapes: instance 0 has ID 0
    EXPECT_EQ(hit.geomID, 0u);
    EXPECT_FLOAT_EQ(hit.t, 1.0f);
    EXPECT_EQ(&world.shape(hit), &world.prototypes[0].shapes[0]);
}

TEST(InstanceScene, BadGroupsNameThePlace) {
    const std::string tri = kTriangleShape;
    auto scene = [](const std::string& groups, const std::string& shapes) {
        return R"({"groups": [)" + groups + R"(], "shapes": [)" + shapes + "]}";
    };
    const std::string placeA = R"({"type": "instance", "group": "a"})";

    EXPECT_EQ(parseError(scene(R"({"name": "a", "shapes": [)" + tri + "]}",
                               R"({"type": "instance", "group": "b"})")),
              "scene.json: /shapes/0/group: unknown group 'b' (defined: a)");
    EXPECT_EQ(parseError(R"({"shapes": [{"type": "instance", "group": "b"}]})"),
              "scene.json: /shapes/0/group: unknown group 'b' (defined: none)");
    EXPECT_EQ(parseError(scene(R"({"name": "a", "shapes": [)" + tri +
                                   R"(]}, {"name": "a", "shapes": [)" + tri + "]}",
                               placeA)),
              "scene.json: /groups/1/name: group 'a' is already defined at /groups/0");
    EXPECT_EQ(parseError(scene(R"({"name": "", "shapes": [)" + tri + "]}", placeA)),
              "scene.json: /groups/0/name: must not be empty");
    EXPECT_EQ(parseError(scene(R"({"name": "a", "shapes": []})", placeA)),
              "scene.json: /groups/0/shapes: a group needs at least one shape");
    EXPECT_TRUE(contains(
        parseError(scene(R"({"name": "a", "shapes": [)" + tri + R"(], "color": 1})", placeA)),
        "scene.json: /groups/0: unknown key 'color'"));
    EXPECT_TRUE(
        contains(parseError(scene(R"({"name": "a", "shapes": [)" + tri + "]}",
                                  R"({"type": "instance", "group": "a", "material": "default"})")),
                 "scene.json: /shapes/0: unknown key 'material'"));
}

TEST(InstanceScene, CyclesAreRejectedWithTheChain) {
    const std::string self = R"({"groups": [{"name": "a", "shapes": [{"type": "instance", "group": "a"}]}],
                                 "shapes": [{"type": "instance", "group": "a"}]})";
    EXPECT_EQ(parseError(self), "scene.json: /groups/0: group 'a' places itself (a -> a)");

    const std::string twoStep = R"({"groups": [
        {"name": "a", "shapes": [{"type": "instance", "group": "b"}]},
        {"name": "b", "shapes": [)" + kTriangleShape + R"(, {"type": "instance", "group": "a"}]}],
      "shapes": [)" + kTriangleShape + "]}";
    // Found even when no top-level shape places the cycle.
    EXPECT_EQ(parseError(twoStep), "scene.json: /groups/0: group 'a' places itself (a -> b -> a)");
}

// Groups g0 ... g{n-1}, each placing the next `fanOut` times; g{n-1} holds a
// triangle. The top level places g0 once.
std::string chain(int n, int fanOut) {
    std::string groups;
    for (int i = 0; i < n; ++i) {
        std::string shapes;
        if (i + 1 == n) {
            shapes = kTriangleShape;
        } else {
            for (int k = 0; k < fanOut; ++k) {
                shapes += (k ? ", " : "") + std::string(R"({"type": "instance", "group": "g)") +
                          std::to_string(i + 1) + R"(", "transform": [{"translate": [)" +
                          std::to_string(k) + ", 0, 0]}]}";
            }
        }
        groups += (i ? ", " : "") + std::string(R"({"name": "g)") + std::to_string(i) +
                  R"(", "shapes": [)" + shapes + "]}";
    }
    return R"({"groups": [)" + groups + R"(], "shapes": [{"type": "instance", "group": "g0"}]})";
}

TEST(InstanceScene, NestingDepthIsLimited) {
    EXPECT_NO_THROW(parseJson(chain(kMaxGroupNesting, 1)));
    EXPECT_EQ(parseError(chain(kMaxGroupNesting + 1, 1)),
              "scene.json: /groups/64: groups nest more than 64 levels deep");
}

TEST(InstanceScene, TooManyInstancesAreRefusedBeforeAllocating) {
    // 16^7 = 2^28 leaf placements, more than the 2^24 limit.
    const SceneDesc desc = parseJson(chain(8, 16));
    EXPECT_EQ(test::errorMessage([&] { buildWorld(desc, BuildOptions{}); }),
              "scene.json: the groups place more than 16777216 instances (the limit, 2^24)");
    // 16^3 = 4096 is fine, and each is placed once at its composed position.
    const World world = buildWorld(parseJson(chain(4, 16)), BuildOptions{});
    EXPECT_EQ(world.instances.size(), 4096u);
    EXPECT_EQ(world.prototypes.size(), 1u);
    EXPECT_EQ(transformPoint(world.instances.back().objectToWorld, Vec3(0.0f)), Vec3(45, 0, 0));
}

TEST(InstanceScene, AGroupsShapeErrorNamesItsPointer) {
    const std::string text = R"({"groups": [{"name": "g", "shapes": [
        {"type": "implicit", "surface": {"type": "gyroid", "scale": 1}}]}],
      "shapes": [{"type": "instance", "group": "g"}]})";
    EXPECT_TRUE(contains(parseError(text), "/groups/0/shapes/0")) << parseError(text);
}

}  // namespace
}  // namespace strahl
