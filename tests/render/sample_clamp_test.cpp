// Sample clamping (render.clamp_direct / clamp_indirect, Cycles' firefly
// control; path_integrator.cpp): off by default and then not touching the
// image at all; on, every sample's direct or indirect light is capped, so no
// pixel gets brighter and the light a clamp cuts is the light it is meant to.

#include <gtest/gtest.h>

#include <string>

#include "render_helpers.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

// A small, bright area light over a white floor and a red wall, seen from
// above: direct light of high variance, and indirect light off the wall.
SceneDesc roomWith(const std::string& render) {
    return parseSceneText(R"({
      "camera": { "eye": [0, 2, 3], "look_at": [0, 0, 0], "fov": 50 },
      "film": { "width": 12, "height": 8 },
      "render": { "integrator": "path", "spp": 32)" + render + R"( },
      "materials": [ { "name": "white", "color": 0.8 }, { "name": "red", "color": [0.8, 0.1, 0.1] },
                     { "name": "lamp", "type": "emissive", "emission": 400 } ],
      "shapes": [
        { "type": "mesh", "material": "white", "positions": [[-2,0,-2],[2,0,-2],[2,0,2],[-2,0,2]],
          "indices": [0, 2, 1, 0, 3, 2] },
        { "type": "mesh", "material": "red", "positions": [[-2,0,-2],[-2,0,2],[-2,2,2],[-2,2,-2]],
          "indices": [0, 1, 2, 0, 2, 3] },
        { "type": "mesh", "material": "lamp", "positions": [[-0.1,1.5,-0.1],[0.1,1.5,-0.1],[0.1,1.5,0.1],[-0.1,1.5,0.1]],
          "indices": [0, 1, 2, 0, 2, 3] } ]
    })", test::scratchDir("clamp") / "room.json");
}

// The room with 4 bounces unless `render` says otherwise.
SceneDesc room(const std::string& render) {
    return roomWith(render.find("max_depth") == std::string::npos ? R"(, "max_depth": 4)" + render
                                                                  : render);
}


TEST(SampleClamp, ZeroIsOffAndLeavesTheImageBitForBit) {
    const std::vector<float> plain = test::renderBeauty(room(""));
    EXPECT_EQ(plain, test::renderBeauty(room(R"(, "clamp_direct": 0, "clamp_indirect": 0)")));
}

TEST(SampleClamp, AClampNeverBrightensAPixelAndCutsTheLightItNames) {
    const std::vector<float> plain = test::renderBeauty(room(""));
    const std::vector<float> direct = test::renderBeauty(room(R"(, "clamp_direct": 0.5)"));
    const std::vector<float> indirect = test::renderBeauty(room(R"(, "clamp_indirect": 0.05)"));
    ASSERT_EQ(plain.size(), direct.size());
    for (size_t i = 0; i < plain.size(); ++i) {
        // Clamping only scales samples down (the sums are added in another
        // order, hence the rounding allowance).
        EXPECT_LE(direct[i], plain[i] * (1.0f + 1e-5f) + 1e-6f) << i;
        EXPECT_LE(indirect[i], plain[i] * (1.0f + 1e-5f) + 1e-6f) << i;
    }
    EXPECT_LT(test::channelSum(direct), 0.9 * test::channelSum(plain));
    EXPECT_LT(test::channelSum(indirect), test::channelSum(plain));
    // With one bounce only (direct light), an indirect clamp has nothing to cut.
    const std::vector<float> oneBounce = test::renderBeauty(room(R"(, "max_depth": 1)"));
    const std::vector<float> oneBounceClamped =
        test::renderBeauty(room(R"(, "max_depth": 1, "clamp_indirect": 0.05)"));
    for (size_t i = 0; i < oneBounce.size(); ++i)
        EXPECT_FLOAT_EQ(oneBounceClamped[i], oneBounce[i]) << i;
}

TEST(SampleClamp, NegativeClampsAreRefusedWithTheirPlace) {
    EXPECT_TRUE(test::contains(test::errorMessage([] { room(R"(, "clamp_direct": -1)"); }),
                               "/render/clamp_direct: must be non-negative (0: off), got -1"));
}

}  // namespace
}  // namespace strahl
