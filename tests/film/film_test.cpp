// Film: box-filter accumulation, crop windows and the AOV conventions of film.h.

#include "strahl/film/film.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>

#include "strahl/core/error.h"
#include "test_support.h"

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
    EXPECT_STREQ(aovName(AovKind::Position), "position");
    EXPECT_STREQ(aovName(AovKind::ObjectId), "objectid");
    EXPECT_STREQ(aovName(AovKind::Variance), "variance");
    EXPECT_EQ(aovChannels(AovKind::Position), 3);
    EXPECT_EQ(aovChannels(AovKind::ObjectId), 1);
    EXPECT_EQ(aovChannels(AovKind::Variance), 3);
    EXPECT_STREQ(aovName(AovKind::Samples), "samples");
    EXPECT_EQ(aovChannels(AovKind::Samples), 1);
    // aovNames() lists every kind in enum order, and aovFromName inverts it.
    ASSERT_EQ(aovNames().size(), 7u);
    for (size_t i = 0; i < aovNames().size(); ++i) {
        const std::optional<AovKind> kind = aovFromName(aovNames()[i]);
        ASSERT_TRUE(kind.has_value()) << aovNames()[i];
        EXPECT_EQ(static_cast<size_t>(*kind), i);
        EXPECT_EQ(aovNames()[i], aovName(*kind));
    }
    EXPECT_FALSE(aovFromName("objectID").has_value());
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

AovSample hitAt(Vec3 position, uint32_t objectId) {
    AovSample s = hitSample(Vec3(0, 0, 1), 1.0f, Color(0.5f));
    s.position = position;
    s.objectId = objectId;
    return s;
}

// The unbiased sample variance of `values`, divided by their count: the
// variance of their mean, computed in double by the two-pass formula.
double varianceOfMean(const std::vector<double>& values) {
    const double n = static_cast<double>(values.size());
    double mean = 0.0;
    for (double v : values) mean += v;
    mean /= n;
    double squares = 0.0;
    for (double v : values) squares += (v - mean) * (v - mean);
    return squares / (n - 1.0) / n;
}

TEST(Film, VarianceIsTheVarianceOfTheBeautyMeanPerChannel) {
    Film film(3, 1, PixelRect{0, 0, 3, 1}, {AovKind::Variance});
    // Pixel 0: red 1, 2, 4, 8, 3; green constant 0.5; blue 0, 10, 0, 10, 0.
    const std::vector<double> red{1, 2, 4, 8, 3}, blue{0, 10, 0, 10, 0};
    for (size_t k = 0; k < red.size(); ++k)
        film.addSample(0, 0,
                       Color(static_cast<float>(red[k]), 0.5f, static_cast<float>(blue[k])),
                       k % 2 ? kMiss : hitSample(Vec3(0, 0, 1), 1.0f, Color(0.2f)));
    // Pixel 1: a single sample; pixel 2: none.
    film.addSample(1, 0, Color(7.0f), kMiss);

    const std::vector<float> variance = film.resolveAov(AovKind::Variance);
    ASSERT_EQ(variance.size(), 9u);
    EXPECT_NEAR(variance[0], varianceOfMean(red), 1e-5 * varianceOfMean(red));  // 7.3 / 5
    EXPECT_EQ(variance[1], 0.0f);
    EXPECT_NEAR(variance[2], varianceOfMean(blue), 1e-5 * varianceOfMean(blue));  // 30 / 5
    for (size_t c = 3; c < 9; ++c) EXPECT_EQ(variance[c], 0.0f) << "channel " << c;
    // The variance AOV does not change the beauty pass.
    EXPECT_FLOAT_EQ(film.resolveBeauty()[0], 3.6f);
}

TEST(Film, VarianceIsStableForALargeMean) {
    // 64 values 4096 + 0.125 k, k = 0 .. 15: a sample variance of 0.34 under a
    // squared mean of 1.7e7, where the sum-of-squares formula in float gives 0.
    Film film(1, 1, PixelRect{0, 0, 1, 1}, {AovKind::Variance});
    std::vector<double> values;
    for (int i = 0; i < 64; ++i) {
        const double v = 4096.0 + 0.125 * ((i * 37) % 16);
        values.push_back(v);
        film.addSample(0, 0, Color(static_cast<float>(v)), kMiss);
    }
    const double expected = varianceOfMean(values);
    const std::vector<float> variance = film.resolveAov(AovKind::Variance);
    for (float v : variance) EXPECT_NEAR(v, expected, 1e-3 * expected);
}

TEST(Film, VarianceOfConstantSamplesIsExactlyZero) {
    Film film(1, 1, PixelRect{0, 0, 1, 1}, {AovKind::Variance});
    for (int i = 0; i < 1000; ++i) film.addSample(0, 0, Color(0.1f, 3.3f, 1e5f), kMiss);
    for (float v : film.resolveAov(AovKind::Variance)) EXPECT_EQ(v, 0.0f);
}

TEST(Film, ObjectIdIsTheFirstSamplesIdNotAnAverage) {
    Film film(5, 1, PixelRect{0, 0, 5, 1}, {AovKind::ObjectId});
    // Pixel 0: the first sample hits object 7; later ones hit 3 or miss.
    film.addSample(0, 0, Color(0.0f), hitAt(Vec3(0.0f), 7));
    film.addSample(0, 0, Color(0.0f), hitAt(Vec3(0.0f), 3));
    film.addSample(0, 0, Color(0.0f), kMiss);
    // Pixel 1: the first sample misses, so the pixel is -1 whatever follows.
    film.addSample(1, 0, Color(0.0f), kMiss);
    film.addSample(1, 0, Color(0.0f), hitAt(Vec3(0.0f), 5));
    // Pixel 2: object 0 is an id like any other. Pixel 3: no samples.
    film.addSample(2, 0, Color(0.0f), hitAt(Vec3(0.0f), 0));
    // Pixel 4: 2^24, the largest id a float still tells from its neighbours.
    film.addSample(4, 0, Color(0.0f), hitAt(Vec3(0.0f), 16777216u));

    const std::vector<float> id = film.resolveAov(AovKind::ObjectId);
    ASSERT_EQ(id.size(), 5u);
    EXPECT_EQ(id[0], 7.0f);
    EXPECT_EQ(id[1], -1.0f);
    EXPECT_EQ(id[2], 0.0f);
    EXPECT_EQ(id[3], -1.0f);
    EXPECT_EQ(id[4], 16777216.0f);
}

TEST(Film, PositionIsTheMeanOverHitsAndZeroWithout) {
    Film film(3, 1, PixelRect{0, 0, 3, 1}, {AovKind::Position});
    film.addSample(0, 0, Color(0.0f), hitAt(Vec3(1.0f, 2.0f, -3.0f), 1));
    film.addSample(0, 0, Color(0.0f), kMiss);  // does not pull the mean towards 0
    film.addSample(0, 0, Color(0.0f), hitAt(Vec3(3.0f, 2.0f, -1.0f), 1));
    film.addSample(1, 0, Color(1.0f), kMiss);

    const std::vector<float> position = film.resolveAov(AovKind::Position);
    ASSERT_EQ(position.size(), 9u);
    EXPECT_FLOAT_EQ(position[0], 2.0f);
    EXPECT_FLOAT_EQ(position[1], 2.0f);
    EXPECT_FLOAT_EQ(position[2], -2.0f);
    for (size_t c = 3; c < 9; ++c) EXPECT_EQ(position[c], 0.0f) << "channel " << c;
}

TEST(Film, EveryAovAloneIsFiniteForHitsMissesAndEmptyPixels) {
    for (std::string_view name : aovNames()) {
        const AovKind kind = *aovFromName(name);
        Film film(3, 1, PixelRect{0, 0, 3, 1}, {kind});
        film.addSample(0, 0, Color(1.0f), hitAt(Vec3(1.0f), 4));
        film.addSample(0, 0, Color(2.0f), kMiss);
        film.addSample(1, 0, Color(3.0f), kMiss);
        const std::vector<float> values = film.resolveAov(kind);
        ASSERT_EQ(values.size(), 3u * static_cast<size_t>(aovChannels(kind))) << name;
        for (float v : values) {
            EXPECT_FALSE(std::isnan(v)) << name;
            // Only depth has a non-finite value: +inf where nothing was hit.
            EXPECT_TRUE(kind == AovKind::Depth || std::isfinite(v)) << name;
        }
    }
}

TEST(Film, AllAovsTogetherKeepTheirOwnSemantics) {
    Film film(1, 1, PixelRect{0, 0, 1, 1},
              {AovKind::Variance, AovKind::ObjectId, AovKind::Position, AovKind::Depth,
               AovKind::Normal, AovKind::Albedo});
    AovSample first = hitAt(Vec3(0.0f, 0.0f, 4.0f), 9);
    first.depth = 2.0f;
    AovSample second = hitAt(Vec3(0.0f, 0.0f, 2.0f), 11);
    second.depth = 4.0f;
    film.addSample(0, 0, Color(1.0f), first);
    film.addSample(0, 0, Color(3.0f), second);
    film.addSample(0, 0, Color(2.0f), kMiss);
    EXPECT_FLOAT_EQ(film.resolveAov(AovKind::Depth)[0], 3.0f);
    EXPECT_FLOAT_EQ(film.resolveAov(AovKind::Position)[2], 3.0f);
    EXPECT_EQ(film.resolveAov(AovKind::ObjectId)[0], 9.0f);
    EXPECT_FLOAT_EQ(film.resolveAov(AovKind::Normal)[2], 2.0f / 3.0f);
    EXPECT_FLOAT_EQ(film.resolveAov(AovKind::Variance)[0], 1.0f / 3.0f);  // s^2 = 1, n = 3
    EXPECT_FLOAT_EQ(film.resolveBeauty()[0], 2.0f);
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

// Distributed rendering moves finished tiles between films as packed bytes:
// unpacking into a fresh film must reproduce exactly the pixels of the tile,
// every AOV and the variance state included, and leave the others untouched.
TEST(Film, PackedPixelsUnpackIntoAnotherFilmBitForBit) {
    const std::vector<AovKind> all{AovKind::Normal,   AovKind::Depth,    AovKind::Albedo,
                                   AovKind::Position, AovKind::ObjectId, AovKind::Variance};
    const PixelRect crop{1, 1, 9, 7};
    Film source(10, 8, crop, all), target(10, 8, crop, all);
    for (int y = crop.y0; y < crop.y1; ++y)
        for (int x = crop.x0; x < crop.x1; ++x)
            for (int s = 0; s < 3; ++s) {
                const float fx = float(x), fy = float(y), fs = float(s);
                AovSample aov;
                aov.hit = (x + s) % 2 == 0;
                aov.normal = Vec3(0.1f * fx, 0.2f * fy, 0.3f * fs);
                aov.depth = 1.0f + fx + 0.5f * fs;
                aov.albedo = Color(0.25f * fs);
                aov.position = Vec3(fx, fy, fs);
                aov.objectId = uint32_t(x * 7 + y);
                source.addSample(x, y, Color(0.1f * fx, 0.3f * fs, 1.0f / (1.0f + fy)), aov);
            }
    const PixelRect tile{3, 2, 7, 5};
    const std::vector<std::byte> bytes = source.packPixels(tile);
    target.unpackPixels(tile, bytes, "tile");
    const std::vector<float> a = source.resolveBeauty(), b = target.resolveBeauty();
    for (int y = crop.y0; y < crop.y1; ++y)
        for (int x = crop.x0; x < crop.x1; ++x) {
            const bool inTile = x >= tile.x0 && x < tile.x1 && y >= tile.y0 && y < tile.y1;
            EXPECT_EQ(target.sampleCount(x, y), inTile ? 3u : 0u) << x << "," << y;
            const size_t i = 3 * (size_t(y - crop.y0) * crop.width() + size_t(x - crop.x0));
            if (inTile) {
                EXPECT_EQ(a[i], b[i]);
                EXPECT_EQ(a[i + 2], b[i + 2]);
            } else {
                EXPECT_EQ(b[i], 0.0f);
            }
        }
    for (AovKind kind : all) {
        const std::vector<float> sa = source.resolveAov(kind), ta = target.resolveAov(kind);
        const int c = aovChannels(kind);
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x)
                for (int k = 0; k < c; ++k) {
                    const size_t i = size_t(c) * (size_t(y - crop.y0) * crop.width() +
                                                  size_t(x - crop.x0)) + size_t(k);
                    EXPECT_EQ(sa[i], ta[i]) << aovName(kind) << " " << x << "," << y;
                }
    }
    EXPECT_THAT(test::errorMessage([&] {
                    target.unpackPixels(tile, std::span(bytes).first(bytes.size() - 1), "tile 7");
                }),
                testing::HasSubstr("tile 7: "));
    EXPECT_THROW(source.packPixels(PixelRect{0, 0, 4, 4}), Error);
}

}  // namespace
}  // namespace strahl

// --- the sample halves (keepHalves, for the denoiser) ---------------------

namespace strahl {
namespace {

const std::vector<AovKind> kHalfAovs{AovKind::Normal, AovKind::Depth, AovKind::Albedo};

// Sample k of a pixel: radiance k + 1, depth k + 1, albedo (k + 1) / 10, a
// miss every third sample.
void addSamples(Film& film, int first, int count) {
    for (int k = first; k < first + count; ++k) {
        const AovSample aov = k % 3 == 2 ? AovSample{}
                                         : hitSample(Vec3(0, 0, 1), float(k + 1),
                                                     Color(float(k + 1) / 10.0f));
        film.addSample(0, 0, Color(float(k + 1)), aov);
    }
}

TEST(FilmHalves, EvenAndOddSamplesGoToTheirHalves) {
    Film film(1, 1, PixelRect{0, 0, 1, 1}, kHalfAovs);
    film.keepHalves(0);
    addSamples(film, 0, 6);  // even 0, 2, 4 (2 misses); odd 1, 3, 5 (5 misses)
    // Even samples 0, 2, 4: radiance 1, 3, 5; sample 2 misses.
    EXPECT_FLOAT_EQ(film.resolveHalfBeauty(0)[0], 3.0f);
    EXPECT_FLOAT_EQ(film.resolveHalfBeauty(1)[0], 4.0f);  // 2, 4, 6
    EXPECT_FLOAT_EQ(film.resolveHalfAov(0, AovKind::Depth)[0], 3.0f);   // hits 0, 4: depths 1, 5
    EXPECT_FLOAT_EQ(film.resolveHalfAov(1, AovKind::Depth)[0], 3.0f);   // hits 1, 3: depths 2, 4
    EXPECT_FLOAT_EQ(film.resolveHalfAov(0, AovKind::Albedo)[0], 0.2f);  // (0.1 + 0 + 0.5) / 3
    EXPECT_FLOAT_EQ(film.resolveHalfAov(1, AovKind::Albedo)[0], 0.2f);  // (0.2 + 0.4 + 0) / 3
    // The halves' sums add up to the whole.
    EXPECT_FLOAT_EQ(film.resolveBeauty()[0], 3.5f);
}

TEST(FilmHalves, APartStartingAtAnOddIndexStartsInTheOddHalf) {
    Film film(1, 1, PixelRect{0, 0, 1, 1}, kHalfAovs);
    film.keepHalves(3);
    film.addSample(0, 0, Color(1.0f), hitSample(Vec3(0, 0, 1), 1.0f, Color(0.5f)));
    EXPECT_FLOAT_EQ(film.resolveHalfBeauty(1)[0], 1.0f);
    EXPECT_FLOAT_EQ(film.resolveHalfBeauty(0)[0], 0.0f);  // no sample: black
    EXPECT_EQ(film.resolveHalfAov(0, AovKind::Depth)[0], kInfinity);
}

TEST(FilmHalves, MergedPartsAndCheckpointsKeepTheHalvesExactly) {
    Film whole(1, 1, PixelRect{0, 0, 1, 1}, kHalfAovs);
    whole.keepHalves(0);
    addSamples(whole, 0, 7);
    Film first(1, 1, PixelRect{0, 0, 1, 1}, kHalfAovs), second = first;
    first.keepHalves(0);
    second.keepHalves(3);
    addSamples(first, 0, 3);
    addSamples(second, 3, 4);
    first.merge(second, "part");
    const FilmPixel a = whole.pixel(0, 0), b = first.pixel(0, 0);
    EXPECT_EQ(a.evenSamples, b.evenSamples);
    EXPECT_EQ(a.evenHits, b.evenHits);
    EXPECT_EQ(a.evenRadiance, b.evenRadiance);
    EXPECT_EQ(a.evenDepth, b.evenDepth);
    EXPECT_EQ(a.evenAlbedo, b.evenAlbedo);
    EXPECT_EQ(a.evenNormal, b.evenNormal);

    std::stringstream state;
    whole.writeState(state);
    Film resumed(1, 1, PixelRect{0, 0, 1, 1}, kHalfAovs);
    resumed.keepHalves(0);
    resumed.readState(state, "checkpoint");
    EXPECT_EQ(resumed.pixel(0, 0).evenRadiance, a.evenRadiance);
    EXPECT_EQ(resumed.resolveHalfBeauty(1), whole.resolveHalfBeauty(1));

    Film without(1, 1, PixelRect{0, 0, 1, 1}, kHalfAovs);
    EXPECT_THROW(without.merge(whole, "part"), Error);
}

TEST(FilmHalves, NeedTheFeatureAovsAndComeBeforeSamples) {
    Film noAlbedo(1, 1, PixelRect{0, 0, 1, 1}, {AovKind::Normal, AovKind::Depth});
    EXPECT_THROW(noAlbedo.keepHalves(0), Error);
    Film late(1, 1, PixelRect{0, 0, 1, 1}, kHalfAovs);
    late.addSample(0, 0, Color(1.0f), AovSample{});
    EXPECT_THROW(late.keepHalves(0), Error);
    Film plain(1, 1, PixelRect{0, 0, 1, 1}, kHalfAovs);
    EXPECT_THROW(plain.resolveHalfBeauty(0), Error);
}

}  // namespace
}  // namespace strahl
