// The path tracer against what must hold whatever the scene: the white
// furnace (a closed object inside a uniform white environment reflects
// exactly what it receives when its material is lossless, never more), an
// analytic direct-lighting case, and the agreement of MIS with BSDF-only and
// light-only sampling (three estimators of one integral).

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "strahl/scene/scene_desc.h"
#include "render_helpers.h"
#include "test_support.h"

namespace strahl {
namespace {

struct Image {
    int width = 0, height = 0;
    std::vector<float> beauty;    // RGB
    std::vector<float> variance;  // RGB: the variance of each pixel's mean
};

Image renderText(const std::string& text, const std::string& name,
                 LightSampling sampling = LightSampling::Mis, int threads = 2) {
    const SceneDesc desc = parseSceneText(text, test::scratchDir("path") / (name + ".json"));
    const Film film = test::renderFilm(
        desc, {.aovs = {AovKind::Variance}, .threads = threads, .sampling = sampling});
    return Image{desc.film.width, desc.film.height, film.resolveBeauty(),
                 film.resolveAov(AovKind::Variance)};
}

// A sphere of `material` filling the middle of an 8 x 8 image, inside a
// uniform environment of radiance 1.
std::string furnaceScene(const std::string& material, const std::string& surface) {
    return R"({
      "camera": { "eye": [0, 0, 4], "look_at": [0, 0, 0], "fov": 30 },
      "film": { "width": 8, "height": 8 },
      "render": { "integrator": "path", "spp": 256, "max_depth": 100 },
      "background": 1,
      "materials": [ )" + material + R"( ],
      "shapes": [ )" + surface + R"( ]
    })";
}

const std::string kImplicitSphere =
    R"({ "type": "implicit", "material": "m", "surface": { "type": "sphere", "radius": 1 } })";
const std::string kTessellatedSphere =
    R"({ "type": "parametric", "material": "m", "surface": { "type": "sphere", "radius": 1 } })";

// Mean radiance of the centre 4 x 4 pixels (all on the sphere).
double centreMean(const Image& image) {
    double sum = 0.0;
    for (int y = 2; y < 6; ++y)
        for (int x = 2; x < 6; ++x)
            for (int c = 0; c < 3; ++c) sum += image.beauty[3 * size_t(y * image.width + x) + c];
    return sum / 48.0;
}

struct FurnaceCase {
    const char* name;
    const char* material;
    bool lossless;  // albedo exactly 1: the sphere must vanish into the background
};

class WhiteFurnace : public ::testing::TestWithParam<FurnaceCase> {};

TEST_P(WhiteFurnace, ReturnsOneForLosslessMaterialsAndNeverMore) {
    const FurnaceCase& c = GetParam();
    for (const std::string& surface : {kImplicitSphere, kTessellatedSphere}) {
        const double mean = centreMean(renderText(furnaceScene(c.material, surface), c.name));
        // 256 spp x 16 pixels; the lossless cases are noise-free up to the
        // Fresnel split, 1.5 % covers the noise of the others.
        if (c.lossless)
            EXPECT_NEAR(mean, 1.0, 0.015) << c.name << " on " << surface;
        else
            EXPECT_LE(mean, 1.015) << c.name << " on " << surface;
        EXPECT_GT(mean, 0.3) << c.name;
    }
}

TEST(WhiteFurnaceSetup, TheSphereCoversTheMeasuredPixels) {
    // Without this, a sphere missing the centre pixels would pass every
    // lossless case above by showing the white background.
    const std::string black = R"({ "name": "m", "type": "diffuse", "color": 0 })";
    for (const std::string& surface : {kImplicitSphere, kTessellatedSphere})
        EXPECT_EQ(centreMean(renderText(furnaceScene(black, surface), "black")), 0.0) << surface;
}

INSTANTIATE_TEST_SUITE_P(
    Materials, WhiteFurnace,
    ::testing::Values(
        FurnaceCase{"lambert", R"({ "name": "m", "type": "diffuse", "color": 1 })", true},
        FurnaceCase{"glass", R"({ "name": "m", "type": "dielectric", "ior": 1.5 })", true},
        FurnaceCase{"rough_glass",
                    R"({ "name": "m", "type": "dielectric", "ior": 1.5, "roughness": 0.3 })",
                    false},
        FurnaceCase{"plastic", R"({ "name": "m", "type": "plastic", "color": 1, "ior": 1.5 })",
                    true},
        FurnaceCase{"rough_plastic",
                    R"({ "name": "m", "type": "plastic", "color": 1, "roughness": 0.4 })", false},
        FurnaceCase{"phong", R"({ "name": "m", "type": "phong", "color": 0.5, "specular": 0.5,
                                  "exponent": 40 })", false},
        FurnaceCase{"blinn", R"({ "name": "m", "type": "blinn", "color": 0.5, "specular": 0.5,
                                  "exponent": 40 })", false},
        FurnaceCase{"gold", R"({ "name": "m", "type": "conductor", "metal": "gold",
                                 "roughness": 0.3 })", false},
        FurnaceCase{"metallic_roughness",
                    R"({ "name": "m", "type": "metallic_roughness", "color": 1, "metallic": 0.5,
                         "roughness": 0.5 })", false}),
    [](const ::testing::TestParamInfo<FurnaceCase>& p) { return std::string(p.param.name); });

TEST(PathTracer, LambertPlaneUnderAPointLightMatchesTheClosedForm) {
    // L = rho / pi * I / h^2 straight below the light; the floor is the only
    // object, so every bounce escapes into a black sky: exact at 1 spp.
    const std::string scene = R"({
      "camera": { "type": "orthographic", "eye": [0, 5, 0], "back": [0, 1, 0],
                  "up": [0, 0, -1], "window": [-0.2, 0.2, -0.2, 0.2] },
      "film": { "width": 5, "height": 5 },
      "render": { "integrator": "path", "spp": 1 },
      "materials": [ { "name": "floor", "color": 0.5 } ],
      "shapes": [ { "type": "mesh", "material": "floor",
                    "positions": [[-10, 0, -10], [10, 0, -10], [10, 0, 10], [-10, 0, 10]],
                    "indices": [0, 2, 1, 0, 3, 2] } ],
      "lights": [ { "type": "point", "position": [0, 2, 0], "intensity": 8 } ]
    })";
    const Image image = renderText(scene, "lambert_point");
    const float expected = 0.5f / kPi * 8.0f / 4.0f;
    const size_t centre = 3 * size_t(2 * 5 + 2);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.beauty[centre + c], expected, 1e-5f);
}

// A small box room lit by a quad light in the ceiling: what a BSDF-sampled ray
// finds and what light sampling finds are both material. The lamp's emission
// is uniform, or a pattern through its uvs (light-sampled all the same).
const std::string kUniformLamp = "8";
const std::string kPatternedLamp =
    R"({ "checkerboard": { "color0": 1, "color1": 0.1, "scale": 2 }, "scale": 8 })";

std::string roomScene(int spp, const std::string& lamp = kUniformLamp) {
    return R"({
      "camera": { "eye": [0, 1, 3.2], "look_at": [0, 1, 0], "fov": 45 },
      "film": { "width": 16, "height": 16 },
      "render": { "integrator": "path", "spp": )" + std::to_string(spp) + R"(, "max_depth": 3 },
      "materials": [
        { "name": "white", "color": 0.7 },
        { "name": "red", "color": [0.7, 0.1, 0.1] },
        { "name": "shiny", "type": "conductor", "metal": "silver", "roughness": 0.35 },
        { "name": "lamp", "type": "emissive", "emission": )" + lamp + R"( } ],
      "shapes": [
        { "type": "mesh", "material": "white",
          "positions": [[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1],
                        [-1, 2, -1], [1, 2, -1], [1, 2, 1], [-1, 2, 1]],
          "indices": [0, 2, 1, 0, 3, 2,  4, 5, 6, 4, 6, 7,  0, 1, 5, 0, 5, 4] },
        { "type": "mesh", "material": "red",
          "positions": [[-1, 0, -1], [-1, 0, 1], [-1, 2, 1], [-1, 2, -1]],
          "indices": [0, 1, 2, 0, 2, 3] },
        { "type": "mesh", "material": "shiny",
          "positions": [[1, 0, -1], [1, 2, -1], [1, 2, 1], [1, 0, 1]],
          "indices": [0, 1, 2, 0, 2, 3] },
        { "type": "mesh", "material": "lamp",
          "positions": [[-0.3, 1.99, -0.3], [0.3, 1.99, -0.3], [0.3, 1.99, 0.3], [-0.3, 1.99, 0.3]],
          "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]],
          "indices": [0, 1, 2, 0, 2, 3] } ]
    })";
}

// Per-pixel z-scores of two independent estimates of the same image.
struct Agreement {
    double meanA = 0, meanB = 0;
    double outliers = 0;  // fraction of channels with |z| > 4
};

Agreement compare(const Image& a, const Image& b) {
    Agreement r;
    size_t n = a.beauty.size(), bad = 0;
    for (size_t i = 0; i < n; ++i) {
        r.meanA += a.beauty[i];
        r.meanB += b.beauty[i];
        const double sigma = std::sqrt(double(a.variance[i]) + double(b.variance[i]));
        const double diff = std::abs(double(a.beauty[i]) - double(b.beauty[i]));
        if (diff > 4.0 * sigma + 1e-6) ++bad;
    }
    r.meanA /= double(n);
    r.meanB /= double(n);
    r.outliers = double(bad) / double(n);
    return r;
}

// `reference` and each of `others` estimate the same image: means within 2 %
// and |z| > 4 in under 1 % of the channels (with 768 channels and independent
// noise that is rare, 6e-5 each for Gaussian errors; heavy-tailed pixels
// allow a few).
void expectAgreement(const Image& reference, std::initializer_list<const Image*> others) {
    for (const Image* other : others) {
        const Agreement a = compare(reference, *other);
        EXPECT_NEAR(a.meanA, a.meanB, 0.02 * a.meanA);
        EXPECT_LT(a.outliers, 0.01);
    }
}

TEST(PathTracer, MisBsdfOnlyAndLightOnlyConvergeToTheSameImage) {
    const Image mis = renderText(roomScene(256), "room_mis", LightSampling::Mis);
    const Image bsdf = renderText(roomScene(1024), "room_bsdf", LightSampling::BsdfOnly);
    const Image light = renderText(roomScene(256), "room_light", LightSampling::LightOnly);
    expectAgreement(mis, {&bsdf, &light});
}

// A lamp whose emission is a mix (a checkerboard blended with a constant by
// a finer checkerboard) is light-sampled through the same code: the three
// estimators agree. With the amount 0 everywhere, the mix is its first
// input: the image of that input alone, bit for bit.
TEST(PathTracer, AMixedLampIsLightSampledWithoutBias) {
    const std::string mixed =
        R"({ "mix": [{ "checkerboard": { "color0": 1, "color1": 0.1, "scale": 2 } }, 0.5],
             "amount": { "checkerboard": { "color0": 0, "color1": 1, "scale": 5 } }, "scale": 8 })";
    const Image mis = renderText(roomScene(256, mixed), "mixed_mis", LightSampling::Mis);
    const Image bsdf = renderText(roomScene(1024, mixed), "mixed_bsdf", LightSampling::BsdfOnly);
    const Image light = renderText(roomScene(256, mixed), "mixed_light", LightSampling::LightOnly);
    expectAgreement(mis, {&bsdf, &light});
    const std::string first =
        R"({ "mix": [{ "checkerboard": { "color0": 1, "color1": 0.1, "scale": 2 } }, 0.5],
             "amount": 0, "scale": 8 })";
    const Image mixedFirst = renderText(roomScene(16, first), "mixed_first");
    const Image patterned = renderText(roomScene(16, kPatternedLamp), "patterned_16");
    EXPECT_EQ(mixedFirst.beauty, patterned.beauty);
    // A mix of two constants is evaluated, not taken for its scale: light
    // sampling and BSDF sampling agree on a lamp of (4 + 12) / 2 = 8.
    const std::string constants = R"({ "mix": [4, 12], "amount": 0.5 })";
    const Image cMis = renderText(roomScene(256, constants), "constants_mis", LightSampling::Mis);
    const Image cLight = renderText(roomScene(256, constants), "constants_light", LightSampling::LightOnly);
    const Image uniform = renderText(roomScene(256, kUniformLamp), "uniform_mis", LightSampling::Mis);
    expectAgreement(cMis, {&cLight, &uniform});
}

// A patterned lamp is light-sampled too: light sampling reads the pattern at
// the sampled point, BSDF sampling where the ray lands, and the MIS weights
// of both agree, so all three estimators still converge to one image.
TEST(PathTracer, APatternedLampIsLightSampledWithoutBias) {
    const Image mis = renderText(roomScene(256, kPatternedLamp), "pattern_mis", LightSampling::Mis);
    const Image bsdf =
        renderText(roomScene(1024, kPatternedLamp), "pattern_bsdf", LightSampling::BsdfOnly);
    const Image light =
        renderText(roomScene(256, kPatternedLamp), "pattern_light", LightSampling::LightOnly);
    expectAgreement(mis, {&bsdf, &light});
    // And light sampling is what makes it converge: MIS beats BSDF sampling alone.
    const Image bsdfSame =
        renderText(roomScene(256, kPatternedLamp), "pattern_bsdf_256", LightSampling::BsdfOnly);
    double vMis = 0, vBsdf = 0;
    size_t misLower = 0;
    for (size_t i = 0; i < mis.variance.size(); ++i) {
        vMis += mis.variance[i];
        vBsdf += bsdfSame.variance[i];
        if (mis.variance[i] < bsdfSame.variance[i]) ++misLower;
    }
    // Measured: MIS has 0.53 of the total variance and less in 96 % of the
    // channels. The total is bounded by what both share: the pixels that see
    // the patterned lamp itself, whose checkers vary within the pixel.
    EXPECT_LT(vMis, 0.75 * vBsdf);
    EXPECT_GT(double(misLower), 0.9 * double(mis.variance.size()));
}

TEST(PathTracer, MisHasLessVarianceThanEitherStrategyAlone) {
    const Image mis = renderText(roomScene(64), "room_mis_v", LightSampling::Mis);
    const Image bsdf = renderText(roomScene(64), "room_bsdf_v", LightSampling::BsdfOnly);
    double vMis = 0, vBsdf = 0;
    for (size_t i = 0; i < mis.variance.size(); ++i) {
        vMis += mis.variance[i];
        vBsdf += bsdf.variance[i];
    }
    EXPECT_LT(vMis, 0.5 * vBsdf);
}

TEST(PathTracer, ImageIsIdenticalForAnyThreadCount) {
    const Image one = renderText(roomScene(8), "room_t1", LightSampling::Mis, 1);
    const Image two = renderText(roomScene(8), "room_t2", LightSampling::Mis, 2);
    EXPECT_EQ(one.beauty, two.beauty);
}

}  // namespace
}  // namespace strahl
