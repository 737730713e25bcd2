// Filter glossy (render.filter_glossy, Cycles' option; path_integrator.cpp):
// off by default and then not touching the image; on, a sharp mirror seen
// after a diffuse bounce turns rough, so light sampling finds the point light
// in it: the floor gets the light the mirror sends it (a caustic that plain
// path tracing cannot find from a point light) and the image brightens.

#include <gtest/gtest.h>

#include <string>

#include "render_helpers.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

// A white floor and a smooth mirror wall under a point light, seen from above.
SceneDesc mirrorCorner(const std::string& render) {
    return parseSceneText(R"({
      "camera": { "eye": [0, 2, 3], "look_at": [0, 0, 0], "fov": 50 },
      "film": { "width": 12, "height": 8 },
      "render": { "integrator": "path", "spp": 64, "max_depth": 3)" + render + R"( },
      "materials": [ { "name": "white", "color": 0.8 },
                     { "name": "mirror", "type": "conductor", "metal": "silver", "roughness": 0 } ],
      "shapes": [
        { "type": "mesh", "material": "white", "positions": [[-2,0,-2],[2,0,-2],[2,0,2],[-2,0,2]],
          "indices": [0, 2, 1, 0, 3, 2] },
        { "type": "mesh", "material": "mirror", "positions": [[-2,0,-2],[-2,0,2],[-2,2,2],[-2,2,-2]],
          "indices": [0, 1, 2, 0, 2, 3] } ],
      "lights": [ { "type": "point", "position": [-1, 1, 0], "intensity": 3 } ]
    })", test::scratchDir("filter-glossy") / "corner.json");
}

TEST(FilterGlossy, ZeroIsOffAndLeavesTheImageBitForBit) {
    EXPECT_EQ(test::renderBeauty(mirrorCorner("")),
              test::renderBeauty(mirrorCorner(R"(, "filter_glossy": 0)")));
}

TEST(FilterGlossy, AMirrorSeenAfterADiffuseBounceBringsThePointLight) {
    const std::vector<float> plain = test::renderBeauty(mirrorCorner(""));
    const std::vector<float> filtered =
        test::renderBeauty(mirrorCorner(R"(, "filter_glossy": 1)"));
    // The mirrored light: an image of the point light as bright again, spread
    // over the floor; the whole image gains at least a tenth.
    EXPECT_GT(test::channelSum(filtered), 1.1 * test::channelSum(plain));
}

TEST(FilterGlossy, NegativeValuesAreRefusedWithTheirPlace) {
    EXPECT_TRUE(test::contains(
        test::errorMessage([] { mirrorCorner(R"(, "filter_glossy": -1)"); }),
        "/render/filter_glossy: must be non-negative (0: off), got -1"));
}

}  // namespace
}  // namespace strahl
