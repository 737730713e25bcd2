// Material opacity in scenes (docs/materials.md, "Opacity"): a constant or
// textured opacity cuts holes out of a mesh for camera and shadow rays, the
// same holes for every query, and the cases strahl cannot render are one
// clear error.

#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../../src/scene/material_builder.h"  // internal to the scene module
#include "strahl/core/error.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

// A unit quad in z = 0 with uvs (u along x, v along y) made of `material`, and
// a solid floor at z = -1.
std::string quadScene(const std::string& material) {
    return R"({"materials": [)" + material + R"(],
      "shapes": [{"type": "mesh", "material": "leaf", "positions": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],
                  "uvs": [[0,0],[1,0],[1,1],[0,1]], "indices": [0,1,2, 0,2,3]},
                 {"type": "mesh", "positions": [[-5,-5,-1],[5,-5,-1],[5,5,-1],[-5,5,-1]],
                  "indices": [0,1,2, 0,2,3]}]})";
}

World world(const std::string& text, const fs::path& file = "scene.json",
            AccelKind accel = AccelKind::Embree) {
    BuildOptions options;
    options.accel = accel;
    return buildWorld(parseSceneText(text, file), options);
}

// Fraction of downward rays through the quad that reach the floor, at points
// (x, y) on an n x n grid over [x0, x1] x [0, 1].
double throughFraction(const World& w, float x0, float x1, int n = 64) {
    int through = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            Ray ray;
            ray.origin = Vec3(x0 + (x1 - x0) * (float(i) + 0.5f) / float(n),
                              (float(j) + 0.5f) / float(n), 2.0f);
            ray.dir = Vec3(0, 0, -1);
            const Hit hit = w.accel->intersect(ray);
            through += hit.valid() && hit.geomID == 1;
        }
    return double(through) / (n * n);
}

TEST(CutoutScene, ConstantOpacityZeroIsInvisibleAndOneIsSolid) {
    const World hole = world(quadScene(R"({"name": "leaf", "opacity": 0})"));
    EXPECT_EQ(throughFraction(hole, 0, 1), 1.0);
    const World solid = world(quadScene(R"({"name": "leaf", "opacity": 1})"));
    EXPECT_EQ(throughFraction(solid, 0, 1), 0.0);
}

TEST(CutoutScene, PartialOpacityLetsThatFractionThroughTheSameForEveryTracer) {
    const std::string text = quadScene(R"({"name": "leaf", "opacity": 0.3})");
    const World embree = world(text), naive = world(text, "scene.json", AccelKind::Naive);
    const double through = throughFraction(embree, 0, 1, 128);
    EXPECT_NEAR(through, 0.7, 0.02);
    // The naive tracer decides by the same rule, but its barycentrics differ
    // from Embree's in the last bits, so a partial opacity agrees in fraction
    // (binary opacities agree hit for hit, as the texture test shows).
    EXPECT_NEAR(throughFraction(naive, 0, 1, 128), through, 0.005);
    // Shadow rays see the same surface: occluded exactly where the camera rays stop.
    for (int k = 0; k < 200; ++k) {
        Ray ray;
        ray.origin = Vec3(0.005f * float(k), 0.37f, 2.0f);
        ray.dir = Vec3(0, 0, -1);
        const Hit hit = embree.accel->intersect(ray);
        Ray shadow = ray;
        shadow.tfar = 2.5f;  // ends above the floor
        EXPECT_EQ(embree.accel->occluded(shadow), hit.geomID == 0);
    }
}

TEST(CutoutScene, AnOpacityTextureCutsWhereItIsZero) {
    const fs::path dir = test::scratchDir("cutout-texture");
    // 2 x 1 grey: left texel 0 (hole), right texel 255 (solid).
    const std::vector<unsigned char> pixels = {0, 255};
    auto out = OIIO::ImageOutput::create((dir / "mask.png").string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open((dir / "mask.png").string(), OIIO::ImageSpec(2, 1, 1, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    ASSERT_TRUE(out->close());
    const std::string text =
        quadScene(R"({"name": "leaf", "opacity": {"texture": "mask.png", "filter": "nearest"}})");
    test::writeFile(dir / "scene.json", text);
    const World w = world(text, dir / "scene.json");
    EXPECT_EQ(throughFraction(w, 0.0f, 0.5f), 1.0);
    EXPECT_EQ(throughFraction(w, 0.5f, 1.0f), 0.0);
    const World naive = world(text, dir / "scene.json", AccelKind::Naive);
    EXPECT_EQ(throughFraction(naive, 0.0f, 0.5f), 1.0);
    EXPECT_EQ(throughFraction(naive, 0.5f, 1.0f), 0.0);
}

TEST(CutoutScene, GltfAlphaBecomesTheBaseColoursAlphaAsOpacity) {
    World w;
    MeshMaterial mask;
    mask.source = MeshMaterial::Source::Gltf;
    mask.dissolve = 0.4f;
    mask.opacityCutoff = 0.5f;
    const Material cut = scene_detail::buildMeshMaterial(mask, "leaf", w);
    EXPECT_TRUE(cut.cutsOut());
    EXPECT_EQ(cut.opacity.value, 0.4f);
    EXPECT_EQ(cut.opacity.channel, 3);  // alpha
    EXPECT_EQ(cut.opacityCutoff, 0.5f);
    MeshMaterial opaque;
    opaque.source = MeshMaterial::Source::Gltf;
    EXPECT_FALSE(scene_detail::buildMeshMaterial(opaque, "wall", w).cutsOut());
    // A cutoff makes the opacity a threshold: 0.4 < 0.5 is a hole everywhere.
    const std::string text =
        quadScene(R"({"name": "leaf", "opacity": 0.4, "opacity_cutoff": 0.5})");
    EXPECT_EQ(throughFraction(world(text), 0, 1), 1.0);
    EXPECT_EQ(throughFraction(world(quadScene(R"({"name": "leaf", "opacity": 0.6, "opacity_cutoff": 0.5})")), 0, 1), 0.0);
}

TEST(CutoutScene, WhatCannotBeCutOutIsOneClearError) {
    EXPECT_EQ(test::errorMessage([] {
                  parseSceneText(quadScene(R"({"name": "leaf", "opacity": 0.5, "emission": 1})"),
                                 "scene.json");
              }),
              "scene.json: /materials/0/opacity: an emitting material cannot have an opacity "
              "(cut-out emitters are not supported)");
    EXPECT_EQ(test::errorMessage([] {
                  parseSceneText(quadScene(R"({"name": "leaf", "opacity": 1.5})"), "scene.json");
              }),
              "scene.json: /materials/0/opacity: must be in [0, 1], got 1.5");
    const std::string implicit = R"({"materials": [{"name": "leaf", "opacity": 0.5}],
        "shapes": [{"type": "implicit", "material": "leaf", "surface": {"type": "sphere"}}]})";
    EXPECT_THAT(test::errorMessage([&] { world(implicit); }),
                testing::HasSubstr("its material has an opacity, and cut-outs are supported on "
                                   "triangle meshes only"));
}

}  // namespace
}  // namespace strahl
