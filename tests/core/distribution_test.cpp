#include "strahl/core/distribution.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core_test_helpers.h"
#include "strahl/core/error.h"
#include "strahl/core/rng.h"

namespace strahl {
namespace {

using test::chiSquareCritical;

// Pearson's statistic over the bins with non-zero expectation.
double chiSquare(const std::vector<int>& counts, const std::vector<double>& expected, int& dof) {
    double chi2 = 0.0;
    dof = -1;
    for (size_t i = 0; i < counts.size(); ++i) {
        if (expected[i] == 0.0) continue;
        chi2 += (counts[i] - expected[i]) * (counts[i] - expected[i]) / expected[i];
        ++dof;
    }
    return chi2;
}

const std::vector<float> kWeights = {1.0f, 0.0f, 3.0f, 2.0f, 0.0f, 4.0f, 0.5f, 0.0f};

TEST(Distribution1D, PdfIntegratesToOneAndPmfSumsToOne) {
    const Distribution1D d(kWeights);
    EXPECT_FLOAT_EQ(d.integral(), 10.5f / 8.0f);
    double integral = 0.0, pmfSum = 0.0;
    const int steps = 8000;  // midpoint rule, 1000 points per bin
    for (int i = 0; i < steps; ++i) integral += d.pdf((static_cast<float>(i) + 0.5f) / steps);
    for (size_t i = 0; i < d.size(); ++i) pmfSum += d.pmf(i);
    EXPECT_NEAR(integral / steps, 1.0, 1e-6);
    EXPECT_NEAR(pmfSum, 1.0, 1e-6);
    EXPECT_FLOAT_EQ(d.pmf(2), 3.0f / 10.5f);
    EXPECT_EQ(d.pmf(1), 0.0f);
    EXPECT_EQ(d.pmf(8), 0.0f);  // out of range
}

TEST(Distribution1D, SamplePdfEqualsPdfAndStaysInItsBin) {
    const Distribution1D d(kWeights);
    Pcg32 rng(1, 2);
    std::vector<float> us = {0.0f, 1.0f / 10.5f, 0x1.fffffep-1f, 0.5f};
    for (int i = 0; i < 20000; ++i) us.push_back(rng.nextFloat());
    for (float u : us) {
        float pdf;
        size_t offset;
        const float x = d.sampleContinuous(u, pdf, offset);
        ASSERT_GE(x, 0.0f);
        ASSERT_LT(x, 1.0f);
        ASSERT_EQ(static_cast<size_t>(x * 8.0f), offset) << "u = " << u;
        ASSERT_EQ(pdf, d.pdf(x)) << "u = " << u;  // exactly: same bin, same formula
        ASSERT_GT(pdf, 0.0f) << "a bin of weight 0 was sampled, u = " << u;
    }
}

TEST(Distribution1D, ContinuousSampleInvertsTheCdf) {
    // Weights 1, 3: cdf 0, 1/4, 1. u = 1/8 is half-way through bin 0, u = 5/8
    // half-way through bin 1.
    const Distribution1D d({1.0f, 3.0f});
    float pdf;
    size_t offset;
    EXPECT_FLOAT_EQ(d.sampleContinuous(0.125f, pdf, offset), 0.25f);
    EXPECT_EQ(offset, 0u);
    EXPECT_FLOAT_EQ(pdf, 0.5f);
    EXPECT_FLOAT_EQ(d.sampleContinuous(0.625f, pdf, offset), 0.75f);
    EXPECT_EQ(offset, 1u);
    EXPECT_FLOAT_EQ(pdf, 1.5f);
}

TEST(Distribution1D, HistogramMatchesWeights) {
    const Distribution1D d(kWeights);
    Pcg32 rng(7, 3);
    const int n = 100000;
    std::vector<int> continuous(kWeights.size(), 0), discrete(kWeights.size(), 0);
    for (int i = 0; i < n; ++i) {
        float pdf, pmf;
        size_t offset;
        d.sampleContinuous(rng.nextFloat(), pdf, offset);
        ++continuous[offset];
        ++discrete[d.sampleDiscrete(rng.nextFloat(), pmf)];
    }
    std::vector<double> expected;
    for (float w : kWeights) expected.push_back(n * w / 10.5);
    for (const auto* counts : {&continuous, &discrete}) {
        int dof;
        const double chi2 = chiSquare(*counts, expected, dof);
        EXPECT_EQ(dof, 4);
        EXPECT_LT(chi2, chiSquareCritical(dof));
        for (size_t i = 0; i < kWeights.size(); ++i) {
            if (kWeights[i] == 0.0f) {
                EXPECT_EQ((*counts)[i], 0) << "bin " << i;
            }
        }
    }
}

TEST(Distribution1D, DiscretePmfMatchesPmf) {
    const Distribution1D d(kWeights);
    for (float u : {0.0f, 0.3f, 0.7f, 0x1.fffffep-1f}) {
        float pmf;
        const size_t i = d.sampleDiscrete(u, pmf);
        EXPECT_EQ(pmf, d.pmf(i));
        EXPECT_GT(pmf, 0.0f);
    }
}

// sampleDiscrete finds its bin without sampleContinuous's point in it: the
// same bin for every u, empty bins, NaN and the ends included.
TEST(Distribution1D, DiscreteBinIsTheContinuousSamplesBin) {
    for (const std::vector<float>& weights :
         {kWeights, std::vector<float>{0.0f, 0.0f, 1.0f, 2.0f, 0.0f, 0.0f},
          std::vector<float>{5.0f}, std::vector<float>{0.0f, 0.0f, 0.0f}}) {
        const Distribution1D d(weights);
        Pcg32 rng(3, 8);
        std::vector<float> us = {0.0f, 0x1.fffffep-1f, 1.0f, -0.5f, std::nanf("")};
        for (int k = 0; k < 20000; ++k) us.push_back(rng.nextFloat());
        for (float u : us) {
            float pdf, pmf;
            size_t offset;
            d.sampleContinuous(u, pdf, offset);
            EXPECT_EQ(d.sampleDiscrete(u, pmf), offset) << "u " << u;
            EXPECT_EQ(pmf, d.pmf(offset));
        }
    }
}

TEST(Distribution1D, UNearOneAndZeroSkipEmptyEndBins) {
    const Distribution1D d({0.0f, 0.0f, 1.0f, 2.0f, 0.0f, 0.0f});
    float pdf;
    size_t offset;
    const float xLow = d.sampleContinuous(0.0f, pdf, offset);
    EXPECT_EQ(offset, 2u);
    EXPECT_FLOAT_EQ(xLow, 2.0f / 6.0f);
    const float xHigh = d.sampleContinuous(0x1.fffffep-1f, pdf, offset);
    EXPECT_EQ(offset, 3u);
    EXPECT_LT(xHigh, 4.0f / 6.0f);
    EXPECT_EQ(pdf, d.pdf(xHigh));
}

TEST(Distribution1D, AllZeroWeightsAreUniform) {
    const Distribution1D d(std::vector<float>(4, 0.0f));
    EXPECT_EQ(d.integral(), 0.0f);
    EXPECT_EQ(d.pdf(0.3f), 1.0f);
    EXPECT_EQ(d.pmf(3), 0.25f);
    float pdf;
    size_t offset;
    EXPECT_FLOAT_EQ(d.sampleContinuous(0.6f, pdf, offset), 0.6f);
    EXPECT_EQ(offset, 2u);
    EXPECT_EQ(pdf, 1.0f);
}

TEST(Distribution1D, TinyWeightsStayFinite) {
    const Distribution1D d({1e-44f, 0.0f, 1e-45f});
    float pdf;
    size_t offset;
    const float x = d.sampleContinuous(0.5f, pdf, offset);
    EXPECT_TRUE(std::isfinite(x));
    EXPECT_TRUE(std::isfinite(pdf));
    EXPECT_GT(pdf, 0.0f);
}

TEST(Distribution1D, RejectsInvalidWeights) {
    EXPECT_THROW(Distribution1D(std::vector<float>{}), Error);
    EXPECT_THROW(Distribution1D({1.0f, -1.0f}), Error);
    EXPECT_THROW(Distribution1D({1.0f, NAN}), Error);
    EXPECT_THROW(Distribution1D({INFINITY}), Error);
}

// 4 columns x 3 rows; row 1 is all zero.
const std::vector<float> kGrid = {1, 2, 0, 1,  //
                                  0, 0, 0, 0,  //
                                  4, 1, 3, 0};
constexpr float kGridSum = 12.0f;

TEST(Distribution2D, PdfIntegratesToOne) {
    const Distribution2D d(kGrid, 4, 3);
    double integral = 0.0;
    const float nu = 40.0f, nv = 30.0f;  // 10 x 10 midpoints per cell
    for (float v = 0.5f; v < nv; v += 1.0f)
        for (float u = 0.5f; u < nu; u += 1.0f) integral += d.pdf(Vec2(u / nu, v / nv));
    EXPECT_NEAR(integral / (nu * nv), 1.0, 1e-6);
    // Density of a cell = weight / mean weight.
    EXPECT_FLOAT_EQ(d.pdf(Vec2(0.1f, 0.9f)), 4.0f / (kGridSum / 12.0f));
    EXPECT_EQ(d.pdf(Vec2(0.6f, 0.5f)), 0.0f);
}

TEST(Distribution2D, SamplePdfEqualsPdfAndHistogramMatches) {
    const Distribution2D d(kGrid, 4, 3);
    Pcg32 rng(11, 5);
    const int n = 60000;
    std::vector<int> counts(12, 0);
    for (int i = 0; i < n; ++i) {
        float pdf;
        const Vec2 uv = d.sample(Vec2(rng.nextFloat(), rng.nextFloat()), pdf);
        ASSERT_GE(uv.x, 0.0f);
        ASSERT_LT(uv.x, 1.0f);
        ASSERT_GE(uv.y, 0.0f);
        ASSERT_LT(uv.y, 1.0f);
        ASSERT_EQ(pdf, d.pdf(uv));
        ++counts[static_cast<size_t>(uv.y * 3.0f) * 4 + static_cast<size_t>(uv.x * 4.0f)];
    }
    std::vector<double> expected;
    for (float w : kGrid) expected.push_back(n * w / kGridSum);
    int dof;
    const double chi2 = chiSquare(counts, expected, dof);
    EXPECT_EQ(dof, 5);
    EXPECT_LT(chi2, chiSquareCritical(dof));
    for (size_t i = 0; i < kGrid.size(); ++i) {
        if (kGrid[i] == 0.0f) {
            EXPECT_EQ(counts[i], 0) << "cell " << i;
        }
    }
}

TEST(Distribution2D, AllZeroIsUniformAndUNearOneStaysInside) {
    const Distribution2D d(std::vector<float>(6, 0.0f), 3, 2);
    float pdf;
    const Vec2 uv = d.sample(Vec2(0x1.fffffep-1f), pdf);
    EXPECT_LT(uv.x, 1.0f);
    EXPECT_LT(uv.y, 1.0f);
    EXPECT_EQ(pdf, 1.0f);
    EXPECT_EQ(d.pdf(Vec2(0.2f, 0.7f)), 1.0f);
}

TEST(Distribution2D, RejectsBadSizes) {
    EXPECT_THROW(Distribution2D(std::vector<float>(5, 1.0f), 3, 2), Error);
    EXPECT_THROW(Distribution2D({}, 0, 0), Error);
}

}  // namespace
}  // namespace strahl
