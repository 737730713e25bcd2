// Display-referred output (PNG, JPEG, TIFF): the crop-sized beauty pass
// through the display transform, clamped and quantised; read back with
// OpenImageIO.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/film/film.h"
#include "strahl/film/image_output.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

// A one-row film of grey pixels with the given linear values.
Film greyRow(const std::vector<float>& values) {
    const int width = static_cast<int>(values.size());
    Film film(width, 1, PixelRect{0, 0, width, 1}, {});
    for (int x = 0; x < width; ++x) film.addSample(x, 0, Color(values[x]), AovSample{});
    return film;
}

struct ReadBack {
    OIIO::ImageSpec spec;
    std::vector<uint32_t> values;  // every channel of every pixel, as stored
};

ReadBack readBack(const fs::path& file, OIIO::TypeDesc type) {
    ReadBack image;
    auto in = OIIO::ImageInput::open(file.string());
    EXPECT_TRUE(in) << OIIO::geterror();
    if (!in) return image;
    image.spec = in->spec();
    const size_t count = image.spec.image_pixels() * static_cast<size_t>(image.spec.nchannels);
    if (type == OIIO::TypeDesc::UINT16) {
        std::vector<uint16_t> raw(count);
        EXPECT_TRUE(in->read_image(0, 0, 0, image.spec.nchannels, type, raw.data()));
        image.values.assign(raw.begin(), raw.end());
    } else {
        std::vector<uint8_t> raw(count);
        EXPECT_TRUE(in->read_image(0, 0, 0, image.spec.nchannels, type, raw.data()));
        image.values.assign(raw.begin(), raw.end());
    }
    return image;
}

// Grey value of pixel x of the read-back row, checking the channels agree.
uint32_t grey(const ReadBack& image, size_t x) {
    EXPECT_EQ(image.values[3 * x], image.values[3 * x + 1]);
    EXPECT_EQ(image.values[3 * x], image.values[3 * x + 2]);
    return image.values[3 * x];
}

// These tests use the built-in config, so $OCIO is unset while they run.
class DisplayImageTest : public ::testing::Test {
  protected:
    void SetUp() override {
        if (const char* value = std::getenv("OCIO")) saved_ = value;
        ::unsetenv("OCIO");
    }
    void TearDown() override {
        if (saved_) ::setenv("OCIO", saved_->c_str(), 1);
    }

  private:
    std::optional<std::string> saved_;
};

TEST_F(DisplayImageTest, PngThroughStandardIsSrgbEncoded) {
    const fs::path file = test::scratchDir("film-png-standard") / "standard.png";
    writeImage(greyRow({0.0f, 0.18f, 1.0f, 4.0f, -1.0f}), file, {}, {});
    const ReadBack image = readBack(file, OIIO::TypeDesc::UINT8);

    EXPECT_EQ(image.spec.format, OIIO::TypeDesc::UINT8);
    EXPECT_EQ(image.spec.nchannels, 3);  // AOVs are EXR-only
    ASSERT_EQ(image.values.size(), 15u);
    EXPECT_EQ(grey(image, 0), 0u);
    EXPECT_EQ(grey(image, 1), 118u);  // 0.4614 * 255
    EXPECT_EQ(grey(image, 2), 255u);
    EXPECT_EQ(grey(image, 3), 255u);  // clamped
    EXPECT_EQ(grey(image, 4), 0u);    // clamped
}

TEST_F(DisplayImageTest, PngThroughRawIsTheLinearValue) {
    const fs::path file = test::scratchDir("film-png-raw") / "raw.png";
    OutputSettings settings;
    settings.color.view = "Raw";
    writeImage(greyRow({0.0f, 0.25f, 0.5f, 1.0f, 2.0f}), file, settings, {});
    const ReadBack image = readBack(file, OIIO::TypeDesc::UINT8);

    EXPECT_EQ(grey(image, 0), 0u);
    EXPECT_EQ(grey(image, 1), 64u);   // 63.75 rounded
    EXPECT_EQ(grey(image, 2), 128u);  // 127.5 rounded
    EXPECT_EQ(grey(image, 3), 255u);
    EXPECT_EQ(grey(image, 4), 255u);
}

TEST_F(DisplayImageTest, PngThroughFilmicKeepsHighlightsBelowWhite) {
    const fs::path file = test::scratchDir("film-png-filmic") / "filmic.png";
    OutputSettings settings;
    settings.color.view = "Filmic";
    writeImage(greyRow({0.18f, 1.0f, 16.0f}), file, settings, {});
    const ReadBack image = readBack(file, OIIO::TypeDesc::UINT8);

    EXPECT_LT(grey(image, 0), grey(image, 1));
    EXPECT_LT(grey(image, 1), grey(image, 2));
    EXPECT_LT(grey(image, 2), 255u);
    EXPECT_GT(grey(image, 2), 230u);
}

TEST_F(DisplayImageTest, PngIsTheCropOnly) {
    const fs::path file = test::scratchDir("film-png-crop") / "crop.png";
    Film film(6, 5, PixelRect{1, 2, 4, 4}, {});
    film.addSample(1, 2, Color(1.0f), AovSample{});
    writeImage(film, file, {}, {});
    const ReadBack image = readBack(file, OIIO::TypeDesc::UINT8);

    EXPECT_EQ(image.spec.width, 3);
    EXPECT_EQ(image.spec.height, 2);
    EXPECT_EQ(image.spec.x, 0);
    EXPECT_EQ(image.spec.y, 0);
    EXPECT_EQ(grey(image, 0), 255u);
    EXPECT_EQ(grey(image, 1), 0u);
}

TEST_F(DisplayImageTest, TiffIsSixteenBit) {
    const fs::path file = test::scratchDir("film-tif") / "deep.tif";
    writeImage(greyRow({0.18f, 1.0f}), file, {}, {});
    const ReadBack image = readBack(file, OIIO::TypeDesc::UINT16);

    EXPECT_EQ(image.spec.format, OIIO::TypeDesc::UINT16);
    // 0.46135 * 65535 = 30235; allow for OCIO's fast pow approximation.
    EXPECT_NEAR(static_cast<double>(grey(image, 0)), 30235.0, 20.0);
    EXPECT_EQ(grey(image, 1), 65535u);
}

TEST_F(DisplayImageTest, JpegAndUpperCaseExtensionsAreAccepted) {
    const fs::path dir = test::scratchDir("film-jpeg");
    for (const char* name : {"a.jpg", "b.JPEG", "c.PNG", "d.TIFF"}) {
        writeImage(greyRow({0.18f, 0.18f, 0.18f, 0.18f}), dir / name, {}, {});
        ASSERT_TRUE(fs::is_regular_file(dir / name)) << name;
    }
    const ReadBack jpeg = readBack(dir / "a.jpg", OIIO::TypeDesc::UINT8);
    EXPECT_EQ(jpeg.spec.nchannels, 3);
    EXPECT_NEAR(static_cast<double>(jpeg.values[0]), 118.0, 3.0);  // lossy, but close
    EXPECT_EQ(readBack(dir / "c.PNG", OIIO::TypeDesc::UINT8).values[0], 118u);

    // Nothing but the four images: no temporary files left behind.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 4);
}

TEST_F(DisplayImageTest, SoftwareTagIsWrittenWhereTheFormatHasOne) {
    const fs::path file = test::scratchDir("film-png-meta") / "meta.png";
    writeImage(greyRow({0.5f}), file, {}, {});
    const ReadBack image = readBack(file, OIIO::TypeDesc::UINT8);
    EXPECT_EQ(image.spec.get_string_attribute("Software"), "strahl " STRAHL_VERSION);
}

TEST_F(DisplayImageTest, AnUnknownViewFailsBeforeAnyFileIsCreated) {
    const fs::path dir = test::scratchDir("film-png-badview");
    OutputSettings settings;
    settings.color.view = "Vivid";
    EXPECT_THROW(writeImage(greyRow({0.5f}), dir / "x.png", settings, {}), Error);
    EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
}  // namespace strahl
