// Subdivision surfaces rendered (geometry/subdivision_surface.h,
// docs/geometry.md): the naive tracer renders the same displaced, creased
// surface of triangles, quads and pentagons as Embree's native subdivision;
// a cage with every vertex pinned renders as its bilinear patches, here the
// flat quads of a box; and the image does not depend on the thread count.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "render_helpers.h"
#include "strahl/scene/scene_desc.h"

namespace strahl {
namespace {

SceneDesc subdivisionSceneWith(const std::string& shape) {
    std::string text = R"({
      "camera": {"eye": [2.5, -4, 2], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 40},
      "film": {"width": 64, "height": 64},
      "render": {"integrator": "direct", "spp": 1},
      "materials": [{"name": "grey", "color": 0.6}],
      "shapes": [
        {"type": "mesh", "material": "grey", "positions": [[-3, -3, -1.6], [3, -3, -1.6], [3, 3, -1.6], [-3, 3, -1.6]],
         "indices": [0, 1, 2, 0, 2, 3]},
        )";
    text.append(shape).append(R"(],
      "lights": [{"type": "point", "position": [2, -3, 3], "intensity": 30}]
    })");
    return parseSceneText(text, "subdivision.json");
}

// A cube with a pyramid top and a pentagon front, a crease loop round its
// bottom and a wavy displacement.
constexpr const char* kMixedShape = R"json({"type": "subdivision", "levels": 4,
    "positions": [[-1,-1,-1],[1,-1,-1],[-1,1,-1],[1,1,-1],[-1,-1,1],[1,-1,1],[-1,1,1],[1,1,1],[0,0,1.6],[0,-1,0.3]],
    "faces": [[0,2,3,1],[4,5,8],[5,7,8],[7,6,8],[6,4,8],[0,1,5,9,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]],
    "creases": [[0,2,"inf"],[2,3,"inf"],[3,1,"inf"],[1,0,"inf"]],
    "displacement": {"formula": "0.04 * sin(9 * x) * sin(7 * z)"}})json";

TEST(SubdivisionRender, TheNaiveTracerRendersTheSameSurface) {
    const SceneDesc desc = subdivisionSceneWith(kMixedShape);
    const std::vector<float> embree = test::renderBeauty(desc);
    const std::vector<float> naive = test::renderBeauty(desc, {.accel = AccelKind::Naive});
    EXPECT_GT(test::channelSum(embree), 0.0);
    // Only pixels on the crease's silhouette may differ (Embree's points
    // next to an infinitely sharp crease approximate the limit).
    EXPECT_LT(test::differingPixels(embree, naive), 0.01);
}

TEST(SubdivisionRender, APinnedCageIsItsPolygons) {
    const std::vector<float> pinned = test::renderBeauty(subdivisionSceneWith(R"({"type": "subdivision", "levels": 2,
        "boundary": "pin_all",
        "positions": [[-1,-1,-1],[1,-1,-1],[-1,1,-1],[1,1,-1],[-1,-1,1],[1,-1,1],[-1,1,1],[1,1,1]],
        "faces": [[0,2,3,1],[4,5,7,6],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]]})"));
    const std::vector<float> box = test::renderBeauty(subdivisionSceneWith(R"({"type": "mesh",
        "positions": [[-1,-1,-1],[1,-1,-1],[-1,1,-1],[1,1,-1],[-1,-1,1],[1,-1,1],[-1,1,1],[1,1,1]],
        "indices": [0,2,3, 0,3,1, 4,5,7, 4,7,6, 0,1,5, 0,5,4, 2,6,7, 2,7,3, 0,4,6, 0,6,2, 1,3,7, 1,7,5]})"));
    // Flat faces shade alike; the shading normals differ only within a
    // refined cell of the box's edges (smoothed across them by the pinned
    // surface), a few pixels.
    EXPECT_LT(test::differingPixels(pinned, box), 0.03);
}

TEST(SubdivisionRender, ImagesDoNotDependOnTheThreadCount) {
    SceneDesc desc = subdivisionSceneWith(kMixedShape);
    desc.render.integrator = "path";
    desc.render.spp = 4;
    const std::vector<float> one = test::renderBeauty(desc, {.threads = 1, .tile = 16});
    const std::vector<float> two = test::renderBeauty(desc, {.threads = 2});
    EXPECT_EQ(one, two);
}

}  // namespace
}  // namespace strahl
