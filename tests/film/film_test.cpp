// Film: box-filter accumulation, crop windows and the AOV conventions of film.h.

#include "strahl/film/film.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "strahl/core/error.h"

namespace strahl {
namespace {

AovSample hitSample(Vec3 normal, float depth, Color albedo) {
    AovSample s;
    s.hit = true;
    s.normal = normal;
    s.depth = depth;
    s.albedo = albedo;
    return s;
}

const AovSample kMiss{};

TEST(Film, AovNamesAndChannelCounts) {
    EXPECT_STREQ(aovName(AovKind::Normal), "normal");
    EXPECT_STREQ(aovName(AovKind::Depth), "depth");
    EXPECT_STREQ(aovName(AovKind::Albedo), "albedo");
    EXPECT_EQ(aovChannels(AovKind::Normal), 3);
    EXPECT_EQ(aovChannels(AovKind::Depth), 1);
    EXPECT_EQ(aovChannels(AovKind::Albedo), 3);
}

TEST(Film, BeautyIsTheMeanOfThePixelsSamples) {
    Film film(2, 2, PixelRect{0, 0, 2, 2}, {});
    film.addSample(1, 0, Color(1.0f, 2.0f, 3.0f), kMiss);
    film.addSample(1, 0, Color(3.0f, 0.0f, 1.0f), kMiss);
    film.addSample(1, 0, Color(2.0f, 1.0f, 2.0f), kMiss);
    film.addSample(0, 1, Color(0.5f), kMiss);

    const std::vector<float> rgb = film.resolveBeauty();
    ASSERT_EQ(rgb.size(), 2u * 2u * 3u);
    // Pixel (1, 0) is the second of the top row.
    EXPECT_FLOAT_EQ(rgb[3], 2.0f);
    EXPECT_FLOAT_EQ(rgb[4], 1.0f);
    EXPECT_FLOAT_EQ(rgb[5], 2.0f);
    // Pixel (0, 1) starts the second row.
    EXPECT_FLOAT_EQ(rgb[6], 0.5f);
    EXPECT_FLOAT_EQ(rgb[7], 0.5f);
    EXPECT_FLOAT_EQ(rgb[8], 0.5f);
}

TEST(Film, PixelsWithoutSamplesResolveToBlack) {
    Film film(3, 1, PixelRect{0, 0, 3, 1}, {AovKind::Normal, AovKind::Albedo});
    film.addSample(1, 0, Color(1.0f), hitSample(Vec3(0, 0, 1), 1.0f, Color(0.5f)));
    const std::vector<float> rgb = film.resolveBeauty();
    const std::vector<float> normal = film.resolveAov(AovKind::Normal);
    const std::vector<float> albedo = film.resolveAov(AovKind::Albedo);
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(rgb[c], 0.0f);
        EXPECT_EQ(rgb[6 + c], 0.0f);
        EXPECT_EQ(normal[c], 0.0f);
        EXPECT_EQ(albedo[6 + c], 0.0f);
        EXPECT_FALSE(std::isnan(rgb[c]));
    }
}

TEST(Film, CropWindowMapsFullImageCoordinates) {
    // A 10x8 image rendering only [3, 6) x [2, 5).
    Film film(10, 8, PixelRect{3, 2, 6, 5}, {});
    EXPECT_EQ(film.fullWidth(), 10);
    EXPECT_EQ(film.fullHeight(), 8);
    EXPECT_EQ(film.crop().x0, 3);
    EXPECT_EQ(film.crop().y1, 5);

    film.addSample(3, 2, Color(1.0f, 0.0f, 0.0f), kMiss);  // top-left of the crop
    film.addSample(5, 4, Color(0.0f, 0.0f, 7.0f), kMiss);  // bottom-right of the crop
    film.addSample(4, 3, Color(0.0f, 2.0f, 0.0f), kMiss);  // centre

    const std::vector<float> rgb = film.resolveBeauty();
    ASSERT_EQ(rgb.size(), 3u * 3u * 3u);
    EXPECT_FLOAT_EQ(rgb[0], 1.0f);
    EXPECT_FLOAT_EQ(rgb[(1 * 3 + 1) * 3 + 1], 2.0f);
    EXPECT_FLOAT_EQ(rgb[(2 * 3 + 2) * 3 + 2], 7.0f);
    float total = 0.0f;
    for (float v : rgb) total += v;
    EXPECT_FLOAT_EQ(total, 10.0f);  // nothing landed anywhere else
}

TEST(Film, NormalAndAlbedoAreMeansOverAllSamplesWithZeroForMisses) {
    Film film(1, 1, PixelRect{0, 0, 1, 1}, {AovKind::Normal, AovKind::Albedo});
    film.addSample(0, 0, Color(0.0f), hitSample(Vec3(0, 0, 1), 2.0f, Color(0.8f, 0.4f, 0.2f)));
    film.addSample(0, 0, Color(0.0f), hitSample(Vec3(0, 1, 0), 2.0f, Color(0.4f, 0.4f, 0.4f)));
    film.addSample(0, 0, Color(0.0f), kMiss);
    film.addSample(0, 0, Color(0.0f), kMiss);

    const std::vector<float> normal = film.resolveAov(AovKind::Normal);
    ASSERT_EQ(normal.size(), 3u);
    EXPECT_FLOAT_EQ(normal[0], 0.0f);
    EXPECT_FLOAT_EQ(normal[1], 0.25f);
    EXPECT_FLOAT_EQ(normal[2], 0.25f);

    const std::vector<float> albedo = film.resolveAov(AovKind::Albedo);
    ASSERT_EQ(albedo.size(), 3u);
    EXPECT_FLOAT_EQ(albedo[0], 0.3f);
    EXPECT_FLOAT_EQ(albedo[1], 0.2f);
    EXPECT_FLOAT_EQ(albedo[2], 0.15f);
}

TEST(Film, DepthIsTheMeanOverHitsAndInfiniteWithoutHits) {
    Film film(3, 1, PixelRect{0, 0, 3, 1}, {AovKind::Depth});
    // Pixel 0: two hits and a miss; the miss does not count.
    film.addSample(0, 0, Color(0.0f), hitSample(Vec3(0, 0, 1), 2.0f, Color(0.0f)));
    film.addSample(0, 0, Color(0.0f), hitSample(Vec3(0, 0, 1), 4.0f, Color(0.0f)));
    film.addSample(0, 0, Color(0.0f), kMiss);
    // Pixel 1: only misses. Pixel 2: no samples at all.
    film.addSample(1, 0, Color(1.0f), kMiss);

    const std::vector<float> depth = film.resolveAov(AovKind::Depth);
    ASSERT_EQ(depth.size(), 3u);
    EXPECT_FLOAT_EQ(depth[0], 3.0f);
    EXPECT_TRUE(std::isinf(depth[1]) && depth[1] > 0.0f);
    EXPECT_TRUE(std::isinf(depth[2]) && depth[2] > 0.0f);
}

TEST(Film, AovsAreIndependentOfTheBeautyPass) {
    Film film(1, 1, PixelRect{0, 0, 1, 1}, {AovKind::Albedo});
    film.addSample(0, 0, Color(4.0f), hitSample(Vec3(1, 0, 0), 1.0f, Color(0.5f)));
    film.addSample(0, 0, Color(0.0f), hitSample(Vec3(1, 0, 0), 1.0f, Color(0.5f)));
    EXPECT_FLOAT_EQ(film.resolveBeauty()[0], 2.0f);
    EXPECT_FLOAT_EQ(film.resolveAov(AovKind::Albedo)[0], 0.5f);
}

TEST(Film, ResolvingAnAovThatWasNotRequestedIsAnError) {
    Film film(2, 2, PixelRect{0, 0, 2, 2}, {AovKind::Depth});
    try {
        film.resolveAov(AovKind::Normal);
        FAIL() << "expected strahl::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("normal"), std::string::npos) << e.what();
    }
}

TEST(Film, RejectsCropsOutsideTheImageAndEmptyCrops) {
    EXPECT_THROW(Film(4, 4, PixelRect{0, 0, 5, 4}, {}), Error);
    EXPECT_THROW(Film(4, 4, PixelRect{-1, 0, 2, 2}, {}), Error);
    EXPECT_THROW(Film(4, 4, PixelRect{2, 2, 2, 3}, {}), Error);
    EXPECT_THROW(Film(0, 4, PixelRect{0, 0, 0, 4}, {}), Error);
    EXPECT_NO_THROW(Film(4, 4, PixelRect{3, 3, 4, 4}, {}));
}

TEST(Film, RejectsAnAovRequestedTwice) {
    try {
        Film film(2, 2, PixelRect{0, 0, 2, 2}, {AovKind::Depth, AovKind::Normal, AovKind::Depth});
        FAIL() << "expected strahl::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("depth"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace strahl
