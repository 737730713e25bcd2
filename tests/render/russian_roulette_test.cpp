// Russian roulette (render.russian_roulette, _depth, _threshold;
// path_integrator.cpp): a path continues with q = min(1, throughput /
// threshold). So a path whose throughput never falls below the threshold is
// never ended or reweighted, and draws no roulette sample: the image is the
// one without roulette, bit for bit. Below it roulette does play (a different
// image) and stays unbiased (the same mean within its noise).

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "render_helpers.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

// A light-grey floor and wall (albedo `albedo`, exactly each bounce's
// throughput factor with cosine sampling of a Lambert BSDF) under a point light.
SceneDesc corner(const std::string& render, float albedo) {
    return parseSceneText(R"({
      "camera": { "eye": [0, 2, 3], "look_at": [0, 0, 0], "fov": 50 },
      "film": { "width": 12, "height": 8 },
      "render": { "integrator": "path", "spp": 64, "max_depth": 3)" + render + R"( },
      "materials": [ { "name": "grey", "color": )" + std::to_string(albedo) + R"( } ],
      "shapes": [
        { "type": "mesh", "material": "grey", "positions": [[-2,0,-2],[2,0,-2],[2,0,2],[-2,0,2]],
          "indices": [0, 2, 1, 0, 3, 2] },
        { "type": "mesh", "material": "grey", "positions": [[-2,0,-2],[-2,0,2],[-2,2,2],[-2,2,-2]],
          "indices": [0, 1, 2, 0, 2, 3] } ],
      "lights": [ { "type": "point", "position": [0.5, 1.5, 0.5], "intensity": 3 } ]
    })", test::scratchDir("roulette") / "corner.json");
}

TEST(RussianRoulette, PathsAboveTheThresholdAreLeftAloneBitForBit) {
    // Albedo 0.9 and 3 bounces: the throughput stays >= 0.9^3 = 0.729, above
    // the default threshold 0.5, so the default roulette never plays here.
    const std::vector<float> off =
        test::renderBeauty(corner(R"(, "russian_roulette": false)", 0.9f));
    EXPECT_EQ(off, test::renderBeauty(corner("", 0.9f)));
    // pbrt-v4's rule (threshold 1) plays from the first bounce: not the same.
    EXPECT_NE(off, test::renderBeauty(corner(R"(, "russian_roulette_threshold": 1)", 0.9f)));
}

TEST(RussianRoulette, BelowTheThresholdItPlaysAndStaysUnbiased) {
    // Albedo 0.3: the throughput falls below 0.5 at the first bounce.
    const std::vector<float> off =
        test::renderBeauty(corner(R"(, "russian_roulette": false, "spp": 1024)", 0.3f));
    const std::vector<float> on = test::renderBeauty(corner(R"(, "spp": 1024)", 0.3f));
    EXPECT_NE(off, on);
    // The whole image's mean agrees to well within its noise (1024 spp x 96
    // pixels; the indirect light roulette touches is a small part of it).
    EXPECT_NEAR(test::channelMean(on), test::channelMean(off), 0.01 * test::channelMean(off));
}

TEST(RussianRoulette, ThresholdOutsideZeroToOneIsRefusedWithItsPlace) {
    for (const char* bad : {"0", "-0.5", "1.5"}) {
        const std::string text = std::string(R"(, "russian_roulette_threshold": )") + bad;
        EXPECT_TRUE(test::contains(test::errorMessage([&] { corner(text, 0.5f); }),
                                   "/render/russian_roulette_threshold: must be in (0, 1], got "))
            << bad;
    }
}

}  // namespace
}  // namespace strahl
