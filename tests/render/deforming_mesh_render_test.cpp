// Deforming meshes rendered (`"deform"` keyframes of an inline mesh,
// docs/geometry.md "Motion blur"): the image is the average of still frames
// over the shutter, a closed shutter renders the mesh at rest where that
// instant puts it (its shadow too), and the naive tracer renders the same
// blur as Embree.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "render_helpers.h"
#include "strahl/scene/scene_desc.h"

namespace strahl {
namespace {

// A tent of four triangles whose apex swings from left to right and whose
// base widens (two keyframes after the first), over a floor under a point
// light, seen through `shutter`. `tent` may replace the tent's mesh keys.
SceneDesc tentScene(const std::string& shutter, const std::string& tent = "") {
    std::string text = R"({
      "camera": {"eye": [0, -4, 2.2], "look_at": [0, 0, 0.2], "up": [0, 0, 1], "fov": 38, "shutter": SHUTTER},
      "film": {"width": 48, "height": 36},
      "render": {"integrator": "direct", "spp": 1},
      "materials": [{"name": "grey", "color": 0.6}, {"name": "red", "color": [0.8, 0.2, 0.1]}],
      "shapes": [
        {"type": "mesh", "material": "grey", "positions": [[-4, -4, -0.45], [4, -4, -0.45], [4, 4, -0.45], [-4, 4, -0.45]],
         "indices": [0, 1, 2, 0, 2, 3]},
        {"type": "mesh", "material": "red", "indices": [0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4], "normals": "smooth",
         TENT}],
      "lights": [{"type": "point", "position": [1, -2, 4], "intensity": 40}]
    })";
    const std::string keys = tent.empty() ? R"("positions": [[-0.6, -0.6, -0.4], [0.6, -0.6, -0.4], [0.6, 0.6, -0.4], [-0.6, 0.6, -0.4], [-0.8, 0, 0.8]],
         "deform": [[[-0.8, -0.6, -0.4], [0.8, -0.6, -0.4], [0.8, 0.6, -0.4], [-0.8, 0.6, -0.4], [0, -0.2, 1.0]],
                    [[-0.6, -0.7, -0.4], [0.6, -0.7, -0.4], [0.6, 0.7, -0.4], [-0.6, 0.7, -0.4], [0.8, 0, 0.6]]])"
                                          : tent;
    text.replace(text.find("SHUTTER"), 7, shutter);
    text.replace(text.find("TENT"), 4, keys);
    return parseSceneText(text, "deform.json");
}

double meanAbsDifference(const std::vector<float>& a, const std::vector<float>& b, double& peak) {
    double sum = 0.0;
    peak = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        sum += std::abs(a[i] - b[i]);
        peak = std::max(peak, double(std::max(a[i], b[i])));
    }
    return sum / double(a.size());
}

TEST(DeformingMeshRender, TheImageIsTheAverageOfItsStillFrames) {
    constexpr int kFrames = 24, kFrameSpp = 32;
    const std::vector<float> image = test::renderBeauty(tentScene("[0, 1]"), {.spp = kFrames * kFrameSpp});
    std::vector<float> average(image.size(), 0.0f);
    for (int k = 0; k < kFrames; ++k) {
        const std::string t = std::to_string((float(k) + 0.5f) / float(kFrames));
        const std::vector<float> still = test::renderBeauty(tentScene("[" + t + ", " + t + "]"), {.spp = kFrameSpp});
        for (size_t i = 0; i < still.size(); ++i) average[i] += still[i] / float(kFrames);
    }
    double peak = 0.0;
    const double d = meanAbsDifference(image, average, peak);
    EXPECT_LT(d, 0.004 * peak);
    const std::vector<float> first = test::renderBeauty(tentScene("[0, 0]"), {.spp = kFrameSpp});
    const double fromFirst = meanAbsDifference(image, first, peak);
    EXPECT_GT(fromFirst, 5 * d);
}

TEST(DeformingMeshRender, ClosedShutterRendersTheMeshWhereThatInstantPutsIt) {
    // Halfway through the first segment (time 0.25): the average of
    // keyframes 0 and 1. Smooth normals are computed per keyframe and
    // interpolated, so they differ from the still mesh's own by rounding.
    const std::vector<float> moving = test::renderBeauty(tentScene("[0.25, 0.25]"), {.spp = 4});
    const std::vector<float> still = test::renderBeauty(tentScene("[0, 1]",
        R"("positions": [[-0.7, -0.6, -0.4], [0.7, -0.6, -0.4], [0.7, 0.6, -0.4], [-0.7, 0.6, -0.4], [-0.4, -0.1, 0.9]])"),
        {.spp = 4});
    double peak = 0.0;
    const double d = meanAbsDifference(moving, still, peak);
    EXPECT_LT(d, 2e-3 * peak);
}

TEST(DeformingMeshRender, TheNaiveTracerRendersTheSameBlur) {
    const SceneDesc scene = tentScene("[0.1, 0.9]");
    const std::vector<float> embree = test::renderBeauty(scene, {.spp = 16});
    const std::vector<float> naive = test::renderBeauty(scene, {.accel = AccelKind::Naive, .spp = 16});
    double peak = 0.0;
    const double d = meanAbsDifference(embree, naive, peak);
    EXPECT_GT(peak, 0.0);
    EXPECT_LT(d, 1e-3 * peak);
}

}  // namespace
}  // namespace strahl
