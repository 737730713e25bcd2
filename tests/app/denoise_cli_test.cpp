// The denoiser from the command line (docs/denoising.md): render --denoise
// and render.denoise, the layers it writes, strahl denoise on its EXR (the
// same image bit for bit), denoising after strahl merge of --denoise parts
// (the same as one render), thread-count independence, and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "app/app_test_helpers.h"
#include "app/cli_runner.h"
#include "app/exr_file.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::runStrahl;

using test::kDefaultScene;
const std::string kDenoiseFlags = " --width 24 --height 20 -q --exr-float";
const std::string kSpp = " --spp 6";

// The values of the named channels, in pixel order.
std::vector<float> channel(const test::ExrFile& e, const std::string& name) {
    const auto it = std::find(e.channels.begin(), e.channels.end(), name);
    if (it == e.channels.end()) {
        ADD_FAILURE() << "no channel " << name;
        return {};
    }
    const size_t c = size_t(it - e.channels.begin()), n = e.channels.size();
    std::vector<float> values;
    for (size_t i = c; i < e.pixels.size(); i += n) values.push_back(e.pixels[i]);
    return values;
}

// Bit for bit, or within `tolerance` relative to the largest value.
void expectSameChannels(const test::ExrFile& a, const test::ExrFile& b,
                        const std::vector<std::string>& names, const std::string& what,
                        float tolerance = 0.0f) {
    for (const std::string& name : names) {
        const std::vector<float> x = channel(a, name), y = channel(b, name);
        ASSERT_EQ(x.size(), y.size()) << what << ": channel " << name;
        float largest = 0.0f;
        for (float v : x) largest = std::max(largest, std::abs(v));
        size_t differing = 0;
        for (size_t i = 0; i < x.size(); ++i)
            differing +=
                tolerance == 0.0f ? x[i] != y[i] : std::abs(x[i] - y[i]) > tolerance * largest;
        EXPECT_EQ(differing, 0u) << what << ": channel " << name;
    }
}

const std::vector<std::string> kBeauty{"R", "G", "B"};

class DenoiseCli : public testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = test::scratchDir("denoise-cli");
        const test::RunResult r =
            runStrahl("render " + kDefaultScene + kDenoiseFlags + kSpp + " --denoise -o " +
                      path("denoised.exr") + " -o " + path("denoised.png"));
        ASSERT_EQ(r.status, 0) << r.err;
    }
    static std::string path(const std::string& name) { return (dir_ / name).string(); }
    static inline fs::path dir_;
};

TEST_F(DenoiseCli, WritesTheDenoisedBeautyWithNoisyFeatureAndHalfLayers) {
    const test::ExrFile e = test::readExr(path("denoised.exr"));
    for (const char* name :
         {"R", "noisy.R", "albedo.R", "normal.X", "depth.Z", "variance.R", "half0.R",
          "half0.albedo.G", "half0.normal.Z", "half0.depth.Z", "half1.B", "half1.depth.Z"})
        EXPECT_NE(std::find(e.channels.begin(), e.channels.end(), name), e.channels.end()) << name;
    // The denoised image differs from the noisy one, and the noisy one is the
    // mean of the halves (3 samples each).
    EXPECT_NE(channel(e, "R"), channel(e, "noisy.R"));
    const std::vector<float> noisy = channel(e, "noisy.G"), a = channel(e, "half0.G"),
                             b = channel(e, "half1.G");
    for (size_t i = 0; i < noisy.size(); ++i) EXPECT_NEAR(noisy[i], 0.5f * (a[i] + b[i]), 1e-5f);
    EXPECT_TRUE(fs::exists(path("denoised.png")));
}

TEST_F(DenoiseCli, TheSceneKeyIsTheFlag) {
    const test::RunResult r = runStrahl("render " + kDefaultScene + kDenoiseFlags + kSpp +
                                        " --set /render/denoise=true -o " + path("key.exr"));
    ASSERT_EQ(r.status, 0) << r.err;
    test::expectIdentical(test::readExr(path("denoised.exr")), test::readExr(path("key.exr")),
                          "render.denoise vs --denoise");
}

TEST_F(DenoiseCli, TheDenoiseCommandGivesTheRendersImage) {
    const test::RunResult r = runStrahl("denoise " + path("denoised.exr") + " -o " +
                                        path("again.exr") + " -o " + path("again.png") + " -q");
    ASSERT_EQ(r.status, 0) << r.err;
    const test::ExrFile rendered = test::readExr(path("denoised.exr"));
    const test::ExrFile again = test::readExr(path("again.exr"));
    expectSameChannels(rendered, again, {"R", "G", "B", "noisy.R", "half1.depth.Z"}, "denoise");
    EXPECT_TRUE(fs::exists(path("again.png")));
}

TEST_F(DenoiseCli, IsTheSameForAnyThreadCount) {
    const test::RunResult r = runStrahl("render " + kDefaultScene + kDenoiseFlags + kSpp +
                                        " --denoise --threads 1 -o " + path("one-thread.exr"));
    ASSERT_EQ(r.status, 0) << r.err;
    test::expectIdentical(test::readExr(path("denoised.exr")),
                          test::readExr(path("one-thread.exr")), "1 thread vs all");
}

TEST_F(DenoiseCli, MergedPartsDenoiseToTheSingleRender) {
    for (const auto& [name, flags] : {std::pair<std::string, std::string>{"p0", " --spp 3"},
                                      {"p1", " --spp 3 --sample-offset 3"}}) {
        const test::RunResult r = runStrahl("render " + kDefaultScene + kDenoiseFlags + flags +
                                            (name == "p0" ? " --sample-offset 0" : "") +
                                            " --denoise -o " + path(name + ".exr"));
        ASSERT_EQ(r.status, 0) << name << ": " << r.err;
    }
    ASSERT_EQ(
        runStrahl("merge " + path("p0.exr") + " " + path("p1.exr") + " -q -o " + path("merged.exr"))
            .status,
        0);
    const test::RunResult r =
        runStrahl("denoise " + path("merged.exr") + " -q -o " + path("merged-denoised.exr"));
    ASSERT_EQ(r.status, 0) << r.err;
    const test::ExrFile single = test::readExr(path("denoised.exr"));
    const test::ExrFile merged = test::readExr(path("merged-denoised.exr"));
    // The halves are exact sums: bit for bit those of one render.
    expectSameChannels(single, merged, {"noisy.R", "half0.R", "half1.albedo.R", "half0.depth.Z"},
                       "merged parts vs one render");
    // The variance AOV the denoiser reads is merged by Chan's formula (rounded
    // differently, docs/farm.md), so the denoised image agrees to rounding.
    expectSameChannels(single, merged, kBeauty, "merged parts vs one render", 1e-4f);
}

TEST_F(DenoiseCli, ACropIsDenoisedInItsDataWindow) {
    const test::RunResult r = runStrahl("render " + kDefaultScene + kDenoiseFlags + kSpp +
                                        " --denoise --crop 4,2,20,16 -o " + path("crop.exr"));
    ASSERT_EQ(r.status, 0) << r.err;
    const test::ExrFile crop = test::readExr(path("crop.exr"));
    EXPECT_EQ(crop.x, 4);
    EXPECT_EQ(crop.width, 16);
    EXPECT_EQ(crop.fullWidth, 24);
    ASSERT_EQ(runStrahl("denoise " + path("crop.exr") + " -q -o " + path("crop2.exr")).status, 0);
    const test::ExrFile again = test::readExr(path("crop2.exr"));
    EXPECT_EQ(again.x, 4);
    EXPECT_EQ(again.fullHeight, 20);
    expectSameChannels(crop, again, kBeauty, "cropped render vs strahl denoise");
}

TEST_F(DenoiseCli, ACheckpointedRenderResumesAndDenoisesAtTheEnd) {
    // Stopped after the first pass (one sample: not denoised, a note says
    // so), then resumed: the image of the uninterrupted render.
    const std::string checkpoint = path("d.ckpt");
    test::RunResult r = runStrahl("render " + kDefaultScene + kDenoiseFlags + kSpp +
                                  " --denoise --time-limit 0 --checkpoint " + checkpoint + " -o " +
                                  path("cut.exr"));
    ASSERT_EQ(r.status, 0) << r.err;
    r = runStrahl("render " + kDefaultScene + kDenoiseFlags + kSpp + " --denoise --resume " +
                  checkpoint + " -o " + path("resumed.exr"));
    ASSERT_EQ(r.status, 0) << r.err;
    test::expectIdentical(test::readExr(path("denoised.exr")), test::readExr(path("resumed.exr")),
                          "resumed vs uninterrupted");
}

// One line on stderr, exit status 1, and no output file.
void expectRefused(const test::RunResult& r, const std::string& needle, const fs::path& output) {
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(output)) << output;
}

TEST_F(DenoiseCli, BadInputIsOneClearError) {
    // An EXR without the layers: rendered without --denoise.
    ASSERT_EQ(runStrahl("render " + kDefaultScene + kDenoiseFlags + kSpp + " --aov variance -o " +
                        path("plain.exr"))
                  .status,
              0);
    expectRefused(runStrahl("denoise " + path("plain.exr") + " -o " + path("out.exr")),
                  "lacks the denoiser's layers half0, half1", path("out.exr"));
    expectRefused(runStrahl("denoise " + path("missing.exr") + " -o " + path("out.exr")),
                  "missing.exr: no such file", path("out.exr"));
    expectRefused(runStrahl("denoise " + path("denoised.png") + " -o " + path("out.exr")),
                  "not an OpenEXR image", path("out.exr"));
    expectRefused(runStrahl("render " + kDefaultScene + kDenoiseFlags + " --spp 1 --denoise -o " +
                            path("one.exr")),
                  "at least 2 samples per pixel", path("one.exr"));
    expectRefused(runStrahl("render " + kDefaultScene + kDenoiseFlags +
                            " --denoise --algorithm raster --integrator eyelight --spp 1 -o " +
                            path("raster.exr")),
                  "needs the ray tracer", path("raster.exr"));
    expectRefused(runStrahl("render " + kDefaultScene + kDenoiseFlags + kSpp +
                            " --set /render/denoise=3 -o " + path("bad-key.exr")),
                  "denoise", path("bad-key.exr"));
}

}  // namespace
}  // namespace strahl
