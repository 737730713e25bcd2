// Many-light sampling through the light BVH (render.light_selection "bvh"),
// rendered: a floor under a grid of small lamps, each point of which is lit
// mostly by the lamps just above it. Choosing lamps by power wastes most
// shadow rays on far lamps; the BVH chooses near ones. Both are unbiased, so
// their images agree in the mean, and the BVH's has far less variance.

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "render_helpers.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

using test::renderFilm;

// A 12 x 12 floor under 12 x 12 lamps (288 emissive triangles), 0.3 above
// it, facing down, seen from above at an angle.
SceneDesc lampGrid(const std::string& selection) {
    std::ostringstream lamps;
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j) {
            const float x = -5.5f + float(i), z = -5.5f + float(j), h = 0.1f;
            if (i + j > 0) lamps << ",";
            lamps << "[" << x - h << ",0.3," << z - h << "],[" << x + h << ",0.3," << z - h
                  << "],[" << x + h << ",0.3," << z + h << "],[" << x - h << ",0.3," << z + h << "]";
        }
    std::ostringstream indices;
    for (int k = 0; k < 144; ++k) {
        const int b = 4 * k;
        if (k > 0) indices << ",";
        // Wound so the front faces down (-y).
        indices << b << "," << b + 1 << "," << b + 2 << "," << b << "," << b + 2 << "," << b + 3;
    }
    return parseSceneText(R"({
      "camera": { "eye": [0, 6, 7], "look_at": [0, 0, 0], "fov": 60 },
      "film": { "width": 24, "height": 16 },
      "render": { "integrator": "path", "spp": 32, "max_depth": 1,
                  "light_selection": ")" + selection + R"(" },
      "materials": [ { "name": "grey", "color": 0.5 },
                     { "name": "lamp", "type": "emissive", "emission": 20 } ],
      "shapes": [
        { "type": "mesh", "material": "grey",
          "positions": [[-6,0,-6],[6,0,-6],[6,0,6],[-6,0,6]], "indices": [0, 2, 1, 0, 3, 2] },
        { "type": "mesh", "material": "lamp", "positions": [)" + lamps.str() + R"(],
          "indices": [)" + indices.str() + R"(] } ]
    })", test::scratchDir("light-bvh") / "lamps.json");
}

TEST(LightBvhRender, ManyLampsAgreeWithPowerSelectionWithFarLessVariance) {
    const auto render = [](const std::string& selection, const std::string& integrator, int spp) {
        return renderFilm(lampGrid(selection), {.aovs = {AovKind::Variance},
                                                .integrator = integrator,
                                                .threads = 2,
                                                .spp = spp});
    };
    const Film power = render("power", "path", 32), bvh = render("bvh", "path", 64);
    // The direct integrator samples every lamp at every hit: no choice, the
    // reference mean (the path tracer at max_depth 1 is direct light too).
    const Film all = render("power", "direct", 8);
    const double meanAll = test::channelMean(all.resolveBeauty()),
                 meanBvh = test::channelMean(bvh.resolveBeauty());
    ASSERT_GT(meanAll, 0.01);
    // The BVH render's own standard error is about 0.7 % here.
    EXPECT_NEAR(meanBvh / meanAll, 1.0, 0.03);
    EXPECT_NEAR(test::channelMean(power.resolveBeauty()) / meanAll, 1.0, 0.1);  // noisy: see below
    const double variancePower = test::channelMean(power.resolveAov(AovKind::Variance));
    // At equal samples: the 64-sample variance of the mean, times 2.
    const double varianceBvh = 2.0 * test::channelMean(bvh.resolveAov(AovKind::Variance));
    EXPECT_LT(varianceBvh, 0.25 * variancePower)
        << "variance of the mean: bvh " << varianceBvh << ", power " << variancePower;
}

TEST(LightBvhRender, TheSameImageForAnyThreadCountAndTileSize) {
    const SceneDesc desc = lampGrid("bvh");
    const Film one = renderFilm(desc, {.threads = 1, .tile = 32});
    const Film two = renderFilm(desc, {.threads = 2, .tile = 5});
    EXPECT_EQ(one.resolveBeauty(), two.resolveBeauty());
}

}  // namespace
}  // namespace strahl
