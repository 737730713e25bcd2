// Sample splitting through the CLI: `strahl render --spp N --sample-offset K`
// parts merged by `strahl merge` are bit for bit the single render of all
// their samples, in any order, also merged in stages; overlapping, mismatched,
// missing, partial and non-EXR parts are one clear error and leave no output.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "app/app_test_helpers.h"
#include "app/cli_runner.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::runStrahl;

// Path tracing with glass and every geometry kind (long, varied paths); every
// AOV, float channels, small.
using test::kGlossyRoom;
const std::string kAovs =
    " --aov normal --aov depth --aov albedo --aov position --aov objectid --aov variance";
const std::string kMergeFlags = " --width 24 --height 18 -q --exr-float" + kAovs;

struct Exr {
    std::map<std::string, std::vector<float>> channels;  // by name, row-major
    std::map<std::string, std::string> attributes;       // strahl:* and a few more, as text
};

Exr readChannels(const fs::path& file) {
    Exr e;
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) {
        ADD_FAILURE() << "cannot read " << file << ": " << OIIO::geterror();
        return e;
    }
    const OIIO::ImageSpec& spec = in->spec();
    const size_t count = size_t(spec.width) * size_t(spec.height);
    const size_t n = size_t(spec.nchannels);
    std::vector<float> pixels(count * n);
    EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    for (size_t c = 0; c < n; ++c) {
        std::vector<float>& plane = e.channels[spec.channel_name(int(c))];
        for (size_t i = 0; i < count; ++i) plane.push_back(pixels[i * n + c]);
    }
    for (const OIIO::ParamValue& p : spec.extra_attribs)
        e.attributes[p.name().string()] = spec.metadata_val(p);
    return e;
}

// Welford's state and the variance are combined by Chan's formula in a merge:
// the same statistics, rounded differently.
bool roundedDifferently(const std::string& channel) {
    return channel.rfind("variance.", 0) == 0 || channel.rfind("strahl.welford.", 0) == 0;
}

// Every channel of `expected` is in `actual` with bit-identical values (a
// NaN-free comparison), but for the variance, which agrees to rounding.
void expectSameImage(const Exr& expected, const Exr& actual, const std::string& what) {
    size_t compared = 0;
    for (const auto& [name, values] : expected.channels) {
        const auto it = actual.channels.find(name);
        ASSERT_NE(it, actual.channels.end()) << what << ": no channel " << name;
        ASSERT_EQ(values.size(), it->second.size()) << what << " " << name;
        size_t differing = 0;
        for (size_t i = 0; i < values.size(); ++i) {
            const float a = values[i], b = it->second[i];
            if (roundedDifferently(name))
                differing += std::abs(a - b) > 1e-5f * std::abs(a) + 1e-30f;
            else
                differing += a != b;
        }
        EXPECT_EQ(differing, 0u) << what << ": channel " << name << ", " << differing << " of "
                                 << values.size() << " values differ";
        ++compared;
    }
    EXPECT_GE(compared, 17u) << what;  // RGB and every AOV at least
}

class FarmMerge : public testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = test::scratchDir("farm-merge");
        render("single", " --spp 6");
        render("single0", " --spp 6 --sample-offset 0");
        render("p0", " --spp 2 --sample-offset 0");
        render("p1", " --spp 3 --sample-offset 2");
        render("p2", " --spp 1 --sample-offset 5");
    }
    // `flags` after kFlags, or instead of them if `replace`.
    static void render(const std::string& name, const std::string& flags, bool replace = false) {
        const test::RunResult r = runStrahl("render " + kGlossyRoom + (replace ? "" : kMergeFlags) +
                                            flags + " -o " + path(name).string());
        ASSERT_EQ(r.status, 0) << name << ": " << r.err;
    }
    static fs::path path(const std::string& name) { return dir_ / (name + ".exr"); }
    static std::string paths(const std::vector<std::string>& names) {
        std::string text;
        for (const std::string& n : names) text.append(" ").append(path(n).string());
        return text;
    }
    static test::RunResult merge(const std::vector<std::string>& parts, const std::string& out) {
        return runStrahl("merge" + paths(parts) + " -o " + path(out).string());
    }
    // One line on stderr, exit status 1, no output and no temporary file.
    static void expectRefused(const std::vector<std::string>& parts, const std::string& needle) {
        const test::RunResult r = merge(parts, "refused");
        EXPECT_EQ(r.status, 1) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_EQ(r.err.rfind("strahl: error: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
        for (const auto& entry : fs::directory_iterator(dir_))
            EXPECT_EQ(entry.path().filename().string().find("refused"), std::string::npos)
                << entry.path();
    }
    static fs::path dir_;
};

fs::path FarmMerge::dir_;

TEST_F(FarmMerge, PartsMergeIntoExactlyTheSingleRenderInAnyOrder) {
    const test::RunResult r = merge({"p2", "p0", "p1"}, "merged");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("merged 3 parts: 6 samples per pixel, sample indices 0-6"),
              std::string::npos)
        << r.err;
    const Exr merged = readChannels(path("merged"));
    // Every channel of the ordinary single render, and of the single render
    // written as a part (its exact sums included).
    expectSameImage(readChannels(path("single")), merged, "merged vs single render");
    expectSameImage(readChannels(path("single0")), merged, "merged vs single render's exact data");
    EXPECT_EQ(merged.attributes.at("strahl:spp"), "6");
    EXPECT_EQ(merged.attributes.at("strahl:sample_ranges"), "\"0-6\"");
    EXPECT_EQ(merged.attributes.at("strahl:samples_begin"), "0");
    EXPECT_EQ(merged.attributes.at("strahl:samples_end"), "6");
    EXPECT_EQ(merged.attributes.at("strahl:partial"), "\"0\"");
    // An ordinary render carries no exact data.
    const Exr single = readChannels(path("single"));
    for (const auto& [name, values] : single.channels) EXPECT_NE(name.rfind("strahl.", 0), 0u);
    EXPECT_EQ(single.attributes.count("strahl:split_fingerprint"), 0u);

    ASSERT_EQ(merge({"p1", "p2", "p0"}, "reordered").status, 0);
    const Exr reordered = readChannels(path("reordered"));
    for (const auto& [name, values] : merged.channels)
        EXPECT_EQ(values, reordered.channels.at(name)) << name;  // variance included: sorted first
}

TEST_F(FarmMerge, MergesMergeAndRangesNeedNotBeContiguous) {
    const test::RunResult gap = merge({"p2", "p0"}, "p02");
    ASSERT_EQ(gap.status, 0) << gap.err;
    EXPECT_EQ(readChannels(path("p02")).attributes.at("strahl:sample_ranges"), "\"0-2,5-6\"");
    ASSERT_EQ(merge({"p1", "p02"}, "staged").status, 0);
    expectSameImage(readChannels(path("single0")), readChannels(path("staged")),
                    "merged in two stages");
    // The staged result holds 0-6: adding p1 again counts its samples twice.
    expectRefused({"staged", "p1"}, "twice");
}

TEST_F(FarmMerge, WritesDisplayOutputsThroughTheDisplayTransform) {
    const test::RunResult r = runStrahl("merge" + paths({"p0", "p1", "p2"}) + " -o " +
                                        (dir_ / "merged.png").string() + " -o " +
                                        path("also").string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "merged.png"));
    EXPECT_TRUE(fs::exists(path("also")));
}

TEST_F(FarmMerge, OverlappingRangesAreRefusedNamingBothFiles) {
    render("overlap", " --spp 2 --sample-offset 1");
    expectRefused({"p0", "overlap"}, path("overlap").string() + ": its samples 1-3 overlap the "
                                     "samples 0-2 of " + path("p0").string());
    expectRefused({"p0", "p0"}, "twice");
}

TEST_F(FarmMerge, PartsOfOtherRendersAreRefused) {
    render("seed", " --spp 1 --sample-offset 7 --seed 99");
    expectRefused({"p0", "seed"}, "rendered with other settings than");
    render("narrow", " --spp 1 --sample-offset 7 --width 20 --height 18 -q --exr-float" + kAovs,
           true);
    expectRefused({"p0", "narrow"}, "image size 20x18 differs");
    render("crop", " --spp 1 --sample-offset 7 --crop 0,0,12,18");
    expectRefused({"p0", "crop"}, "data window 0,0,12,18 differs");
    const test::RunResult other =
        runStrahl("render " + (test::sourceDir() / "scenes/default.json").string() + kMergeFlags +
                  " --spp 1 --sample-offset 7 -o " + path("other").string());
    ASSERT_EQ(other.status, 0) << other.err;
    expectRefused({"p0", "other"}, "rendered with other settings than");
    render("fewer", " --spp 1 --sample-offset 7 --width 24 --height 18 -q --exr-float --aov depth",
           true);
    expectRefused({"p0", "fewer"}, "its channels differ");
    render("half", " --spp 1 --sample-offset 7 --width 24 --height 18 -q" + kAovs, true);
    expectRefused({"p0", "half"}, "its channels differ");
}

TEST_F(FarmMerge, MissingAndNonExrInputsAreRefused) {
    expectRefused({"p0", "absent"}, path("absent").string() + ": cannot read: no such file");
    const fs::path png = dir_ / "picture.png";
    ASSERT_EQ(
        runStrahl("render " + kGlossyRoom + kMergeFlags + " --spp 1 -o " + png.string()).status, 0);
    const test::RunResult r =
        runStrahl("merge" + paths({"p0"}) + " " + png.string() + " -o " + path("refused").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(png.string() + ": not an OpenEXR image"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("refused")));
}

TEST_F(FarmMerge, APartialPartIsRefused) {
    // --time-limit 0 stops after the first of three passes.
    render("partial", " --spp 3 --sample-offset 6 --time-limit 0");
    expectRefused({"p0", "partial"}, "a partial render cannot be merged");
}

TEST_F(FarmMerge, APartResumesFromItsCheckpointAndOnlyAsThatPart) {
    const std::string checkpoint = (dir_ / "part.ckpt").string();
    // Stopped after its first pass, then resumed: the part that was asked for.
    render("resumed", " --spp 3 --sample-offset 2 --time-limit 0 --checkpoint " + checkpoint);
    render("resumed", " --spp 3 --sample-offset 2 --resume " + checkpoint);
    const Exr resumed = readChannels(path("resumed")), p1 = readChannels(path("p1"));
    for (const auto& [name, values] : p1.channels)
        EXPECT_EQ(values, resumed.channels.at(name)) << name;
    // The offset is part of the checkpoint's fingerprint.
    const test::RunResult r = runStrahl("render " + kGlossyRoom + kMergeFlags +
                                        " --spp 3 --sample-offset 3 --resume " + checkpoint +
                                        " -o " + path("other").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("samples from 2"), std::string::npos) << r.err;
}

TEST_F(FarmMerge, PlainImagesAreAveragedBySampleCountWithAWarning) {
    render("plain2", " --spp 2");
    render("plain3", " --spp 3 --seed 5");
    const test::RunResult r = merge({"plain2", "plain3"}, "mean");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("strahl: warning: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("not bit-exact"), std::string::npos) << r.err;
    const Exr a = readChannels(path("plain2")), b = readChannels(path("plain3")),
              m = readChannels(path("mean"));
    EXPECT_EQ(m.attributes.at("strahl:spp"), "5");
    EXPECT_EQ(m.channels.count("strahl.sum.R.0"), 0u);  // no exact data to pass on
    for (const char* channel : {"R", "G", "B", "albedo.G", "normal.Z"}) {
        const std::vector<float>& x = a.channels.at(channel);
        const std::vector<float>& y = b.channels.at(channel);
        const std::vector<float>& z = m.channels.at(channel);
        for (size_t i = 0; i < z.size(); ++i)
            EXPECT_NEAR(z[i], (2.0f * x[i] + 3.0f * y[i]) / 5.0f, 1e-5f * (1.0f + std::abs(z[i])))
                << channel << " " << i;
    }
}

TEST_F(FarmMerge, BadCommandLinesExitWithStatus2) {
    EXPECT_EQ(runStrahl("merge -o " + path("x").string()).status, 2);
    EXPECT_EQ(runStrahl("merge" + paths({"p0"})).status, 2);
    EXPECT_EQ(runStrahl("render " + kGlossyRoom + kMergeFlags + " --sample-offset -1 -o " +
                        path("x").string()).status,
              2);
    EXPECT_FALSE(fs::exists(path("x")));
}

}  // namespace
}  // namespace strahl
