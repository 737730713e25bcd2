// Curves rendered (geometry/curve_set.h, docs/geometry.md): a straight round
// curve is a cylinder — its image matches a parametric cylinder's — and the
// naive tracer renders the same curves as Embree.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "render_helpers.h"
#include "strahl/scene/scene_desc.h"

namespace strahl {
namespace {

// A camera looking at a vertical shape from the side, lit by a point light,
// on a floor, with `shape` (a JSON object) the only other shape.
SceneDesc sceneWith(const std::string& shape) {
    return parseSceneText(R"({
      "camera": {"eye": [0, -4, 0.6], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 40},
      "film": {"width": 64, "height": 64},
      "render": {"integrator": "direct", "spp": 1},
      "materials": [{"name": "grey", "color": 0.6}],
      "shapes": [
        {"type": "mesh", "material": "grey", "positions": [[-3, -3, -1.2], [3, -3, -1.2], [3, 3, -1.2], [-3, 3, -1.2]],
         "indices": [0, 1, 2, 0, 2, 3]},
        )" + shape + R"(],
      "lights": [{"type": "point", "position": [2, -3, 3], "intensity": 30}]
    })",
                          "curves.json");
}

// Fraction of pixels whose beauty differs by more than 2 % of the brightest.
double differingPixels(const std::vector<float>& a, const std::vector<float>& b) {
    float peak = 0.0f;
    for (float v : a) peak = std::max(peak, v);
    int differing = 0;
    for (size_t i = 0; i < a.size(); i += 3) {
        const float d = std::abs(a[i] - b[i]) + std::abs(a[i + 1] - b[i + 1]) + std::abs(a[i + 2] - b[i + 2]);
        if (d > 0.02f * peak) ++differing;
    }
    return double(differing) / double(a.size() / 3);
}

TEST(CurvesRender, AStraightRoundCurveLooksLikeACylinder) {
    const std::vector<float> curve = test::renderBeauty(sceneWith(R"(
        {"type": "curves", "basis": "bezier", "radius": 0.4,
         "points": [[0, 0, -1], [0, 0, -0.3], [0, 0, 0.3], [0, 0, 1]]})"));
    const std::vector<float> cylinder = test::renderBeauty(sceneWith(R"(
        {"type": "parametric", "mode": "direct",
         "surface": {"type": "cylinder", "radius": 0.4, "z_min": -1, "z_max": 1}})"));
    ASSERT_EQ(curve.size(), cylinder.size());
    // Only the silhouette and the open ends' rims may differ (Embree's curve
    // is float Newton on a sweep, the cylinder double Newton on a patch).
    EXPECT_LT(differingPixels(curve, cylinder), 0.01);
    EXPECT_GT(test::channelSum(curve), 0.0);
}

TEST(CurvesRender, TheNaiveTracerRendersTheSameCurves) {
    for (const char* profile : {"round", "flat"}) {
        const SceneDesc desc = sceneWith(std::string(R"(
            {"type": "curves", "basis": "bspline", "profile": ")") + profile + R"(",
             "points": [[-1, 0, -1, 0.1], [-0.5, 0.3, -0.4, 0.12], [0.4, -0.2, 0, 0.1], [0.6, 0.2, 0.5, 0.08],
                        [0.1, 0, 1, 0.05], [0.5, 0, -1, 0.1], [0.8, 0, 0, 0.1], [0.5, 0, 0.8, 0.1], [0.9, 0, 1, 0.1]],
             "strands": [5, 4]})");
        const std::vector<float> embree = test::renderBeauty(desc);
        const std::vector<float> naive = test::renderFilm(desc, {.accel = AccelKind::Naive}).resolveBeauty();
        EXPECT_LT(differingPixels(embree, naive), 0.005) << profile;
    }
}

}  // namespace
}  // namespace strahl
