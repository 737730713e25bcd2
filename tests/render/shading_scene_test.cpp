// End-to-end checks of lights, textures and the ao integrator through the
// scene file: cases with a closed-form answer, rendered by the real pipeline
// (parser, builder, texture system, light set, integrator, film).

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "strahl/scene/scene_desc.h"
#include "render_helpers.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

void expectColorNear(const Color& actual, const Color& expected, float tolerance) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance) << "channel " << c;
}

struct RenderedWithAlbedo {
    int width = 0;
    std::vector<float> beauty, albedo;
    Color at(int x, int y) const {
        const size_t i = 3 * (size_t(y) * size_t(width) + size_t(x));
        return Color(beauty[i], beauty[i + 1], beauty[i + 2]);
    }
    Color albedoAt(int x, int y) const {
        const size_t i = 3 * (size_t(y) * size_t(width) + size_t(x));
        return Color(albedo[i], albedo[i + 1], albedo[i + 2]);
    }
};

RenderedWithAlbedo renderIn(const fs::path& dir, const std::string& text) {
    const SceneDesc desc = parseSceneText(text, dir / "scene.json");
    const Film film = test::renderFilm(desc, {.aovs = {AovKind::Albedo}});
    return RenderedWithAlbedo{desc.film.width, film.resolveBeauty(),
                              film.resolveAov(AovKind::Albedo)};
}

// An orthographic camera looking straight down at a floor quad at y = 0
// with material `floor`, plus `extra` scene sections.
std::string floorScene(const std::string& integrator, int spp, const std::string& floor,
                       const std::string& extra, int size = 4) {
    return R"({
      "camera": { "type": "orthographic", "eye": [0, 5, 0], "back": [0, 1, 0], "up": [0, 0, -1],
                  "window": [-1, 1, -1, 1] },
      "film": { "width": )" + std::to_string(size) + R"(, "height": )" + std::to_string(size) + R"( },
      "render": { "integrator": ")" + integrator + R"(", "spp": )" + std::to_string(spp) + R"( },
      "materials": [ )" + floor + R"( ],
      "shapes": [ { "type": "mesh", "material": "floor",
                    "positions": [[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]],
                    "uvs": [[0, 1], [1, 1], [1, 0], [0, 0]],
                    "indices": [0, 2, 1, 0, 3, 2] } ])" + extra + "}";
}

TEST(SkyLight, LambertPlaneReflectsRhoTimesTheSkyRadianceWithoutNoise) {
    // Irradiance from a uniform sky is pi L; reflected radiance rho/pi * pi L.
    // Cosine-weighted sky sampling makes every sample exactly rho L.
    const fs::path dir = test::scratchDir("sky-plane");
    const RenderedWithAlbedo r =
        renderIn(dir, floorScene("direct", 4, R"({ "name": "floor", "color": 0.5 })",
                                 R"(, "background": [2, 1, 0.5])"));
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) expectColorNear(r.at(x, y), Color(1.0f, 0.5f, 0.25f), 1e-5f);
}

// A 2 x 2 constant float EXR: an environment map equal to a uniform sky.
void writeConstantExr(const fs::path& file, float value) {
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out);
    const OIIO::ImageSpec spec(2, 2, 3, OIIO::TypeDesc::FLOAT);
    ASSERT_TRUE(out->open(file.string(), spec));
    const std::vector<float> pixels(12, value);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
}

TEST(EnvironmentLight, ConstantMapLightsLikeTheSkyAndScales) {
    const fs::path dir = test::scratchDir("env-plane");
    writeConstantExr(dir / "grey.exr", 0.5f);
    const RenderedWithAlbedo r = renderIn(
        dir, floorScene("path", 64, R"({ "name": "floor", "color": 0.8 })",
                        R"(, "lights": [ { "type": "environment", "file": "grey.exr",
                                          "scale": 2, "rotation": 30 } ])"));
    // rho * L = 0.8 * 0.5 * 2 at every pixel; MIS of light and BSDF samples
    // is unbiased but not noise-free here, so average the image.
    Color mean(0.0f);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) mean += r.at(x, y) / 16.0f;
    expectColorNear(mean, Color(0.8f), 0.02f);
}

TEST(NormalMap, TerminatorShadowingScalesTheLightByTheSmithTermOfTheTilt) {
    // A uniform normal map tilting the floor's normal 30 degrees towards +x
    // (dp/du), lit by a directional light 70 degrees from the vertical on
    // that side: the shadowing multiplies the light by
    // G = 2 / (1 + sqrt(1 + a^2 tan^2 70)), a^2 = tan^2 30 / 8 (Chiang et al. 2019).
    const fs::path dir = test::scratchDir("normal-map-shadowing");
    const float tilt = glm::radians(30.0f), light = glm::radians(70.0f);
    {
        auto out = OIIO::ImageOutput::create((dir / "tilt.exr").string());
        ASSERT_TRUE(out);
        ASSERT_TRUE(out->open((dir / "tilt.exr").string(), OIIO::ImageSpec(1, 1, 3, OIIO::TypeDesc::FLOAT)));
        const float texel[3] = {0.5f + 0.5f * std::sin(tilt), 0.5f, 0.5f + 0.5f * std::cos(tilt)};
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, texel));
        out->close();
    }
    const std::string lights = R"(, "lights": [{"type": "directional", "irradiance": 1, "direction": [)" +
                               std::to_string(-std::sin(light)) + ", " +
                               std::to_string(-std::cos(light)) + ", 0]}]";
    const auto render = [&](bool shadowing) {
        return renderIn(dir, floorScene("direct", 1,
                                        R"({ "name": "floor", "color": 0.5, "normal_map":
                                             {"texture": "tilt.exr", "shadowing": )" +
                                            std::string(shadowing ? "true" : "false") + "} }",
                                        lights))
            .at(1, 1);
    };
    const Color plain = render(false), shadowed = render(true);
    // Without shadowing: rho / pi * cos(angle between the tilted normal and the light).
    EXPECT_NEAR(plain.r, 0.5f / kPi * std::cos(light - tilt), 1e-4f);
    const float a2 = std::tan(tilt) * std::tan(tilt) / 8.0f;
    const float g = 2.0f / (1.0f + std::sqrt(1.0f + a2 * std::tan(light) * std::tan(light)));
    EXPECT_NEAR(shadowed.r / plain.r, g, 1e-4f);
    EXPECT_LT(g, 0.94f);  // a visible effect
}

TEST(Textures, MeshUvsPlaceTheImageUpright) {
    // A 64 x 64 image in four quadrants: top left red, top right white,
    // bottom left black, bottom right blue.
    const fs::path dir = test::scratchDir("texture-quad");
    {
        constexpr int n = 64;
        std::vector<unsigned char> pixels(size_t(n) * n * 3);
        for (int y = 0; y < n; ++y) {
            for (int x = 0; x < n; ++x) {
                const bool right = x >= n / 2, bottom = y >= n / 2;
                const unsigned char rgb[4][3] = {{255, 0, 0}, {255, 255, 255}, {0, 0, 0}, {0, 0, 255}};
                const unsigned char* c = rgb[(bottom ? 2 : 0) + (right ? 1 : 0)];
                for (int k = 0; k < 3; ++k) pixels[3 * (size_t(y) * n + x) + k] = c[k];
            }
        }
        auto out = OIIO::ImageOutput::create((dir / "tex.png").string());
        ASSERT_TRUE(out);
        ASSERT_TRUE(out->open((dir / "tex.png").string(),
                              OIIO::ImageSpec(n, n, 3, OIIO::TypeDesc::UINT8)));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
        out->close();
    }
    // The quad's uv (0, 1) corner is at the top left of the view, so the
    // picture must appear as drawn. The lookups are filtered over the pixel
    // footprint (and wrap periodically), so the test asks which colour
    // dominates each corner pixel rather than for exact texels.
    const RenderedWithAlbedo r = renderIn(
        dir, floorScene("direct", 1,
                        R"({ "name": "floor", "color": { "texture": "tex.png" } })", "", 8));
    const Color topLeft = r.albedoAt(1, 1), topRight = r.albedoAt(6, 1);
    const Color bottomLeft = r.albedoAt(1, 6), bottomRight = r.albedoAt(6, 6);
    EXPECT_GT(topLeft.x, 0.8f);
    EXPECT_LT(topLeft.y, 0.1f);
    EXPECT_GT(topRight.x, 0.8f);
    EXPECT_GT(topRight.y, 0.8f);
    EXPECT_GT(topRight.z, 0.8f);
    EXPECT_LT(maxComponent(bottomLeft), 0.1f);
    EXPECT_GT(bottomRight.z, 0.8f);
    EXPECT_LT(bottomRight.x, 0.1f);
}

TEST(AmbientOcclusion, OpenPlaneIsOneAndACoveredSpotIsDarker) {
    const fs::path dir = test::scratchDir("ao-plane");
    const std::string floor = R"({ "name": "floor", "color": 0.5 })";
    const RenderedWithAlbedo open = renderIn(dir, floorScene("ao", 16, floor, ""));
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) expectColorNear(open.at(x, y), Color(1.0f), 0.0f);
    // A roof 0.1 above the floor's left half, seen through by the camera
    // (one-sided quad facing up is still an occluder from below).
    const RenderedWithAlbedo covered = renderIn(
        dir, R"({
      "camera": { "type": "orthographic", "eye": [0, 5, 0], "back": [0, 1, 0], "up": [0, 0, -1],
                  "window": [-1, 1, -1, 1] },
      "film": { "width": 4, "height": 4 },
      "render": { "integrator": "ao", "spp": 64, "ao_distance": 1 },
      "materials": [ { "name": "floor", "color": 0.5 } ],
      "shapes": [ { "type": "mesh", "material": "floor",
                    "positions": [[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]],
                    "indices": [0, 2, 1, 0, 3, 2] },
                  { "type": "mesh", "material": "floor",
                    "positions": [[-3, 0.1, -3], [-0.01, 0.1, -3], [-0.01, 0.1, 3], [-3, 0.1, 3]],
                    "indices": [0, 2, 1, 0, 3, 2] } ]
    })");
    // Pixel column 0 sees the roof itself (open above: 1); the floor under the
    // roof is hidden. Column 2 (x = 0.25) is floor 0.26 from the roof's edge:
    // directions towards -x flatter than 0.1 / 0.26 are blocked.
    EXPECT_LT(covered.at(2, 1).x, 0.97f);
    EXPECT_GT(covered.at(2, 1).x, 0.5f);
    EXPECT_EQ(covered.at(0, 1).x, 1.0f);
}

}  // namespace
}  // namespace strahl
