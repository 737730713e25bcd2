// The two modes of a parametric surface render the same image: a torus and
// the teapot, once intersected directly and once finely tessellated with
// exact normals, through the whole shading stage.

#include <gtest/gtest.h>

#include <cmath>

#include "render_helpers.h"

namespace strahl {
namespace {

std::string scene(const std::string& mode) {
    const std::string settings =
        mode == "direct" ? R"("mode": "direct")" : R"("tessellation": {"max_error": 0.0002})";
    return R"({
      "camera": { "eye": [0, 1.9, 3.4], "look_at": [0, 0.45, 0], "fov": 45 },
      "film": { "width": 96, "height": 72 },
      "shapes": [
        { "type": "parametric", )" + settings + R"(,
          "surface": { "type": "torus", "major_radius": 0.6, "minor_radius": 0.25 },
          "transform": [ { "rotate": { "axis": [1, 0, 0], "angle": -60 } }, { "translate": [-1.1, 0.6, 0] } ] },
        { "type": "parametric", )" + settings + R"(,
          "surface": { "type": "bezier", "file": "data/teapot.bpt", "reverse": true },
          "transform": [ { "rotate": { "axis": [1, 0, 0], "angle": -90 } }, { "scale": 0.3 },
                         { "translate": [1.0, 0, 0] } ] }
      ],
      "lights": [ { "type": "point", "position": [-2, 5, 4], "intensity": 30 } ]
    })";
}

TEST(ParametricRender, DirectAndTessellatedImagesAgree) {
    const auto file = test::sourceDir() / "scenes" / "scene.json";
    const test::Rendered direct = test::render(parseSceneText(scene("direct"), file), AccelKind::Embree, "direct");
    const test::Rendered tessellated =
        test::render(parseSceneText(scene("tessellated"), file), AccelKind::Embree, "direct");
    ASSERT_EQ(direct.beauty.size(), tessellated.beauty.size());
    // Coverage: a pixel covered in one mode and not the other can only be on
    // a silhouette, where the chord cuts inside the surface.
    size_t covered = 0, coverageDiffers = 0, shadingDiffers = 0;
    double sumDifference = 0.0;
    for (size_t i = 0; i < direct.depth.size(); ++i) {
        const bool a = std::isfinite(direct.depth[i]) && direct.depth[i] > 0.0f;
        const bool b = std::isfinite(tessellated.depth[i]) && tessellated.depth[i] > 0.0f;
        covered += a;
        if (a != b) {
            ++coverageDiffers;
            continue;
        }
        if (!a) continue;
        for (int c = 0; c < 3; ++c) {
            const double d = std::abs(direct.beauty[3 * i + size_t(c)] - tessellated.beauty[3 * i + size_t(c)]);
            sumDifference += d;
            if (d > 0.02) ++shadingDiffers;
        }
    }
    ASSERT_GT(covered, 1000u);
    EXPECT_LE(coverageDiffers, covered / 200) << "more than 0.5% of the covered pixels";
    // Exact normals in both: the shading matches except where a shadow
    // terminator or silhouette falls differently.
    EXPECT_LE(shadingDiffers, covered / 100);
    EXPECT_LT(sumDifference / double(3 * covered), 2e-3);
}

}  // namespace
}  // namespace strahl
