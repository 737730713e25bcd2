// Motion blur (core/motion.h, docs/geometry.md "Motion blur"): a moving
// instance's image is the average of still frames over the shutter (camera
// rays sample the time), a closed shutter shows the ball and its shadow where
// the keyframe puts them (shadow rays are cast at their path's time), and the
// naive tracer renders the same blur as Embree.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "render_helpers.h"
#include "strahl/scene/scene_desc.h"

namespace strahl {
namespace {

// A ball on a floor under a point light, placed by keyframes: it slides 1.2
// units in x and rises 0.3 (two segments, the second turning about z),
// seen through `shutter`.
SceneDesc ballScene(const std::string& shutter, const std::string& integrator = "direct") {
    std::string text = R"({
      "camera": {"eye": [0, -4, 2.2], "look_at": [0, 0, 0.3], "up": [0, 0, 1], "fov": 38, "shutter": SHUTTER},
      "film": {"width": 48, "height": 36},
      "render": {"integrator": "INTEGRATOR", "spp": 1},
      "materials": [{"name": "grey", "color": 0.6}, {"name": "red", "color": [0.8, 0.2, 0.1]}],
      "groups": [{"name": "ball", "shapes": [
        {"type": "implicit", "material": "red", "surface": {"type": "sphere", "radius": 0.45}}]}],
      "shapes": [
        {"type": "mesh", "material": "grey", "positions": [[-4, -4, -0.45], [4, -4, -0.45], [4, 4, -0.45], [-4, 4, -0.45]],
         "indices": [0, 1, 2, 0, 2, 3]},
        {"type": "instance", "group": "ball", "motion": [
          [{"translate": [-0.6, 0, 0]}],
          [{"translate": [0, 0, 0.15]}],
          [{"rotate": {"axis": [0, 0, 1], "angle": 20}}, {"translate": [0.6, 0, 0.3]}]]}],
      "lights": [{"type": "point", "position": [1, -2, 4], "intensity": 40}]
    })";
    text.replace(text.find("SHUTTER"), 7, shutter);
    text.replace(text.find("INTEGRATOR"), 10, integrator);
    return parseSceneText(text, "motion.json");
}

struct Difference {
    double meanAbs = 0, peak = 0;
};

Difference compare(const std::vector<float>& a, const std::vector<float>& b) {
    Difference d;
    for (size_t i = 0; i < a.size(); ++i) {
        d.meanAbs += std::abs(a[i] - b[i]);
        d.peak = std::max(d.peak, double(std::max(a[i], b[i])));
    }
    d.meanAbs /= double(a.size());
    return d;
}

TEST(MotionBlur, AMovingBallIsTheAverageOfItsStillFrames) {
    constexpr int kFrames = 32, kFrameSpp = 32, kBlurredSpp = kFrames * kFrameSpp;
    const SceneDesc blurred = ballScene("[0, 1]");
    const std::vector<float> image = test::renderBeauty(blurred, {.spp = kBlurredSpp});

    std::vector<float> average(image.size(), 0.0f);
    for (int k = 0; k < kFrames; ++k) {
        const float t = (float(k) + 0.5f) / float(kFrames);
        std::string instant = "[";
        instant.append(std::to_string(t)).append(", ").append(std::to_string(t)).append("]");
        const std::vector<float> still = test::renderBeauty(ballScene(instant), {.spp = kFrameSpp});
        for (size_t i = 0; i < still.size(); ++i) average[i] += still[i] / float(kFrames);
    }
    const Difference d = compare(image, average);
    // Both estimate one integral over pixel area and shutter time with 1024
    // samples a pixel; the noise of their difference averages to well under
    // 1 % of the peak. An unblurred ball moves whole regions by a tenth of it.
    EXPECT_LT(d.meanAbs, 0.004 * d.peak) << "mean |blurred - average of stills| " << d.meanAbs;

    // And the blur is real: the first and the last instants differ from it.
    const std::vector<float> first = test::renderBeauty(ballScene("[0, 0]"), {.spp = kFrameSpp});
    EXPECT_GT(compare(image, first).meanAbs, 5 * d.meanAbs);
}

TEST(MotionBlur, ClosedShutterRendersTheKeyframe) {
    // At time 1 the ball is where its last keyframe puts it, as a ball at
    // rest there is rendered — and so is its shadow, which only shadow rays
    // cast at time 1 find there.
    const std::vector<float> moving = test::renderBeauty(ballScene("[1, 1]"), {.spp = 4});
    SceneDesc rest = ballScene("[0, 1]");
    for (ShapeDesc& shape : rest.shapes)
        if (shape.kind == ShapeKind::Instance) {
            shape.transform = shape.motion.back();
            shape.motion.clear();
        }
    const std::vector<float> still = test::renderBeauty(rest, {.spp = 4});
    const Difference d = compare(moving, still);
    EXPECT_LT(d.meanAbs, 1e-4 * d.peak);
}

TEST(MotionBlur, TheNaiveTracerRendersTheSameBlur) {
    const SceneDesc scene = ballScene("[0.2, 0.9]");
    const std::vector<float> embree = test::renderBeauty(scene, {.spp = 16});
    const std::vector<float> naive = test::renderBeauty(scene, {.accel = AccelKind::Naive, .spp = 16});
    const Difference d = compare(embree, naive);
    EXPECT_LT(d.meanAbs, 1e-3 * d.peak);
}

TEST(MotionBlur, ImagesDoNotDependOnTheThreadCount) {
    const SceneDesc scene = ballScene("[0, 1]", "path");
    const std::vector<float> one = test::renderBeauty(scene, {.threads = 1, .spp = 8});
    const std::vector<float> two = test::renderBeauty(scene, {.threads = 2, .tile = 8, .spp = 8});
    EXPECT_EQ(one, two);
}

}  // namespace
}  // namespace strahl
