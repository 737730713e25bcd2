// The exact state of a part of a split render in its EXR (exact_part.h) and
// reading strahl EXRs back (exr_input.h): what is written comes back bit for
// bit, and what is not a strahl part is recognised as such.

#include "strahl/film/exact_part.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "film_test_helpers.h"
#include "strahl/core/error.h"
#include "strahl/film/exr_input.h"
#include "strahl/film/image_output.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

using test::kAllAovs;

// A film with negative, tiny and large sums in every buffer.
Film sampleFilm(const PixelRect& crop, const std::vector<AovKind>& aovs) {
    Film film(9, 7, crop, aovs);
    for (int s = 0; s < 5; ++s)
        for (int y = crop.y0; y < crop.y1; ++y)
            for (int x = crop.x0; x < crop.x1; ++x) {
                const float fx = float(x), fy = float(y), fs = float(s);
                AovSample aov;
                aov.hit = (x * y + s) % 4 != 0;
                aov.normal = Vec3(-std::sin(fx + fs), std::cos(fy), -1.0f);
                aov.depth = 3e6f * fx + 1e-6f * fs;
                aov.albedo = Color(0.1f * fs, 0.5f, 1e-30f);
                aov.position = Vec3(-1e7f * fx, fy, -fs);
                aov.objectId = uint32_t(x + 100 * s);
                film.addSample(x, y, Color(-fx, 1e5f * fs, 1e-20f * fy), aov);
            }
    return film;
}

void expectSameState(const Film& a, const Film& b) {
    const PixelRect& crop = a.crop();
    for (int y = crop.y0; y < crop.y1; ++y)
        for (int x = crop.x0; x < crop.x1; ++x) {
            const FilmPixel p = a.pixel(x, y), q = b.pixel(x, y);
            EXPECT_EQ(p.samples, q.samples);
            EXPECT_EQ(p.hits, q.hits);
            EXPECT_EQ(p.radiance, q.radiance);
            EXPECT_EQ(p.normal, q.normal);
            EXPECT_EQ(p.depth, q.depth);
            EXPECT_EQ(p.albedo, q.albedo);
            EXPECT_EQ(p.position, q.position);
            EXPECT_EQ(p.objectId, q.objectId);
            EXPECT_EQ(p.mean, q.mean);
            EXPECT_EQ(p.m2, q.m2);
        }
}

TEST(SampleRanges, FormatParseAndJoin) {
    EXPECT_EQ(formatRanges({{0, 2}, {5, 6}}), "0-2,5-6");
    const auto parsed = parseRanges("0-2,5-6");
    ASSERT_TRUE(parsed);
    ASSERT_EQ(parsed->size(), 2u);
    EXPECT_EQ((*parsed)[1].begin, 5u);
    EXPECT_EQ((*parsed)[1].end, 6u);
    for (const char* bad : {"", "2-2", "3-1", "0-2,1-4", "0-2,", "a-b", "0-2;5-6", "-1-2"})
        EXPECT_FALSE(parseRanges(bad)) << bad;
    const std::vector<SampleRange> joined = joinRanges({{5, 6}, {2, 5}, {0, 1}});
    EXPECT_EQ(formatRanges(joined), "0-1,2-6");
    SamplePart part{joined, "x"};
    EXPECT_EQ(part.sampleCount(), 5u);
}

TEST(ExactChannels, RoundTripEveryBufferBitForBit) {
    const PixelRect crop{2, 1, 8, 6};
    const Film film = sampleFilm(crop, kAllAovs);
    std::vector<std::string> names{"R", "G", "B"};
    std::vector<std::vector<float>> planes{film.resolveBeauty()};
    appendExactChannels(film, names, planes);
    // objectid's own channel is the AOV channel, written by image_output.
    names.push_back("objectid.X");
    planes.push_back(film.resolveAov(AovKind::ObjectId));
    EXPECT_TRUE(hasExactChannels(names));
    EXPECT_FALSE(hasExactChannels({"R", "G", "B", "depth.Z"}));

    // Interleave as an image reader delivers them (beauty plane has 3 channels).
    const size_t count = size_t(crop.width()) * size_t(crop.height());
    std::vector<float> pixels(count * names.size());
    for (size_t i = 0; i < count; ++i) {
        for (size_t c = 0; c < 3; ++c) pixels[i * names.size() + c] = planes[0][3 * i + c];
        for (size_t p = 1; p < planes.size(); ++p) pixels[i * names.size() + 2 + p] = planes[p][i];
    }
    Film back(9, 7, crop, kAllAovs);
    readExactChannels(back, names, pixels, "part.exr");
    expectSameState(film, back);

    // A channel that is not a 24-bit piece, and a missing one, name the file.
    pixels[5] = 0.5f;
    EXPECT_THAT(test::errorMessage([&] { readExactChannels(back, names, pixels, "part.exr"); }),
                testing::HasSubstr("part.exr: channel '"));
    names[4] = "renamed";
    EXPECT_THAT(test::errorMessage([&] { readExactChannels(back, names, pixels, "part.exr"); }),
                testing::HasSubstr("is missing"));
}

TEST(ExrInput, APartEXRReadsBackAsTheFilmThatWasWritten) {
    const fs::path dir = test::scratchDir("exr-part");
    for (bool exrFloat : {false, true}) {
        const PixelRect crop{1, 2, 9, 7};
        const Film film = sampleFilm(crop, kAllAovs);
        ImageMetadata metadata;
        metadata.spp = 5;
        metadata.integrator = "path";
        metadata.extra["scene"] = "test.json";
        metadata.part = SamplePart{{{10, 15}}, "settings"};
        OutputSettings settings;
        settings.exrFloat = exrFloat;
        const fs::path file = dir / "part.exr";
        writeImage(film, file, settings, metadata);

        const ExrHeader h = readExrHeader(file);
        EXPECT_TRUE(h.exact());
        EXPECT_EQ(h.exrFloat, exrFloat);
        EXPECT_EQ(h.fullWidth, 9);
        EXPECT_EQ(h.dataWindow.x0, 1);
        EXPECT_EQ(h.dataWindow.y1, 7);
        EXPECT_EQ(h.aovs, kAllAovs);
        EXPECT_EQ(h.samples, 5u);
        EXPECT_EQ(h.metadata.integrator, "path");
        EXPECT_EQ(h.metadata.extra.at("scene"), "test.json");
        EXPECT_EQ(formatRanges(h.metadata.part->ranges), "10-15");
        EXPECT_EQ(h.metadata.part->fingerprint, "settings");
        expectSameState(film, readExrFilm(h));
    }
}

TEST(ExrInput, APlainEXRGivesAnApproximateFilmOfItsSampleCount) {
    const fs::path dir = test::scratchDir("exr-plain");
    const PixelRect crop{0, 0, 9, 7};
    const Film film = sampleFilm(crop, kAllAovs);
    ImageMetadata metadata;
    metadata.spp = 5;
    OutputSettings settings;
    settings.exrFloat = true;
    writeImage(film, dir / "plain.exr", settings, metadata);
    const ExrHeader h = readExrHeader(dir / "plain.exr");
    EXPECT_FALSE(h.exact());
    const Film back = readExrFilm(h);
    EXPECT_EQ(back.sampleCount(3, 3), 5u);
    const std::vector<float> a = film.resolveBeauty(), b = back.resolveBeauty();
    for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-6f * std::abs(a[i]));
    EXPECT_EQ(film.resolveAov(AovKind::ObjectId), back.resolveAov(AovKind::ObjectId));
}

TEST(ExrInput, RejectsWhatIsNotAStrahlEXR) {
    const fs::path dir = test::scratchDir("exr-bad");
    EXPECT_THAT(test::errorMessage([&] { readExrHeader(dir / "missing.exr"); }),
                testing::HasSubstr("missing.exr: cannot read: no such file"));
    const Film film(4, 4, PixelRect{0, 0, 4, 4}, {});
    ImageMetadata metadata;
    metadata.spp = 1;
    writeImage(film, dir / "image.png", OutputSettings{}, metadata);
    EXPECT_THAT(test::errorMessage([&] { readExrHeader(dir / "image.png"); }),
                testing::HasSubstr("image.png: not an OpenEXR image"));
    metadata.spp = 0;  // no sample count: not from strahl render
    writeImage(film, dir / "nospp.exr", OutputSettings{}, metadata);
    EXPECT_THAT(test::errorMessage([&] { readExrHeader(dir / "nospp.exr"); }),
                testing::HasSubstr("nospp.exr: has no sample count"));
}

}  // namespace
}  // namespace strahl
