#include "strahl/core/sampler.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace strahl {
namespace {

// The points of one dimension pair over samples 0 .. n-1 of a pixel.
std::vector<Vec2> pairPoints(uint64_t seed, int px, int py, int pair, uint32_t n) {
    std::vector<Vec2> points;
    for (uint32_t i = 0; i < n; ++i) {
        Sampler sampler(seed, px, py, i);
        for (int k = 0; k < pair; ++k) sampler.get2D();
        points.push_back(sampler.get2D());
    }
    return points;
}

TEST(Sampler, SecondSobolDimensionMatchesTheKnownSequence) {
    // Joe & Kuo's dimension 2 in index order (not Gray-code order, which
    // would swap 4-5 with 6-7): 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
    const float expected[] = {0.0f, 0.5f, 0.75f, 0.25f, 0.625f, 0.125f, 0.375f, 0.875f};
    for (uint32_t i = 0; i < 8; ++i)
        EXPECT_EQ(sobol::toUnitFloat(sobol::dimension1(i)), expected[i]) << i;
}

TEST(Sampler, TableDrivenSecondDimensionEqualsTheDefinition) {
    // Every single bit (the matrix columns), then a spread of indices.
    for (uint32_t bit = 0; bit < 32; ++bit)
        EXPECT_EQ(sobol::dimension1(1u << bit), sobol::dimension1BitByBit(1u << bit)) << bit;
    uint64_t state = 1;
    for (int i = 0; i < 100000; ++i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        const auto index = static_cast<uint32_t>(state >> 32);
        ASSERT_EQ(sobol::dimension1(index), sobol::dimension1BitByBit(index)) << index;
    }
}

TEST(Sampler, ShortcutFirstDimensionScrambleEqualsTheDefinition) {
    uint64_t state = 5;
    for (int i = 0; i < 100000; ++i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        const auto index = static_cast<uint32_t>(state >> 32);
        const auto seed = static_cast<uint32_t>(state);
        ASSERT_EQ(sobol::scrambledDimension0(index, seed),
                  sobol::nestedUniformScramble(sobol::dimension0(index), seed))
            << index << " " << seed;
    }
}

TEST(Sampler, BitReversalAndTheReversedTableEqualTheDefinitions) {
    const auto reversedBitByBit = [](uint32_t x) {
        uint32_t r = 0;
        for (int b = 0; b < 32; ++b) r |= ((x >> b) & 1u) << (31 - b);
        return r;
    };
    uint64_t state = 9;
    for (int i = 0; i < 100000; ++i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        const auto index = static_cast<uint32_t>(state >> 32);
        const auto seed = static_cast<uint32_t>(state);
        ASSERT_EQ(sobol::reverseBits(index), reversedBitByBit(index)) << index;
        ASSERT_EQ(sobol::scrambledDimension1(index, seed),
                  sobol::nestedUniformScramble(sobol::dimension1(index), seed))
            << index << " " << seed;
    }
}

TEST(Sampler, EveryPairIsA02NetForPowersOfTwo) {
    // 2^m consecutive samples put exactly one point in every elementary
    // interval of area 2^-m, for every shape 2^a x 2^b with a + b = m.
    for (int pair = 0; pair < 4; ++pair) {
        for (int m : {4, 6, 8}) {
            const uint32_t n = 1u << m;
            const std::vector<Vec2> points = pairPoints(7, 13, 42, pair, n);
            for (int a = 0; a <= m; ++a) {
                const int b = m - a;
                std::set<uint32_t> cells;
                for (const Vec2& p : points) {
                    const auto cx = static_cast<uint32_t>(p.x * static_cast<float>(1u << a));
                    const auto cy = static_cast<uint32_t>(p.y * static_cast<float>(1u << b));
                    cells.insert((cy << a) | cx);
                }
                EXPECT_EQ(cells.size(), n) << "pair " << pair << " m " << m << " a " << a;
            }
        }
    }
}

TEST(Sampler, OneDimensionalValuesAreStratified) {
    const uint32_t n = 64;
    std::set<uint32_t> strata;
    for (uint32_t i = 0; i < n; ++i) {
        Sampler sampler(3, 5, 9, i);
        sampler.get2D();
        strata.insert(static_cast<uint32_t>(sampler.get1D() * static_cast<float>(n)));
    }
    EXPECT_EQ(strata.size(), n);
}

TEST(Sampler, ValuesDependOnlyOnSeedPixelIndexAndDimension) {
    Sampler a(11, 100, 200, 17), b(11, 100, 200, 17);
    for (int d = 0; d < 10; ++d) EXPECT_EQ(a.get2D(), b.get2D());
    // A different pixel, seed or sample index gives different values.
    EXPECT_NE(Sampler(11, 101, 200, 17).get2D(), Sampler(11, 100, 200, 17).get2D());
    EXPECT_NE(Sampler(12, 100, 200, 17).get2D(), Sampler(11, 100, 200, 17).get2D());
    EXPECT_NE(Sampler(11, 100, 200, 18).get2D(), Sampler(11, 100, 200, 17).get2D());
}

// A consumer that does not use a pair skips it (a pinhole's lens sample): the
// pairs after it are those that drawing it would have given.
TEST(Sampler, SkippingAPairGivesTheLaterPairsOfDrawingIt) {
    for (uint32_t index : {0u, 1u, 17u, 1000u}) {
        Sampler drawn(3, 5, 8, index), skipped(3, 5, 8, index);
        drawn.get2D();
        skipped.skip2D();
        EXPECT_EQ(skipped.dimension(), drawn.dimension());
        EXPECT_EQ(skipped.get2D(), drawn.get2D()) << index;
        drawn.get1D();
        skipped.skip2D();
        EXPECT_EQ(skipped.get1D(), drawn.get1D()) << index;
    }
}

TEST(Sampler, PairsAreDecorrelated) {
    // The correlation between the first coordinates of two pairs over many
    // samples is near zero (without the index shuffle every pair would be
    // identical: correlation 1).
    const uint32_t n = 4096;
    double sx = 0, sy = 0, sxy = 0, sxx = 0, syy = 0;
    for (uint32_t i = 0; i < n; ++i) {
        Sampler sampler(1, 2, 3, i);
        const float x = sampler.get2D().x;
        const float y = sampler.get2D().x;
        sx += x, sy += y, sxy += x * y, sxx += x * x, syy += y * y;
    }
    const double nd = n;
    const double cov = sxy / nd - (sx / nd) * (sy / nd);
    const double corr = cov / std::sqrt((sxx / nd - (sx / nd) * (sx / nd)) *
                                        (syy / nd - (sy / nd) * (sy / nd)));
    EXPECT_LT(std::abs(corr), 0.05);
}

TEST(Sampler, ValuesLieInTheUnitInterval) {
    for (uint32_t i = 0; i < 1000; ++i) {
        Sampler sampler(99, 1, 1, i);
        for (int d = 0; d < 5; ++d) {
            const Vec2 u = sampler.get2D();
            EXPECT_GE(u.x, 0.0f);
            EXPECT_LT(u.x, 1.0f);
            EXPECT_GE(u.y, 0.0f);
            EXPECT_LT(u.y, 1.0f);
        }
    }
}

}  // namespace
}  // namespace strahl
