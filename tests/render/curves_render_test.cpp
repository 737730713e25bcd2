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
SceneDesc curveSceneWith(const std::string& shape) {
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

TEST(CurvesRender, AStraightRoundCurveLooksLikeACylinder) {
    const std::vector<float> curve = test::renderBeauty(curveSceneWith(R"(
        {"type": "curves", "basis": "bezier", "radius": 0.4,
         "points": [[0, 0, -1], [0, 0, -0.3], [0, 0, 0.3], [0, 0, 1]]})"));
    const std::vector<float> cylinder = test::renderBeauty(curveSceneWith(R"(
        {"type": "parametric", "mode": "direct",
         "surface": {"type": "cylinder", "radius": 0.4, "z_min": -1, "z_max": 1}})"));
    ASSERT_EQ(curve.size(), cylinder.size());
    // Only the silhouette and the open ends' rims may differ (Embree's curve
    // is float Newton on a sweep, the cylinder double Newton on a patch).
    EXPECT_LT(test::differingPixels(curve, cylinder), 0.01);
    EXPECT_GT(test::channelSum(curve), 0.0);
}

TEST(CurvesRender, AStraightOrientedRibbonLooksLikeARectangle) {
    // Across n x C' = (0, -1, 0) x (0, 0, 1) = -x: a 0.8-wide band facing the camera.
    const std::vector<float> ribbon = test::renderBeauty(curveSceneWith(R"(
        {"type": "curves", "basis": "bezier", "profile": "oriented", "radius": 0.4,
         "points": [[0, 0, -1], [0, 0, -0.3], [0, 0, 0.3], [0, 0, 1]],
         "normals": [[0, -1, 0], [0, -1, 0], [0, -1, 0], [0, -1, 0]]})"));
    const std::vector<float> rectangle = test::renderBeauty(curveSceneWith(R"(
        {"type": "mesh", "positions": [[-0.4, 0, -1], [0.4, 0, -1], [0.4, 0, 1], [-0.4, 0, 1]],
         "indices": [0, 1, 2, 0, 2, 3]})"));
    ASSERT_EQ(ribbon.size(), rectangle.size());
    EXPECT_LT(test::differingPixels(ribbon, rectangle), 0.005);
    EXPECT_GT(test::channelSum(ribbon), 0.0);
}

TEST(CurvesRender, TheNaiveTracerRendersTheSameCurves) {
    for (const std::string profile : {"round", "flat", "oriented"}) {
        // Oriented ribbons lie across normals that turn a little along them.
        const std::string normals =
            profile != "oriented" ? ""
                                  : R"(, "normals": [[0, -1, 0], [0, -1, 0.2], [0.1, -1, 0], [0, -1, -0.2], [0, -1, 0],
                                                   [0, -1, 0], [0.3, -1, 0], [0, -1, 0], [0, -1, 0.3]])";
        std::string shape = R"({"type": "curves", "basis": "bspline", "profile": "PROFILE",
             "points": [[-1, 0, -1, 0.1], [-0.5, 0.3, -0.4, 0.12], [0.4, -0.2, 0, 0.1], [0.6, 0.2, 0.5, 0.08],
                        [0.1, 0, 1, 0.05], [0.5, 0, -1, 0.1], [0.8, 0, 0, 0.1], [0.5, 0, 0.8, 0.1], [0.9, 0, 1, 0.1]],
             "strands": [5, 4]NORMALS})";
        shape.replace(shape.find("PROFILE"), 7, profile);
        shape.replace(shape.find("NORMALS"), 7, normals);
        const SceneDesc desc = curveSceneWith(shape);
        const std::vector<float> embree = test::renderBeauty(desc);
        const std::vector<float> naive = test::renderFilm(desc, {.accel = AccelKind::Naive}).resolveBeauty();
        EXPECT_LT(test::differingPixels(embree, naive), 0.005) << profile;
    }
}

}  // namespace
}  // namespace strahl

namespace strahl {
namespace {

// A white furnace: lossless hair on round and flat curves inside a uniform
// white sky. Every path's weight is 1 at every bounce, so the image is 1 —
// unless the integrator ended paths that leave a flat ribbon on the "wrong"
// side of its bent shading normal (it once did: 0.4 % dark).
TEST(CurvesRender, LosslessHairInAWhiteFurnaceIsInvisible) {
    for (const char* profile : {"round", "flat"}) {
        const SceneDesc desc = parseSceneText(std::string(R"({
          "camera": {"eye": [0, -4, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 30},
          "film": {"width": 48, "height": 48},
          "render": {"integrator": "path", "spp": 64, "max_depth": 12, "russian_roulette": false},
          "background": 1,
          "materials": [{"name": "white hair", "type": "hair", "sigma_a": 0, "beta_m": 0.3, "beta_n": 0.4}],
          "shapes": [{"type": "curves", "material": "white hair", "basis": "bspline", "profile": ")") + profile + R"(",
            "points": [[-1, 0, -1, 0.2], [-0.3, 0.2, -0.3, 0.25], [0.3, -0.2, 0.3, 0.25], [1, 0, 1, 0.2],
                       [-1, 0.3, 1, 0.15], [-0.2, 0, 0.2, 0.2], [0.2, 0.1, -0.2, 0.2], [1, 0.3, -1, 0.15]],
            "strands": [4, 4]}]
        })",
                                              "furnace.json");
        const std::vector<float> image = test::renderBeauty(desc);
        double sum = 0.0, lowest = 1.0;
        for (float v : image) {
            sum += v;
            lowest = std::min(lowest, double(v));
        }
        EXPECT_NEAR(sum / double(image.size()), 1.0, 2e-3) << profile;
        // Next-event estimation and MIS make single pixels noisy (64 spp).
        EXPECT_GT(lowest, 0.9) << profile;
    }
}

// A lossless round fibre lit from behind, seen from the front by the direct
// integrator: the light reaches the camera through the fibre (TT). A shadow
// ray leaving where the camera ray hit would cross the fibre and be blocked
// by its far wall (measured: the image 2400 times darker); leaving from the
// side facing the light (ShadingContext::spawnTo) it is not.
TEST(CurvesRender, LightShinesThroughABacklitFibre) {
    const SceneDesc desc = parseSceneText(R"({
      "camera": {"eye": [0, -4, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 20},
      "film": {"width": 32, "height": 32},
      "render": {"integrator": "direct", "spp": 4},
      "materials": [{"name": "white hair", "type": "hair", "sigma_a": 0}],
      "shapes": [{"type": "curves", "material": "white hair", "basis": "bezier", "radius": 0.3,
        "points": [[0, 0, -1], [0, 0, -0.3], [0, 0, 0.3], [0, 0, 1]]}],
      "lights": [{"type": "directional", "direction": [0.1, -1, 0], "irradiance": 1}]
    })",
                                          "backlit.json");
    const std::vector<float> image = test::renderBeauty(desc);
    EXPECT_GT(test::channelSum(image) / double(image.size()), 0.3);  // measured 0.59
}

}  // namespace
}  // namespace strahl
