// EXR output: written with writeImage, read back with OpenImageIO. Channel
// names, half vs float, values, crop windows and metadata.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "strahl/film/film.h"
#include "strahl/film/image_output.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

// An EXR read back as float, with its channels found by name.
struct ExrImage {
    OIIO::ImageSpec spec;
    std::vector<float> pixels;

    int channel(const std::string& name) const {
        for (size_t i = 0; i < spec.channelnames.size(); ++i)
            if (spec.channelnames[i] == name) return static_cast<int>(i);
        ADD_FAILURE() << "no channel " << name;
        return 0;
    }
    // (x, y) relative to the data window.
    float at(int x, int y, const std::string& name) const {
        const size_t pixel =
            static_cast<size_t>(y) * static_cast<size_t>(spec.width) + static_cast<size_t>(x);
        return pixels[pixel * static_cast<size_t>(spec.nchannels) +
                      static_cast<size_t>(channel(name))];
    }
};

ExrImage readExr(const fs::path& file) {
    ExrImage image;
    auto in = OIIO::ImageInput::open(file.string());
    EXPECT_TRUE(in) << OIIO::geterror();
    if (!in) return image;
    image.spec = in->spec();
    image.pixels.resize(image.spec.image_pixels() * static_cast<size_t>(image.spec.nchannels));
    EXPECT_TRUE(
        in->read_image(0, 0, 0, image.spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        << in->geterror();
    return image;
}

AovSample hit(Vec3 normal, float depth, Color albedo) {
    AovSample s;
    s.hit = true;
    s.normal = normal;
    s.depth = depth;
    s.albedo = albedo;
    return s;
}

// A 3x2 film with all AOVs: pixel (x, y) has radiance (x, y, 0.1) and hits at
// depth 1 + x + y, except (2, 1), which misses.
Film allAovsFilm() {
    Film film(3, 2, PixelRect{0, 0, 3, 2}, {AovKind::Normal, AovKind::Depth, AovKind::Albedo});
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 3; ++x) {
            const Color radiance(static_cast<float>(x), static_cast<float>(y), 0.1f);
            if (x == 2 && y == 1)
                film.addSample(x, y, radiance, AovSample{});
            else
                film.addSample(x, y, radiance,
                               hit(Vec3(0.0f, 1.0f, 0.0f), static_cast<float>(1 + x + y),
                                   Color(0.25f, 0.5f, 0.75f)));
        }
    }
    return film;
}

TEST(ExrOutput, ChannelsAreBeautyThenEachAov) {
    const fs::path file = test::scratchDir("film-exr-channels") / "aovs.exr";
    writeImage(allAovsFilm(), file, {}, {});
    const ExrImage image = readExr(file);

    // OpenEXR stores channels sorted by name, so compare as sets.
    const std::set<std::string> names(image.spec.channelnames.begin(),
                                      image.spec.channelnames.end());
    const std::set<std::string> expected{"R",        "G",       "B",        "normal.X", "normal.Y",
                                         "normal.Z", "depth.Z", "albedo.R", "albedo.G", "albedo.B"};
    EXPECT_EQ(names, expected);
    EXPECT_EQ(image.spec.nchannels, 10);
}

// A 2x1 film with every AOV: pixel 0 has two hits on object 12 and 70001 at
// positions (1, 2, 3) and (3, 2, 1) with radiance 1 and 3; pixel 1 one miss.
Film everyAovFilm() {
    std::vector<AovKind> kinds;
    for (std::string_view name : aovNames()) kinds.push_back(*aovFromName(name));
    Film film(2, 1, PixelRect{0, 0, 2, 1}, kinds);
    AovSample a = hit(Vec3(0.0f, 0.0f, 1.0f), 2.0f, Color(0.5f));
    a.position = Vec3(1.0f, 2.0f, 3.0f);
    a.objectId = 70001;  // beyond half's range (65504): must survive as float
    AovSample b = a;
    b.position = Vec3(3.0f, 2.0f, 1.0f);
    b.objectId = 12;
    film.addSample(0, 0, Color(1.0f, 2.0f, 0.0f), a);
    film.addSample(0, 0, Color(3.0f, 2.0f, 4.0f), b);
    film.addSample(1, 0, Color(0.25f), AovSample{});
    return film;
}

TEST(ExrOutput, EveryAovIsANamedLayer) {
    const fs::path file = test::scratchDir("film-exr-every-aov") / "every.exr";
    writeImage(everyAovFilm(), file, {}, {});
    const ExrImage image = readExr(file);

    const std::set<std::string> names(image.spec.channelnames.begin(),
                                      image.spec.channelnames.end());
    const std::set<std::string> expected{
        "R",          "G",          "B",          "normal.X",   "normal.Y",   "normal.Z",
        "depth.Z",    "albedo.R",   "albedo.G",   "albedo.B",   "position.X", "position.Y",
        "position.Z", "objectid.X", "variance.R", "variance.G", "variance.B", "samples.X"};
    EXPECT_EQ(names, expected);
    EXPECT_EQ(image.spec.nchannels, 18);

    // Values: the mean position over hits, the first sample's id, the variance
    // of the mean (red: 1 and 3, s^2 = 2, / 2 samples = 1; green: constant).
    EXPECT_FLOAT_EQ(image.at(0, 0, "position.X"), 2.0f);
    EXPECT_FLOAT_EQ(image.at(0, 0, "position.Z"), 2.0f);
    EXPECT_EQ(image.at(0, 0, "objectid.X"), 70001.0f);
    EXPECT_FLOAT_EQ(image.at(0, 0, "variance.R"), 1.0f);
    EXPECT_EQ(image.at(0, 0, "variance.G"), 0.0f);
    EXPECT_FLOAT_EQ(image.at(0, 0, "variance.B"), 4.0f);
    // The missed pixel: no position, no object, a single sample.
    EXPECT_EQ(image.at(1, 0, "position.Y"), 0.0f);
    EXPECT_EQ(image.at(1, 0, "objectid.X"), -1.0f);
    EXPECT_EQ(image.at(1, 0, "variance.B"), 0.0f);
    EXPECT_FLOAT_EQ(image.at(1, 0, "R"), 0.25f);
    EXPECT_EQ(image.at(0, 0, "samples.X"), 2.0f);
    EXPECT_EQ(image.at(1, 0, "samples.X"), 1.0f);
}

TEST(ExrOutput, ObjectIdsAndSampleCountsAreFloatInAHalfFile) {
    const fs::path file = test::scratchDir("film-exr-objectid-float") / "ids.exr";
    writeImage(everyAovFilm(), file, {}, {});
    const ExrImage image = readExr(file);

    ASSERT_EQ(image.spec.channelformats.size(), 18u);
    for (size_t c = 0; c < image.spec.channelnames.size(); ++c) {
        // Counts too: half holds integers exactly only up to 2048.
        const bool id = image.spec.channelnames[c] == "objectid.X" ||
                        image.spec.channelnames[c] == "samples.X";
        EXPECT_EQ(image.spec.channelformats[c], id ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF)
            << image.spec.channelnames[c];
    }
}

TEST(ExrOutput, FloatFileHasOneFormatForAllChannels) {
    const fs::path file = test::scratchDir("film-exr-all-float") / "float.exr";
    OutputSettings settings;
    settings.exrFloat = true;
    writeImage(everyAovFilm(), file, settings, {});
    const ExrImage image = readExr(file);

    EXPECT_EQ(image.spec.format, OIIO::TypeDesc::FLOAT);
    EXPECT_TRUE(image.spec.channelformats.empty());
    EXPECT_EQ(image.at(0, 0, "objectid.X"), 70001.0f);
}

TEST(ExrOutput, HalfByDefaultWithTheFilmsValues) {
    const fs::path file = test::scratchDir("film-exr-half") / "half.exr";
    writeImage(allAovsFilm(), file, {}, {});
    const ExrImage image = readExr(file);

    EXPECT_EQ(image.spec.format, OIIO::TypeDesc::HALF);
    EXPECT_EQ(image.spec.get_string_attribute("compression"), "zip");
    EXPECT_FLOAT_EQ(image.at(2, 0, "R"), 2.0f);
    EXPECT_FLOAT_EQ(image.at(1, 1, "G"), 1.0f);
    EXPECT_NEAR(image.at(0, 0, "B"), 0.1f, 1e-4f);  // half has 11 significant bits
    EXPECT_FLOAT_EQ(image.at(1, 0, "normal.Y"), 1.0f);
    EXPECT_FLOAT_EQ(image.at(1, 0, "normal.X"), 0.0f);
    EXPECT_FLOAT_EQ(image.at(1, 1, "depth.Z"), 3.0f);
    EXPECT_FLOAT_EQ(image.at(0, 1, "albedo.R"), 0.25f);
    EXPECT_FLOAT_EQ(image.at(0, 1, "albedo.B"), 0.75f);
    // The missed pixel: no depth (+inf), zero normal and albedo.
    EXPECT_TRUE(std::isinf(image.at(2, 1, "depth.Z")));
    EXPECT_GT(image.at(2, 1, "depth.Z"), 0.0f);
    EXPECT_EQ(image.at(2, 1, "normal.Y"), 0.0f);
    EXPECT_EQ(image.at(2, 1, "albedo.G"), 0.0f);
}

TEST(ExrOutput, FloatOnRequestKeepsFullPrecision) {
    const fs::path file = test::scratchDir("film-exr-float") / "float.exr";
    Film film(1, 1, PixelRect{0, 0, 1, 1}, {});
    film.addSample(0, 0, Color(0.1f, 1.0e-7f, 123456.0f), AovSample{});
    OutputSettings settings;
    settings.exrFloat = true;
    writeImage(film, file, settings, {});
    const ExrImage image = readExr(file);

    EXPECT_EQ(image.spec.format, OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(image.spec.nchannels, 3);  // no AOVs requested
    EXPECT_EQ(image.at(0, 0, "R"), 0.1f);
    EXPECT_EQ(image.at(0, 0, "G"), 1.0e-7f);
    EXPECT_EQ(image.at(0, 0, "B"), 123456.0f);
}

TEST(ExrOutput, CropIsTheDataWindowInsideTheFullDisplayWindow) {
    const fs::path file = test::scratchDir("film-exr-crop") / "crop.exr";
    Film film(8, 6, PixelRect{2, 1, 5, 4}, {AovKind::Depth});
    film.addSample(2, 1, Color(1.0f), hit(Vec3(0.0f, 0.0f, 1.0f), 5.0f, Color(0.5f)));
    film.addSample(4, 3, Color(3.0f), hit(Vec3(0.0f, 0.0f, 1.0f), 7.0f, Color(0.5f)));
    writeImage(film, file, {}, {});
    const ExrImage image = readExr(file);

    EXPECT_EQ(image.spec.x, 2);
    EXPECT_EQ(image.spec.y, 1);
    EXPECT_EQ(image.spec.width, 3);
    EXPECT_EQ(image.spec.height, 3);
    EXPECT_EQ(image.spec.full_x, 0);
    EXPECT_EQ(image.spec.full_y, 0);
    EXPECT_EQ(image.spec.full_width, 8);
    EXPECT_EQ(image.spec.full_height, 6);
    EXPECT_FLOAT_EQ(image.at(0, 0, "R"), 1.0f);
    EXPECT_FLOAT_EQ(image.at(2, 2, "R"), 3.0f);
    EXPECT_FLOAT_EQ(image.at(2, 2, "depth.Z"), 7.0f);
    EXPECT_TRUE(std::isinf(image.at(1, 1, "depth.Z")));
}

TEST(ExrOutput, MetadataIsStoredInTheHeader) {
    const fs::path file = test::scratchDir("film-exr-metadata") / "meta.exr";
    ImageMetadata metadata;
    metadata.renderSeconds = 12.5;
    metadata.spp = 64;
    metadata.integrator = "direct";
    metadata.camera = "perspective, fov 45";
    metadata.worldToCamera = Mat4(1.0f);
    metadata.worldToCamera[3] = Vec4(1.0f, 2.0f, 3.0f, 1.0f);  // translation column
    metadata.extra = {{"scene", "cornell.json"}, {"seed", "7"}};
    writeImage(allAovsFilm(), file, {}, metadata);
    const OIIO::ImageSpec spec = readExr(file).spec;

    EXPECT_EQ(spec.get_string_attribute("Software"), "strahl " STRAHL_VERSION);
    EXPECT_EQ(spec.get_string_attribute("strahl:version"), STRAHL_VERSION);
    const OIIO::ParamValue* time = spec.find_attribute("strahl:renderTime");
    ASSERT_NE(time, nullptr);
    EXPECT_EQ(time->type(), OIIO::TypeDesc::FLOAT);
    EXPECT_FLOAT_EQ(time->get_float(), 12.5f);
    const OIIO::ParamValue* spp = spec.find_attribute("strahl:spp");
    ASSERT_NE(spp, nullptr);
    EXPECT_EQ(spp->type(), OIIO::TypeDesc::INT);
    EXPECT_EQ(spp->get_int(), 64);
    EXPECT_EQ(spec.get_string_attribute("strahl:integrator"), "direct");
    EXPECT_EQ(spec.get_string_attribute("strahl:camera"), "perspective, fov 45");
    EXPECT_EQ(spec.get_string_attribute("strahl:scene"), "cornell.json");
    EXPECT_EQ(spec.get_string_attribute("strahl:seed"), "7");

    const OIIO::ParamValue* matrix = spec.find_attribute("worldToCamera");
    ASSERT_NE(matrix, nullptr);
    ASSERT_EQ(matrix->type(), OIIO::TypeMatrix44);
    const float* m = static_cast<const float*>(matrix->data());
    // Row-vector convention (Imath): the translation is the last row.
    EXPECT_FLOAT_EQ(m[12], 1.0f);
    EXPECT_FLOAT_EQ(m[13], 2.0f);
    EXPECT_FLOAT_EQ(m[14], 3.0f);
    EXPECT_FLOAT_EQ(m[0], 1.0f);
    EXPECT_FLOAT_EQ(m[3], 0.0f);
}

TEST(ExrOutput, OverwritesAnExistingFileAndLeavesNothingElse) {
    const fs::path dir = test::scratchDir("film-exr-overwrite");
    const fs::path file = dir / "again.exr";
    Film first(1, 1, PixelRect{0, 0, 1, 1}, {});
    first.addSample(0, 0, Color(1.0f), AovSample{});
    writeImage(first, file, {}, {});
    Film second(1, 1, PixelRect{0, 0, 1, 1}, {});
    second.addSample(0, 0, Color(2.0f), AovSample{});
    writeImage(second, file, {}, {});

    EXPECT_FLOAT_EQ(readExr(file).at(0, 0, "R"), 2.0f);
    std::vector<std::string> entries;
    for (const auto& entry : fs::directory_iterator(dir))
        entries.push_back(entry.path().filename().string());
    EXPECT_EQ(entries, std::vector<std::string>{"again.exr"});
}

}  // namespace
}  // namespace strahl
