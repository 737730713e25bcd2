// Pixel filters: their shapes and the importance sampling of filter.h
// (docs/camera.md, "Pixel filters").

#include "strahl/core/filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core_test_helpers.h"
#include "strahl/core/error.h"
#include "strahl/core/rng.h"

namespace strahl {
namespace {

using test::chiSquareCritical;

std::vector<PixelFilter> defaultFilters() {
    return {PixelFilter::box(), PixelFilter::gaussian(), PixelFilter::blackmanHarris(),
            PixelFilter::tent()};
}

// Simpson's rule for the integral of evaluate over [x0, x1] x [y0, y1]; the
// filters are smooth inside their support, so 16 panels per axis is plenty.
double cellIntegral(const PixelFilter& filter, double x0, double x1, double y0, double y1) {
    constexpr int kPanels = 16;  // even
    const auto weight = [](int i) { return i == 0 || i == kPanels ? 1.0 : (i % 2 ? 4.0 : 2.0); };
    const double hx = (x1 - x0) / kPanels, hy = (y1 - y0) / kPanels;
    double sum = 0.0;
    for (int j = 0; j <= kPanels; ++j)
        for (int i = 0; i <= kPanels; ++i)
            sum += weight(i) * weight(j) *
                   filter.evaluate(Vec2(static_cast<float>(x0 + i * hx),
                                        static_cast<float>(y0 + j * hy)));
    return sum * hx * hy / 9.0;
}

// The normal quantile of 1 - 1e-3 for chiSquareCritical, rounded as these tests
// have always used it. The approximation is accurate to a few percent for k >= 10.
constexpr double kFilterQuantile = 3.09;

struct ChiSquare {
    double statistic = 0.0;
    int dof = 0;
};

// Pearson's chi-square of `samples` offsets drawn by `sampler` against the
// expected cell probabilities of `expected` on a kCells x kCells grid over the
// support of `expected`. Cells expecting fewer than 5 samples are pooled (the
// usual validity rule), and the pooled cell counts as one more.
template <typename Sampler>
ChiSquare chiSquare(const PixelFilter& expected, Sampler sampler, int samples) {
    constexpr int kCells = 32;
    const float r = expected.radius();
    const double cell = 2.0 * r / kCells;
    std::vector<double> observed(kCells * kCells, 0.0);
    Pcg32 rng(20240607, 1);  // fixed seed: the test is deterministic
    for (int s = 0; s < samples; ++s) {
        const Vec2 u(rng.nextFloat(), rng.nextFloat());
        const Vec2 p = sampler(u);
        const int i = std::min(kCells - 1, static_cast<int>((p.x + r) / cell));
        const int j = std::min(kCells - 1, static_cast<int>((p.y + r) / cell));
        observed[static_cast<size_t>(j * kCells + i)] += 1.0;
    }
    const double total = expected.integral();
    ChiSquare result;
    double pooledObserved = 0.0, pooledExpected = 0.0;
    for (int j = 0; j < kCells; ++j) {
        for (int i = 0; i < kCells; ++i) {
            const double e = samples *
                             cellIntegral(expected, -r + i * cell, -r + (i + 1) * cell,
                                          -r + j * cell, -r + (j + 1) * cell) /
                             total;
            const double o = observed[static_cast<size_t>(j * kCells + i)];
            if (e < 5.0) {
                pooledObserved += o;
                pooledExpected += e;
                continue;
            }
            result.statistic += (o - e) * (o - e) / e;
            ++result.dof;
        }
    }
    if (pooledExpected > 0.0) {
        result.statistic += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) /
                            pooledExpected;
        ++result.dof;
    }
    result.dof -= 1;  // the counts sum to the sample count
    return result;
}

TEST(PixelFilter, DefaultsAndNames) {
    const PixelFilter box = PixelFilter::box();
    EXPECT_EQ(box.type(), FilterType::Box);
    EXPECT_EQ(box.radius(), 0.5f);
    EXPECT_STREQ(box.name(), "box");
    const PixelFilter gaussian = PixelFilter::gaussian();
    EXPECT_EQ(gaussian.type(), FilterType::Gaussian);
    EXPECT_EQ(gaussian.radius(), 1.5f);
    EXPECT_EQ(gaussian.sigma(), 0.5f);
    EXPECT_STREQ(gaussian.name(), "gaussian");
    const PixelFilter bh = PixelFilter::blackmanHarris();
    EXPECT_EQ(bh.type(), FilterType::BlackmanHarris);
    EXPECT_EQ(bh.radius(), 2.0f);
    EXPECT_STREQ(bh.name(), "blackman-harris");

    for (const PixelFilter& f : defaultFilters()) {
        const PixelFilter byName = PixelFilter::fromName(f.name());
        EXPECT_EQ(byName.type(), f.type());
        EXPECT_EQ(byName.radius(), f.radius());
        EXPECT_EQ(byName.sigma(), f.sigma());
    }
    const PixelFilter wide = PixelFilter::fromName("gaussian", 2.5f);
    EXPECT_EQ(wide.radius(), 2.5f);
    EXPECT_EQ(wide.sigma(), 0.5f);
    EXPECT_EQ(PixelFilter::fromName("box", 1.0f).radius(), 1.0f);
    EXPECT_EQ(PixelFilter::fromName("blackman-harris", 1.5f).radius(), 1.5f);
    ASSERT_EQ(PixelFilter::names().size(), 4u);
    EXPECT_EQ(PixelFilter::names()[2], "blackman-harris");
    const PixelFilter tent = PixelFilter::fromName("tent", 2.0f);
    EXPECT_EQ(tent.type(), FilterType::Tent);
    EXPECT_EQ(tent.radius(), 2.0f);
    EXPECT_FLOAT_EQ(tent.evaluate(Vec2(0.5f, 0.0f)), 0.75f);  // 1 - |x| / r
    EXPECT_FLOAT_EQ(tent.integral(), 4.0f);                    // (r)^2
}

TEST(PixelFilter, UnknownNameListsTheValidOnes) {
    try {
        PixelFilter::fromName("mitchell");
        FAIL() << "expected strahl::Error";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("'mitchell'"), std::string::npos) << message;
        for (std::string_view name : PixelFilter::names())
            EXPECT_NE(message.find(name), std::string::npos) << message;
    }
}

TEST(PixelFilter, RejectsNonPositiveOrNonFiniteParameters) {
    EXPECT_THROW(PixelFilter::box(0.0f), Error);
    EXPECT_THROW(PixelFilter::gaussian(-1.0f), Error);
    EXPECT_THROW(PixelFilter::gaussian(1.5f, 0.0f), Error);
    EXPECT_THROW(PixelFilter::gaussian(1.5f, std::nanf("")), Error);
    EXPECT_THROW(PixelFilter::blackmanHarris(kInfinity), Error);
    EXPECT_THROW(PixelFilter::fromName("box", -0.5f), Error);
}

TEST(PixelFilter, ShapesAreSeparableNonNegativeWithUnitPeak) {
    for (const PixelFilter& f : defaultFilters()) {
        const float r = f.radius();
        EXPECT_FLOAT_EQ(f.evaluate(Vec2(0.0f)), 1.0f) << f.name();
        EXPECT_EQ(f.evaluate(Vec2(r * 1.01f, 0.0f)), 0.0f) << f.name();
        EXPECT_EQ(f.evaluate(Vec2(0.0f, -r * 1.01f)), 0.0f) << f.name();
        for (float x = -r; x <= r; x += r / 7.0f) {
            for (float y = -r; y <= r; y += r / 5.0f) {
                const float v = f.evaluate(Vec2(x, y));
                EXPECT_GE(v, 0.0f);
                EXPECT_NEAR(v, f.evaluate(Vec2(x, 0.0f)) * f.evaluate(Vec2(0.0f, y)), 1e-6f);
                EXPECT_EQ(v, f.evaluate(Vec2(-x, y)));  // symmetric
            }
        }
    }
    // The Gaussian is shifted to reach 0 at the radius; Blackman-Harris nearly does.
    EXPECT_NEAR(PixelFilter::gaussian().evaluate(Vec2(1.5f, 0.0f)), 0.0f, 1e-7f);
    EXPECT_NEAR(PixelFilter::blackmanHarris().evaluate(Vec2(2.0f, 0.0f)), 6e-5f, 1e-6f);
    // A Gaussian value: (exp(-2) - exp(-4.5)) / (1 - exp(-4.5)) at x = 1, sigma 0.5.
    const double g = (std::exp(-2.0) - std::exp(-4.5)) / (1.0 - std::exp(-4.5));
    EXPECT_NEAR(PixelFilter::gaussian().evaluate(Vec2(1.0f, 0.0f)), g, 1e-6);
}

TEST(PixelFilter, IntegralMatchesQuadrature) {
    for (const PixelFilter& f : defaultFilters()) {
        const double r = f.radius();
        EXPECT_NEAR(f.integral(), cellIntegral(f, -r, r, -r, r), 1e-4 * f.integral()) << f.name();
    }
    EXPECT_FLOAT_EQ(PixelFilter::box().integral(), 1.0f);
    // The cosines integrate to 0 over a period, leaving (2 r a0)^2.
    EXPECT_NEAR(PixelFilter::blackmanHarris().integral(), std::pow(4.0 * 0.35875, 2.0), 1e-5);
}

TEST(PixelFilter, BoxOfHalfAPixelSamplesUniformlyOverThePixel) {
    const PixelFilter box = PixelFilter::box();
    Pcg32 rng(7, 3);
    for (int i = 0; i < 10000; ++i) {
        const Vec2 u(rng.nextFloat(), rng.nextFloat());
        const Vec2 p = box.sample(u);
        // Exactly the uniform jitter u - 1/2, bit for bit.
        EXPECT_EQ(p.x, u.x - 0.5f);
        EXPECT_EQ(p.y, u.y - 0.5f);
    }
    EXPECT_EQ(box.sample(Vec2(0.0f)), Vec2(-0.5f));
    EXPECT_EQ(box.sample(Vec2(0.5f)), Vec2(0.0f));
}

TEST(PixelFilter, SampleHistogramsMatchTheFilters) {
    constexpr int kSamples = 400000;
    const std::vector<PixelFilter> filters = {PixelFilter::box(),
                                              PixelFilter::gaussian(),
                                              PixelFilter::blackmanHarris(),
                                              PixelFilter::box(1.5f),
                                              PixelFilter::gaussian(1.0f, 0.7f),
                                              PixelFilter::blackmanHarris(1.0f)};
    for (const PixelFilter& f : filters) {
        const ChiSquare c = chiSquare(f, [&](Vec2 u) { return f.sample(u); }, kSamples);
        EXPECT_GT(c.dof, 100) << f.name();
        EXPECT_LT(c.statistic, chiSquareCritical(c.dof, kFilterQuantile))
            << f.name() << " radius " << f.radius() << ", dof " << c.dof;
    }
}

TEST(PixelFilter, ChiSquareTestDetectsAWrongDistribution) {
    // The same machinery rejects uniform samples judged against a Gaussian and
    // Gaussian ones judged against Blackman-Harris of the same width, so the
    // passing test above has teeth.
    constexpr int kSamples = 400000;
    const PixelFilter gaussian = PixelFilter::gaussian();
    const PixelFilter uniform = PixelFilter::box(gaussian.radius());
    const ChiSquare a = chiSquare(gaussian, [&](Vec2 u) { return uniform.sample(u); }, kSamples);
    EXPECT_GT(a.statistic, 10.0 * chiSquareCritical(a.dof, kFilterQuantile));
    const PixelFilter bh = PixelFilter::blackmanHarris(1.5f);
    const ChiSquare b = chiSquare(bh, [&](Vec2 u) { return gaussian.sample(u); }, kSamples);
    EXPECT_GT(b.statistic, chiSquareCritical(b.dof, kFilterQuantile));
}

TEST(PixelFilter, SamplesStayWithinTheRadiusAndCoverIt) {
    for (const PixelFilter& f : defaultFilters()) {
        const float r = f.radius();
        Vec2 lo(kInfinity), hi(-kInfinity);
        // A fine grid, plus the extremes of [0, 1).
        std::vector<float> us = {0.0f, 1.0f - 0x1p-24f, 0x1p-24f, 0.5f};
        for (int i = 0; i < 4096; ++i) us.push_back((static_cast<float>(i) + 0.5f) / 4096.0f);
        for (float ux : us) {
            for (float uy : {0.0f, 0.3f, 1.0f - 0x1p-24f, ux}) {
                const Vec2 p = f.sample(Vec2(ux, uy));
                EXPECT_LE(std::abs(p.x), r) << f.name();
                EXPECT_LE(std::abs(p.y), r) << f.name();
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
        }
        EXPECT_NEAR(lo.x, -r, 1e-3f * r) << f.name();
        EXPECT_NEAR(hi.x, r, 1e-3f * r) << f.name();
        EXPECT_NEAR(lo.y, -r, 1e-3f * r) << f.name();
    }
}

TEST(PixelFilter, SamplingIsMonotoneAndCentred) {
    for (const PixelFilter& f : defaultFilters()) {
        float previous = -kInfinity;
        for (int i = 0; i < 4096; ++i) {
            const float u = (static_cast<float>(i) + 0.5f) / 4096.0f;
            const float x = f.sample(Vec2(u, 0.5f)).x;
            EXPECT_GE(x, previous) << f.name() << " u " << u;
            previous = x;
        }
        const Vec2 centre = f.sample(Vec2(0.5f));
        EXPECT_NEAR(centre.x, 0.0f, 1e-5f) << f.name();
        EXPECT_NEAR(centre.y, 0.0f, 1e-5f) << f.name();
    }
}

TEST(PixelFilter, MeanOffsetIsZero) {
    constexpr int kSamples = 200000;
    for (const PixelFilter& f : defaultFilters()) {
        Pcg32 rng(99, 5);
        double sumX = 0.0, sumY = 0.0, sumSq = 0.0;
        for (int s = 0; s < kSamples; ++s) {
            const Vec2 p = f.sample(Vec2(rng.nextFloat(), rng.nextFloat()));
            sumX += p.x;
            sumY += p.y;
            sumSq += static_cast<double>(p.x) * p.x;
        }
        // Five standard errors of the mean.
        const double tol = 5.0 * std::sqrt(sumSq / kSamples / kSamples);
        EXPECT_NEAR(sumX / kSamples, 0.0, tol) << f.name();
        EXPECT_NEAR(sumY / kSamples, 0.0, tol) << f.name();
    }
}

TEST(PixelFilter, SamplingIsAPureFunction) {
    const PixelFilter f = PixelFilter::blackmanHarris();
    const PixelFilter copy = f;
    for (float u : {0.0f, 0.123f, 0.5f, 0.876f}) {
        EXPECT_EQ(f.sample(Vec2(u, 1.0f - u)), f.sample(Vec2(u, 1.0f - u)));
        EXPECT_EQ(f.sample(Vec2(u, 0.25f)), copy.sample(Vec2(u, 0.25f)));
    }
}

}  // namespace
}  // namespace strahl
