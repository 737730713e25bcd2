// Statistical image regression for path-traced scenes (scenes/statistical/):
// a render at the scene's spp is compared with a reference at 16x the spp and
// another seed, stored with its per-pixel variance, by per-pixel z-scores
//     z = (a - r) / sqrt(var_a + var_r),
// where var is the variance of each pixel's mean (the variance AOV). For an
// unbiased change z is roughly standard normal; path-tracing noise has heavy
// tails, so the test bounds the fraction of large |z| and the drift of the
// mean rather than assuming Gaussian statistics (Mitsuba's test_renders.py).
// STRAHL_UPDATE_REFERENCES=1 rewrites the references.

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "strahl/film/image_output.h"
#include "render_helpers.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

// The reference: 16x the samples, so its own variance adds ~6% to the test's.
constexpr int kReferenceSppFactor = 16;
constexpr uint64_t kReferenceSeed = 1000003;
// |z| > 4 has probability 6e-5 for a normal variable; allowing 1% absorbs the
// heavy tails of caustic paths while a bias of a few percent in a region of
// the image fails it.
constexpr double kLargeZ = 4.0;
constexpr double kMaxLargeZFraction = 0.01;
// The image means must agree to 1%.
constexpr double kMaxMeanDrift = 0.01;

struct NoisyImage {
    std::vector<float> beauty, variance;
};

NoisyImage renderScene(const SceneDesc& desc, int spp, uint64_t seed, const fs::path& exr) {
    const Film film =
        test::renderFilm(desc, {.aovs = {AovKind::Variance}, .spp = spp, .seed = seed});
    if (!exr.empty()) {
        OutputSettings settings;
        settings.exrFloat = true;
        writeImage(film, exr, settings, ImageMetadata{});
    }
    return NoisyImage{film.resolveBeauty(), film.resolveAov(AovKind::Variance)};
}

// Beauty (R, G, B) and variance (variance.R/G/B) of a stored reference.
NoisyImage readReference(const fs::path& file, size_t pixels) {
    OIIO::ImageBuf image(file.string());
    EXPECT_TRUE(image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << image.geterror();
    const OIIO::ImageSpec& spec = image.spec();
    NoisyImage out;
    out.beauty.resize(3 * pixels);
    out.variance.resize(3 * pixels);
    const char* beauty[] = {"R", "G", "B"};
    const char* variance[] = {"variance.R", "variance.G", "variance.B"};
    for (int c = 0; c < 3; ++c) {
        const int b = spec.channelindex(beauty[c]), v = spec.channelindex(variance[c]);
        EXPECT_GE(b, 0) << file << " has no channel " << beauty[c];
        EXPECT_GE(v, 0) << file << " has no channel " << variance[c];
        if (b < 0 || v < 0) return out;
        for (size_t i = 0; i < pixels; ++i) {
            const int x = int(i % size_t(spec.width)), y = int(i / size_t(spec.width));
            out.beauty[3 * i + c] = image.getchannel(x, y, 0, b);
            out.variance[3 * i + c] = image.getchannel(x, y, 0, v);
        }
    }
    return out;
}

std::vector<std::string> statisticalScenes() {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(test::sourceDir() / "scenes/statistical"))
        if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

class StatisticalRegression : public ::testing::TestWithParam<std::string> {};

TEST_P(StatisticalRegression, AgreesWithTheReferenceWithinNoise) {
    const fs::path scene = test::sourceDir() / "scenes/statistical" / (GetParam() + ".json");
    const fs::path reference =
        test::sourceDir() / "tests/golden/statistical" / (GetParam() + ".exr");
    const SceneDesc desc = parseSceneFile(scene);
    const size_t pixels = size_t(desc.film.width) * size_t(desc.film.height);

    if (std::getenv("STRAHL_UPDATE_REFERENCES")) {
        fs::create_directories(reference.parent_path());
        renderScene(desc, desc.render.spp * kReferenceSppFactor, kReferenceSeed, reference);
        GTEST_SKIP() << "reference rewritten: " << reference;
    }
    ASSERT_TRUE(fs::exists(reference))
        << reference << " is missing; create it with STRAHL_UPDATE_REFERENCES=1 (see "
        << "scenes/statistical/README.md)";

    const NoisyImage test = renderScene(desc, desc.render.spp, desc.render.seed, {});
    const NoisyImage ref = readReference(reference, pixels);
    ASSERT_EQ(ref.beauty.size(), test.beauty.size());

    double sumTest = 0, sumRef = 0, largeZ = 0;
    for (size_t i = 0; i < test.beauty.size(); ++i) {
        sumTest += test.beauty[i];
        sumRef += ref.beauty[i];
        const double sigma = std::sqrt(double(test.variance[i]) + double(ref.variance[i]));
        const double diff = std::abs(double(test.beauty[i]) - double(ref.beauty[i]));
        // 1e-6: pixels that are black in both have zero variance.
        if (diff > kLargeZ * sigma + 1e-6) ++largeZ;
    }
    EXPECT_NEAR(sumTest / sumRef, 1.0, kMaxMeanDrift);
    EXPECT_LE(largeZ / double(test.beauty.size()), kMaxLargeZFraction)
        << largeZ << " of " << test.beauty.size() << " channels have |z| > " << kLargeZ;
}

INSTANTIATE_TEST_SUITE_P(Scenes, StatisticalRegression, ::testing::ValuesIn(statisticalScenes()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

// The test must be able to fail: a 5% brighter image is caught.
TEST(StatisticalRegressionPower, DetectsAFivePercentBias) {
    const SceneDesc desc =
        parseSceneFile(test::sourceDir() / "scenes/statistical/glossy_room.json");
    const NoisyImage a = renderScene(desc, desc.render.spp, 1, {});
    const NoisyImage b = renderScene(desc, desc.render.spp, 2, {});
    double largeZ = 0, sumA = 0, sumB = 0;
    for (size_t i = 0; i < a.beauty.size(); ++i) {
        const double biased = 1.05 * b.beauty[i];
        sumA += a.beauty[i];
        sumB += biased;
        const double sigma = std::sqrt(double(a.variance[i]) + 1.05 * 1.05 * b.variance[i]);
        if (std::abs(a.beauty[i] - biased) > kLargeZ * sigma + 1e-6) ++largeZ;
    }
    const bool meanCaught = std::abs(sumB / sumA - 1.0) > kMaxMeanDrift;
    EXPECT_TRUE(meanCaught || largeZ / double(a.beauty.size()) > kMaxLargeZFraction);
}

}  // namespace
}  // namespace strahl
