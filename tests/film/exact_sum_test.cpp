// ExactSum and Film::merge: sums over split sample ranges add up to the
// sequential sum bit for bit (which float sums do not), in any order.

#include "strahl/film/exact_sum.h"

#include <gtest/gtest.h>

#include <bit>

#include <cmath>
#include <limits>
#include <vector>

#include "film_test_helpers.h"
#include "strahl/core/error.h"
#include "strahl/core/rng.h"
#include "strahl/film/film.h"

namespace strahl {
namespace {

// Values of very different magnitudes: float sums of them depend on the order.
std::vector<float> awkwardValues(size_t n) {
    std::vector<float> v;
    uint64_t state = 12345;
    for (size_t i = 0; i < n; ++i) {
        state = mixBits(state + i);
        const float unit = static_cast<float>(state >> 40) * 0x1p-24f;
        v.push_back((i % 3 == 0 ? 1e4f : i % 3 == 1 ? 1e-3f : 1.0f) * unit);
    }
    return v;
}

TEST(ExactSum, SplitSumsAddUpToTheSequentialSumBitForBit) {
    const std::vector<float> v = awkwardValues(1000);
    ExactSum all;
    for (float x : v) all.add(x);
    for (size_t split : {1u, 7u, 333u, 999u}) {
        ExactSum a, b;
        for (size_t i = 0; i < split; ++i) a.add(v[i]);
        for (size_t i = split; i < v.size(); ++i) b.add(v[i]);
        ExactSum ab = a, ba = b;
        ab += b;
        ba += a;
        EXPECT_EQ(ab.raw(), all.raw()) << split;
        EXPECT_EQ(ba.raw(), all.raw()) << split;
    }
    // Floats do not: the reason for ExactSum (a sanity check of the test data).
    float sequential = 0.0f, head = 0.0f, tail = 0.0f;
    for (size_t i = 0; i < v.size(); ++i) (i < 333 ? head : tail) += v[i], sequential += v[i];
    EXPECT_NE(head + tail, sequential);
}

TEST(ExactSum, HoldsFloatsExactlyAndResolvesTheMean) {
    ExactSum s;
    s.add(1.5f);
    s.add(-0.25f);
    s.add(0x1p-40f);
    EXPECT_EQ(s.value(), 1.25 + 0x1p-40);
    EXPECT_EQ(s.mean(0), 0.0f);
    EXPECT_EQ(s.mean(5), static_cast<float>((1.25 + 0x1p-40) / 5.0));
    // A float that is an exact multiple of 2^-64 survives; below that it is truncated toward 0.
    ExactSum tiny;
    tiny.add(0x1p-64f);
    EXPECT_EQ(tiny.raw(), Int128(1));
    tiny.add(-0x1p-66f);
    EXPECT_EQ(tiny.raw(), Int128(1));
}

TEST(ExactSum, ConversionFromTheFloatBitsEqualsTheDefinition) {
    const auto same = [](float x) {
        ASSERT_TRUE(ExactSum::toFixed(x) == ExactSum::toFixedByDouble(x)) << x;
    };
    // Every exponent (subnormals, the values that shift out, the bound and
    // beyond it, infinities, NaN) with the smallest, largest and a middle
    // fraction, both signs.
    for (uint32_t biased = 0; biased < 256; ++biased)
        for (uint32_t fraction : {0u, 1u, 0x400001u, 0x7FFFFFu})
            for (uint32_t sign : {0u, 1u})
                same(std::bit_cast<float>((sign << 31) | (biased << 23) | fraction));
    // Random bit patterns.
    uint64_t state = 3;
    for (int i = 0; i < 200000; ++i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        same(std::bit_cast<float>(static_cast<uint32_t>(state >> 32)));
    }
}

TEST(ExactSum, ClampsHugeAndDropsNanSamples) {
    ExactSum s;
    s.add(std::numeric_limits<float>::quiet_NaN());
    EXPECT_EQ(s.raw(), Int128(0));
    s.add(std::numeric_limits<float>::infinity());
    EXPECT_EQ(s.value(), ExactSum::kBound);
    s.add(-1e30f);
    EXPECT_EQ(s.value(), 0.0);
    // The most samples a pixel may have, all at the bound, do not overflow.
    ExactSum big = ExactSum::fromValue(ExactSum::kBound * double(ExactSum::kMaxSamples));
    EXPECT_GT(big.raw(), Int128(0));
    EXPECT_EQ(big.value(), ExactSum::kBound * double(ExactSum::kMaxSamples));
}

// Every first-hit value of sample s of pixel (x, y), deterministic.
AovSample sampleAov(int x, int y, int s) {
    AovSample aov;
    aov.hit = (x + y + s) % 3 != 0;
    const float fx = float(x), fy = float(y), fs = float(s);
    aov.normal = Vec3(std::sin(fx + fs), std::cos(fy * fs), -0.3f);
    aov.depth = 1.0f + 1e3f * fx + 0.01f * fs;
    aov.albedo = Color(0.1f * fs, 0.7f, 1.0f / (1.0f + fx));
    aov.position = Vec3(-fx * 100.0f, fy * 0.001f, fs);
    aov.objectId = uint32_t(10 * s + x);
    return aov;
}

Color sampleRadiance(int x, int y, int s) {
    return Color(std::exp(float(s % 5) * 3.0f) * 0.01f, float(x) / (1.0f + float(s)),
                 s % 4 == 0 ? 1e-5f : 100.0f + float(y));
}

Film renderSamples(const PixelRect& crop, const std::vector<AovKind>& aovs, int s0, int s1) {
    Film film(8, 6, crop, aovs);
    for (int s = s0; s < s1; ++s)
        for (int y = crop.y0; y < crop.y1; ++y)
            for (int x = crop.x0; x < crop.x1; ++x)
                film.addSample(x, y, sampleRadiance(x, y, s), sampleAov(x, y, s));
    return film;
}

using test::kAllAovs;

TEST(FilmMerge, PartsMergeIntoTheSingleFilmBitForBitExceptTheVariance) {
    const PixelRect crop{1, 1, 7, 5};
    const Film whole = renderSamples(crop, kAllAovs, 0, 11);
    Film merged = renderSamples(crop, kAllAovs, 0, 4);
    merged.merge(renderSamples(crop, kAllAovs, 4, 5), "part 2");
    merged.merge(renderSamples(crop, kAllAovs, 5, 11), "part 3");

    EXPECT_EQ(merged.resolveBeauty(), whole.resolveBeauty());
    for (AovKind kind : kAllAovs) {
        const std::vector<float> a = merged.resolveAov(kind), b = whole.resolveAov(kind);
        ASSERT_EQ(a.size(), b.size());
        for (size_t i = 0; i < a.size(); ++i) {
            if (kind == AovKind::Variance)  // Chan's formula: the same statistic, other rounding
                EXPECT_NEAR(a[i], b[i], 1e-4f * std::abs(b[i]) + 1e-12f) << aovName(kind) << i;
            else
                EXPECT_EQ(a[i], b[i]) << aovName(kind) << " value " << i;
        }
    }
    for (int y = crop.y0; y < crop.y1; ++y)
        for (int x = crop.x0; x < crop.x1; ++x) {
            EXPECT_EQ(merged.sampleCount(x, y), 11u);
            const FilmPixel p = merged.pixel(x, y), q = whole.pixel(x, y);
            EXPECT_EQ(p.hits, q.hits);
            EXPECT_EQ(p.radiance, q.radiance);
            EXPECT_EQ(p.position, q.position);
        }
}

TEST(FilmMerge, ObjectIdComesFromTheEarlierFilmAndEmptyFilmsAreNeutral) {
    const PixelRect crop{0, 0, 8, 6};
    Film empty(8, 6, crop, kAllAovs);
    empty.merge(renderSamples(crop, kAllAovs, 2, 5), "part");
    const Film direct = renderSamples(crop, kAllAovs, 2, 5);
    EXPECT_EQ(empty.resolveBeauty(), direct.resolveBeauty());
    EXPECT_EQ(empty.resolveAov(AovKind::Variance), direct.resolveAov(AovKind::Variance));
    EXPECT_EQ(empty.resolveAov(AovKind::ObjectId), direct.resolveAov(AovKind::ObjectId));
    Film earlier = renderSamples(crop, kAllAovs, 0, 2);
    earlier.merge(direct, "part");
    EXPECT_EQ(earlier.resolveAov(AovKind::ObjectId),
              renderSamples(crop, kAllAovs, 0, 5).resolveAov(AovKind::ObjectId));
}

TEST(FilmMerge, RejectsFilmsOfAnotherShape) {
    Film a(8, 6, PixelRect{0, 0, 8, 6}, {});
    EXPECT_THROW(a.merge(Film(8, 6, PixelRect{0, 0, 4, 6}, {}), "b"), Error);
    EXPECT_THROW(a.merge(Film(8, 6, PixelRect{0, 0, 8, 6}, {AovKind::Depth}), "b"), Error);
    EXPECT_THROW(a.merge(Film(8, 7, PixelRect{0, 0, 8, 6}, {}), "b"), Error);
}

TEST(FilmMerge, RefusesMoreSamplesThanTheSumsCanHold) {
    Film a(1, 1, PixelRect{0, 0, 1, 1}, {});
    FilmPixel p;
    p.samples = ExactSum::kMaxSamples;
    a.setPixel(0, 0, p);
    Film b(1, 1, PixelRect{0, 0, 1, 1}, {});
    b.addSample(0, 0, Color(1.0f), AovSample{});
    EXPECT_THROW(a.merge(b, "b"), Error);
}

}  // namespace
}  // namespace strahl
