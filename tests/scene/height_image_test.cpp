// Height images: a float EXR and an 8-bit RGB PNG written with OpenImageIO
// read back as heights (row-major, top row first, luminance of RGB), and the
// errors of missing files, non-images and non-finite values.

#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../../src/scene/height_image.h"  // internal to the scene module
#include "strahl/core/error.h"
#include "strahl/geometry/height_field.h"
#include "test_support.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace strahl {
namespace {

using scene_detail::HeightImage;
using scene_detail::loadHeightImage;

template <typename T>
void writeImage(const fs::path& file, int width, int height, int channels, OIIO::TypeDesc type,
                const std::vector<T>& pixels) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    const OIIO::ImageSpec spec(width, height, channels, type);
    ASSERT_TRUE(out->open(file.string(), spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(type, pixels.data())) << out->geterror();
    ASSERT_TRUE(out->close());
}

TEST(HeightImage, FloatExrReadsBackRowMajorTopRowFirst) {
    const fs::path file = test::scratchDir("height-exr") / "heights.exr";
    // 4 x 3, value = 10 * row + column (+ a fraction EXR keeps exactly).
    std::vector<float> pixels;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) pixels.push_back(10.0f * float(r) + float(c) + 0.25f);
    writeImage(file, 4, 3, 1, OIIO::TypeDesc::FLOAT, pixels);

    const HeightImage image = loadHeightImage(file);
    EXPECT_EQ(image.columns, 4);
    EXPECT_EQ(image.rows, 3);
    EXPECT_EQ(image.heights, pixels);

    // Into a height field: the image's top-left pixel is the (−x, +y) corner.
    const ParametricSurfacePtr field =
        makeHeightField(image.heights, image.columns, image.rows, 3.0, 2.0, 1.0);
    EXPECT_EQ(field->point(0, -1.5, 1.0).z, 0.25);
    EXPECT_EQ(field->point(0, 1.5, -1.0).z, 23.25);
}

TEST(HeightImage, RgbPngGivesItsLuminance) {
    const fs::path file = test::scratchDir("height-png") / "heights.png";
    // 3 x 2: red, green, blue / white, black, grey.
    const std::vector<uint8_t> pixels = {255, 0,   0,   0, 255, 0, 0,  0,  255,
                                         255, 255, 255, 0, 0,   0, 51, 51, 51};
    writeImage(file, 3, 2, 3, OIIO::TypeDesc::UINT8, pixels);

    const HeightImage image = loadHeightImage(file);
    ASSERT_EQ(image.columns, 3);
    ASSERT_EQ(image.rows, 2);
    const float expected[] = {0.2126f, 0.7152f, 0.0722f, 1.0f, 0.0f, 0.2f};
    for (size_t k = 0; k < 6; ++k) EXPECT_NEAR(image.heights[k], expected[k], 1e-6) << k;
}

TEST(HeightImage, GreyscaleAlphaUsesTheFirstChannel) {
    const fs::path file = test::scratchDir("height-ga") / "heights.png";
    const std::vector<uint8_t> pixels = {0, 255, 255, 0, 102, 255, 204, 255};  // (grey, alpha) x 4
    writeImage(file, 2, 2, 2, OIIO::TypeDesc::UINT8, pixels);
    const HeightImage image = loadHeightImage(file);
    ASSERT_EQ(image.heights.size(), 4u);
    EXPECT_NEAR(image.heights[0], 0.0f, 1e-6);
    EXPECT_NEAR(image.heights[1], 1.0f, 1e-6);
    EXPECT_NEAR(image.heights[2], 0.4f, 1e-6);
    EXPECT_NEAR(image.heights[3], 0.8f, 1e-6);
}

TEST(HeightImage, BadFilesAreErrorsNamingTheFile) {
    const fs::path dir = test::scratchDir("height-bad");

    const fs::path text = dir / "notes.png";
    test::writeFile(text, "this is not an image, only text renamed to .png\n");
    std::string m = test::errorMessage([&] { loadHeightImage(text); });
    EXPECT_THAT(m, HasSubstr(text.string() + ": cannot read the height image"));
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;

    const fs::path missing = dir / "missing.exr";
    m = test::errorMessage([&] { loadHeightImage(missing); });
    EXPECT_THAT(m, HasSubstr(missing.string() + ": cannot read the height image: no such file"));

    m = test::errorMessage([&] { loadHeightImage(dir); });
    EXPECT_THAT(m, HasSubstr(dir.string() + ": cannot read the height image: not a regular file"));

    const fs::path nan = dir / "nan.exr";
    writeImage(nan, 2, 2, 1, OIIO::TypeDesc::FLOAT,
               std::vector<float>{0.0f, 1.0f, std::nanf(""), 2.0f});
    m = test::errorMessage([&] { loadHeightImage(nan); });
    EXPECT_THAT(
        m, HasSubstr(nan.string() + ": the height image has a non-finite value at pixel (0, 1)"));
}

}  // namespace
}  // namespace strahl
