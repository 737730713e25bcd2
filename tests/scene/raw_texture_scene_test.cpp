// Whether an 8-bit image is read as stored or sRGB-decoded (docs/materials.md,
// "raw"): colours are decoded and scalars are data unless the texture says
// "raw" otherwise; Mitsuba's bitmaps say it for both (docs/mitsuba.md).

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "albedo_probe.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

// A unit quad in z = 0 made of `material` ("m"), next to a 1 x 1 image grey.png of value 128.
World quadWith(const std::string& material) {
    const fs::path dir = test::scratchDir("raw-texture");
    const std::vector<unsigned char> pixel = {128};
    auto out = OIIO::ImageOutput::create((dir / "grey.png").string());
    EXPECT_TRUE(out && out->open((dir / "grey.png").string(), OIIO::ImageSpec(1, 1, 1, OIIO::TypeDesc::UINT8)) &&
                out->write_image(OIIO::TypeDesc::UINT8, pixel.data()) && out->close());
    const std::string text = R"({"materials": [)" + material + R"(],
      "shapes": [{"type": "mesh", "material": "m", "positions": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],
                  "uvs": [[0,0],[1,0],[1,1],[0,1]], "indices": [0,1,2, 0,2,3]}]})";
    return buildWorld(parseSceneText(text, dir / "scene.json"), {});
}

const float kStored = 128.0f / 255.0f;
const float kDecoded = std::pow((kStored + 0.055f) / 1.055f, 2.4f);

TEST(RawTexture, ColoursAreDecodedUnlessRaw) {
    EXPECT_NEAR(test::albedoAt(quadWith(R"({"name": "m", "color": {"texture": "grey.png"}})"), 0.5f, 0.5f).g,
                kDecoded, 2e-3f);
    EXPECT_NEAR(test::albedoAt(quadWith(R"({"name": "m", "color": {"texture": "grey.png", "raw": true}})"), 0.5f, 0.5f).g,
                kStored, 2e-3f);
}

TEST(RawTexture, ScalarsAreDataUnlessRawIsFalse) {
    // A blend of black and white weighted by the image: the weight is the albedo.
    const auto blend = [](const std::string& raw) {
        return R"({"name": "m", "type": "blend", "materials": [{"color": 0}, {"color": 1}],
                   "weight": {"texture": "grey.png")" + raw + "}}";
    };
    EXPECT_NEAR(test::albedoAt(quadWith(blend("")), 0.5f, 0.5f).r, kStored, 2e-3f);
    EXPECT_NEAR(test::albedoAt(quadWith(blend(R"(, "raw": false)")), 0.5f, 0.5f).r, kDecoded, 2e-3f);
}

}  // namespace
}  // namespace strahl
