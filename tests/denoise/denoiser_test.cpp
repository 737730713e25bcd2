// The denoiser (denoise/denoiser.h) on synthetic images whose truth is known:
// constant and noise-free inputs come back unchanged, a sharp albedo edge is
// not blurred across, a flat region keeps its mean, noise goes down, the
// result does not depend on the thread count, and bad input is one clear error.

#include "strahl/denoise/denoiser.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>

#include "strahl/core/error.h"

namespace strahl {
namespace {

constexpr int kSize = 48;

// Per pixel: the true radiance and the albedo; the normal faces the camera
// and the depth is 1 everywhere, unless the test says otherwise.
struct Scene {
    std::function<float(int x, int y)> radiance;
    std::function<float(int x, int y)> albedo = [](int, int) { return 0.5f; };
};

// Two independent halves of a render of `scene` whose per-half noise has
// standard deviation sigma (Gaussian, seeded), and the variance of the full
// mean: sigma^2 / 2.
DenoiseInput makeInput(const Scene& scene, float sigma, uint32_t seed = 1) {
    DenoiseInput in;
    in.width = in.height = kSize;
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    for (DenoiseHalf& half : in.halves) {
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const float l = scene.radiance(x, y), a = scene.albedo(x, y);
                for (int c = 0; c < 3; ++c) {
                    half.color.push_back(l + sigma * noise(rng));
                    half.albedo.push_back(a);
                }
                half.normal.insert(half.normal.end(), {0.0f, 0.0f, 1.0f});
                half.depth.push_back(1.0f);
            }
    }
    in.variance.assign(size_t(kSize) * kSize * 3, 0.5f * sigma * sigma);
    return in;
}

float truth(const Scene& scene, int x, int y) {
    return scene.radiance(x, y);
}

double meanSquaredError(const std::vector<float>& image, const Scene& scene) {
    double sum = 0.0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int c = 0; c < 3; ++c) {
                const double d = image[3 * size_t(y * kSize + x) + size_t(c)] - truth(scene, x, y);
                sum += d * d;
            }
    return sum / (3.0 * kSize * kSize);
}

std::vector<float> noisyMean(const DenoiseInput& in) {
    std::vector<float> mean(in.halves[0].color.size());
    for (size_t i = 0; i < mean.size(); ++i)
        mean[i] = 0.5f * (in.halves[0].color[i] + in.halves[1].color[i]);
    return mean;
}

TEST(Denoiser, ConstantInputComesBackUnchanged) {
    const Scene scene{[](int, int) { return 0.37f; }};
    const std::vector<float> out = denoise(makeInput(scene, 0.0f));
    ASSERT_EQ(out.size(), size_t(kSize) * kSize * 3);
    for (float v : out) EXPECT_NEAR(v, 0.37f, 1e-6f);
}

TEST(Denoiser, NoiseFreeImageComesBackUnchanged) {
    // A gradient with a step in radiance and albedo: with no noise (variance
    // 0) every pixel that differs from another gets no weight from it.
    const Scene scene{[](int x, int y) { return 0.1f + 0.01f * float(x) + (y > 20 ? 0.5f : 0.0f); },
                      [](int, int y) { return y > 20 ? 0.8f : 0.2f; }};
    const std::vector<float> out = denoise(makeInput(scene, 0.0f));
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            EXPECT_NEAR(out[3 * size_t(y * kSize + x)], truth(scene, x, y), 1e-5f)
                << "pixel " << x << ", " << y;
}

TEST(Denoiser, RemovesMostOfTheNoiseOfASmoothImage) {
    const Scene scene{[](int x, int y) { return 0.5f + 0.004f * float(x + y); }};
    const DenoiseInput in = makeInput(scene, 0.1f);
    const double before = meanSquaredError(noisyMean(in), scene);
    const double after = meanSquaredError(denoise(in), scene);
    EXPECT_LT(after, before / 10.0) << "noisy MSE " << before << ", denoised " << after;
}

TEST(Denoiser, KeepsASharpAlbedoEdge) {
    // A checkerboard texture of 8-pixel squares, albedo 0.2 and 0.8 under
    // uniform light: the radiance follows the albedo. The regression on the
    // albedo feature must keep the steps: across every edge, the denoised
    // contrast is measured against the true one (0.6).
    const auto albedo = [](int x, int y) { return ((x / 8 + y / 8) % 2) ? 0.8f : 0.2f; };
    const Scene scene{[&](int x, int y) { return albedo(x, y); }, albedo};
    const DenoiseInput in = makeInput(scene, 0.1f);
    const std::vector<float> out = denoise(in);
    double contrast = 0.0;
    int edges = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 7; x + 1 < kSize; x += 8) {
            const float a = out[3 * size_t(y * kSize + x)], b = out[3 * size_t(y * kSize + x + 1)];
            contrast += std::abs(b - a);
            ++edges;
        }
    contrast /= edges;
    EXPECT_NEAR(contrast, 0.6, 0.03) << "mean contrast across the checker edges";
    // The noise still goes down several times (8 x 8 squares hold fewer
    // pixels than the 11 x 11 window: less to average than on a smooth image).
    EXPECT_LT(meanSquaredError(out, scene), meanSquaredError(noisyMean(in), scene) / 5.0);
}

TEST(Denoiser, KeepsTheMeanOfAFlatRegion) {
    // No energy lost or gained: over a flat lit region the denoised mean is
    // the true value within the statistical error of the noisy mean itself.
    const Scene scene{[](int, int) { return 2.0f; }};
    const DenoiseInput in = makeInput(scene, 0.5f, 7);
    const std::vector<float> out = denoise(in);
    double sum = 0.0;
    for (float v : out) sum += v;
    const double mean = sum / double(out.size());
    // The noisy mean over 48 x 48 x 3 values has standard error 0.5 / sqrt(2 * 6912) = 0.004.
    EXPECT_NEAR(mean, 2.0, 0.015);
}

// The largest |out - truth| over the image, over all channels.
float largestError(const std::vector<float>& image, const Scene& scene) {
    float worst = 0.0f;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(image[3 * size_t(y * kSize + x) + size_t(c)] -
                                                 truth(scene, x, y)));
    return worst;
}

TEST(Denoiser, ALoneFireflyIsNotSpreadIntoABlob) {
    // One of 16 samples carried 4000 (a path that found a caustic): the mean
    // of its half (8 samples) is 500 over a flat 0.5, and the variance of the
    // pixel's mean is about 4000^2 / 16 / 16 = 62500, as the film measures it.
    const Scene scene{[](int, int) { return 0.5f; }};
    DenoiseInput in = makeInput(scene, 0.02f, 3);
    const size_t firefly = 3 * size_t(24 * kSize + 24);
    for (int c = 0; c < 3; ++c) {
        in.halves[0].color[firefly + size_t(c)] = 500.0f;
        in.variance[firefly + size_t(c)] = 62500.0f;
    }
    // Unlimited, the regression spreads it over its window (the weights come
    // from the other half, which does not have it): what the limit is for.
    DenoiseSettings unlimited;
    unlimited.outlierFactor = 0.0f;
    unlimited.maxStandardErrors = 0.0f;
    EXPECT_GT(largestError(denoise(in, unlimited), scene), 1.0f);
    // Limited to 4 x the other half's neighbourhood (about 2.1 here): the
    // image stays within a few noise deviations of the truth everywhere.
    EXPECT_LT(largestError(denoise(in), scene), 0.1f);
}

TEST(Denoiser, KeepsAHighlightBothHalvesSee) {
    // A one-pixel highlight of 20 in both halves is image, not noise: the
    // limit does not touch it and the filter keeps it.
    const Scene scene{[](int x, int y) { return x == 24 && y == 24 ? 20.0f : 0.5f; }};
    const std::vector<float> out = denoise(makeInput(scene, 0.02f, 4));
    EXPECT_GT(out[3 * size_t(24 * kSize + 24)], 19.5f);
    EXPECT_LT(largestError(out, scene), 0.1f);
}

TEST(Denoiser, KeepsEveryPixelWithinThreeStandardErrorsOfItsMean) {
    // Small noisy lamps (50, variance 25, as a light seen through glass is)
    // on a dim, nearly noise-free background: NL-means weights count a
    // high-variance pixel as similar to anything, so unlimited, the lamps
    // bleed into their neighbours (by over 4 standard errors here; by 100
    // times the true value next to the DamagedHelmet's lamps).
    const auto lamp = [](int x, int y) { return x % 12 == 6 && y % 12 == 6; };
    const Scene scene{[&](int x, int y) { return lamp(x, y) ? 50.0f : 0.1f; }};
    DenoiseInput in = makeInput(scene, 0.01f, 5);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            if (lamp(x, y))
                for (int c = 0; c < 3; ++c)
                    in.variance[3 * size_t(y * kSize + x) + size_t(c)] = 25.0f;
    const std::vector<float> mean = noisyMean(in);
    // How far each pixel moved, in its standard errors (sqrt of the larger
    // of its variance and its neighbourhood's without the lamps, here the
    // background's).
    const auto worstMove = [&](const std::vector<float>& out) {
        float worst = 0.0f;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                for (int c = 0; c < 3; ++c) {
                    const size_t i = 3 * size_t(y * kSize + x) + size_t(c);
                    worst = std::max(worst, std::abs(out[i] - mean[i]) / std::sqrt(in.variance[i]));
                }
        return worst;
    };
    DenoiseSettings unlimited;
    unlimited.maxStandardErrors = 0.0f;
    EXPECT_GT(worstMove(denoise(in, unlimited)), 3.5f);
    EXPECT_LE(worstMove(denoise(in)), 3.0f + 1e-3f);
    EXPECT_LT(largestError(denoise(in), scene), 0.1f);
}

TEST(Denoiser, IsIdenticalForAnyThreadCount) {
    const Scene scene{[](int x, int y) { return 0.3f + 0.5f * float((x * 7 + y * 3) % 11 > 5); },
                      [](int x, int y) { return (x * 7 + y * 3) % 11 > 5 ? 0.9f : 0.3f; }};
    const DenoiseInput in = makeInput(scene, 0.2f);
    DenoiseSettings one, two;
    one.threads = 1;
    two.threads = 2;
    const std::vector<float> a = denoise(in, one), b = denoise(in, two), c = denoise(in);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(std::bit_cast<uint32_t>(a[i]), std::bit_cast<uint32_t>(b[i])) << "value " << i;
        ASSERT_EQ(std::bit_cast<uint32_t>(a[i]), std::bit_cast<uint32_t>(c[i])) << "value " << i;
    }
}

TEST(Denoiser, MissesWithInfiniteDepthAreFine) {
    Scene scene{[](int x, int) { return x < 24 ? 0.0f : 1.0f; }};
    DenoiseInput in = makeInput(scene, 0.05f);
    for (DenoiseHalf& half : in.halves)
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < 24; ++x)
                half.depth[size_t(y * kSize + x)] = std::numeric_limits<float>::infinity();
    const std::vector<float> out = denoise(in);
    for (float v : out) ASSERT_TRUE(std::isfinite(v));
}

void expectError(const DenoiseInput& in, const std::string& what) {
    try {
        denoise(in, {}, "in.exr");
        ADD_FAILURE() << "no error for " << what;
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("in.exr"), std::string::npos) << message;
        EXPECT_NE(message.find(what), std::string::npos) << message;
    }
}

TEST(Denoiser, BadInputIsOneClearError) {
    const Scene scene{[](int, int) { return 1.0f; }};
    DenoiseInput in = makeInput(scene, 0.1f);
    in.halves[1].albedo.pop_back();
    expectError(in, "half 1 albedo");
    in = makeInput(scene, 0.1f);
    in.halves[0].color[40] = std::numeric_limits<float>::quiet_NaN();
    expectError(in, "half 0 beauty");
    in = makeInput(scene, 0.1f);
    in.halves[0].color[40] = std::numeric_limits<float>::infinity();
    expectError(in, "half 0 beauty");
    in = makeInput(scene, 0.1f);
    in.variance[5] = -1.0f;
    expectError(in, "variance");
    in = makeInput(scene, 0.1f);
    in.halves[1].depth[3] = -std::numeric_limits<float>::infinity();
    expectError(in, "half 1 depth");
    in = DenoiseInput{};
    expectError(in, "image size 0x0");
}

}  // namespace
}  // namespace strahl
