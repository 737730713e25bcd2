// `strahl render --set POINTER=VALUE` and the flags that are scene patches
// (docs/cli.md#scene-patches): the same image as the flag or the edited file,
// clear errors, and a fingerprint that follows every patched setting.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "app/cli_runner.h"
#include "app/exr_file.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::contains;
using test::readExr;
using test::runStrahl;

const std::string kDirectQuad = R"({
  "camera": { "eye": [0, 0, 3] },
  "film": { "width": 16, "height": 12 },
  "render": { "integrator": "direct", "spp": 1 },
  "shapes": [ { "type": "mesh", "positions": [[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]],
                "indices": [0,1,2,0,2,3] } ],
  "lights": [ { "type": "point", "position": [0, 0, 2], "intensity": 3 } ]
})";

TEST(ScenePatchCli, SetGivesTheImageOfTheFlagAndOfTheEditedFile) {
    const fs::path dir = test::scratchDir("set-cli-same");
    test::writeFile(dir / "quad.json", kDirectQuad);
    std::string edited = kDirectQuad;
    edited.replace(edited.find("\"spp\": 1"), 8, "\"spp\": 3");
    test::writeFile(dir / "edited.json", edited);
    const std::string scene = (dir / "quad.json").string();
    ASSERT_EQ(runStrahl("render " + scene + " -q --spp 3 -o " + (dir / "flag.exr").string()).status, 0);
    const test::RunResult r =
        runStrahl("render " + scene + " -q --set /render/spp=3 -o " + (dir / "set.exr").string());
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_EQ(runStrahl("render " + (dir / "edited.json").string() + " -q -o " +
                        (dir / "edited.exr").string())
                  .status,
              0);
    const test::ExrFile flag = readExr(dir / "flag.exr"), set = readExr(dir / "set.exr");
    test::expectIdentical(flag, set, "--spp 3 vs --set /render/spp=3");
    test::expectIdentical(flag, readExr(dir / "edited.exr"), "--spp 3 vs the edited file");
    EXPECT_EQ(flag.fingerprint, set.fingerprint);  // the same patched document
}

TEST(ScenePatchCli, SetReachesEveryKeyAndALaterPatchWins) {
    const fs::path dir = test::scratchDir("set-cli-keys");
    test::writeFile(dir / "quad.json", kDirectQuad);
    const fs::path out = dir / "a.exr";
    const test::RunResult r = runStrahl(
        "render " + (dir / "quad.json").string() + " -q --width 40 --set /film/width=24 " +
        "--set /film/height=10 --set /camera/fov=20 --set '/film/aovs=[\"depth\"]' -o " +
        out.string());
    ASSERT_EQ(r.status, 0) << r.err;
    const test::ExrFile e = readExr(out);
    EXPECT_EQ(e.width, 24);  // --set comes after the flags
    EXPECT_EQ(e.height, 10);
    EXPECT_TRUE(std::any_of(e.channels.begin(), e.channels.end(),
                            [](const std::string& c) { return contains(c, "depth"); }));
}

TEST(ScenePatchCli, BadPatchesAreClearErrorsWithoutOutput) {
    const fs::path dir = test::scratchDir("set-cli-bad");
    test::writeFile(dir / "quad.json", kDirectQuad);
    const std::string render = "render " + (dir / "quad.json").string() + " -o " +
                               (dir / "a.exr").string() + " ";
    test::RunResult r = runStrahl(render + "--set /render/spp");
    EXPECT_EQ(r.status, 2);  // a usage error, like every malformed option
    EXPECT_TRUE(contains(r.err, "expected POINTER=VALUE")) << r.err;
    r = runStrahl(render + "--set /film/width/x=1");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "strahl: error: " + (dir / "quad.json").string() +
                         ": /film/width is a number, not an object (--set /film/width/x=1)\n");
    r = runStrahl(render + "--set /render/spp=0");
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.err, "/render/spp: must be between 1 and")) << r.err;
    EXPECT_TRUE(contains(r.err, "(set by --set /render/spp=0)")) << r.err;
    r = runStrahl(render + "--set /render/sample_count=4");
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.err, "unknown key 'sample_count'")) << r.err;
    EXPECT_FALSE(fs::exists(dir / "a.exr"));
}

TEST(ScenePatchCli, SkipExistingRendersAgainWhenAPatchChangesTheImage) {
    const fs::path dir = test::scratchDir("set-cli-skip");
    test::writeFile(dir / "quad.json", kDirectQuad);
    const std::string render = "render " + (dir / "quad.json").string() + " -o " +
                               (dir / "a.exr").string() + " --skip-existing ";
    ASSERT_EQ(runStrahl(render + "--set /lights/0/intensity=5").status, 0);
    test::RunResult r = runStrahl(render + "--set /lights/0/intensity=5");
    EXPECT_TRUE(contains(r.err, "skipped")) << r.err;
    // A setting no flag exists for still makes another image.
    r = runStrahl(render + "--set /lights/0/intensity=6");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "was rendered with other settings")) << r.err;
    EXPECT_TRUE(contains(r.err, "wrote")) << r.err;
}

TEST(ScenePatchCli, InfoTakesPatchesToo) {
    const fs::path dir = test::scratchDir("set-cli-info");
    test::writeFile(dir / "quad.json", kDirectQuad);
    const test::RunResult r =
        runStrahl("info " + (dir / "quad.json").string() + " --set /shapes/0/indices=[0,1,2]");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(contains(r.out, " 1 triangles")) << r.out;
}

// --clamp-direct and --clamp-indirect are scene patches like every flag: the
// image of --set, a fingerprint of their own, and, being biased, said in the
// image's metadata.
TEST(ScenePatchCli, ClampFlagsArePatchesAndRecordedInTheImage) {
    const fs::path dir = test::scratchDir("clamp-cli");
    test::writeFile(dir / "quad.json", kDirectQuad);
    const std::string scene = (dir / "quad.json").string() + " -q --integrator path";
    ASSERT_EQ(runStrahl("render " + scene + " --clamp-direct 0.25 -o " + (dir / "flag.exr").string()).status, 0);
    ASSERT_EQ(runStrahl("render " + scene + " --set /render/clamp_direct=0.25 -o " +
                        (dir / "set.exr").string())
                  .status,
              0);
    ASSERT_EQ(runStrahl("render " + scene + " -o " + (dir / "plain.exr").string()).status, 0);
    const test::ExrFile flag = readExr(dir / "flag.exr"), set = readExr(dir / "set.exr"),
                        plain = readExr(dir / "plain.exr");
    test::expectIdentical(flag, set, "--clamp-direct and --set");
    EXPECT_EQ(flag.fingerprint, set.fingerprint);
    EXPECT_NE(flag.fingerprint, plain.fingerprint);
    auto in = OIIO::ImageInput::open((dir / "flag.exr").string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("strahl:clamp_direct"), "0.250000");
    EXPECT_EQ(in->spec().get_string_attribute("strahl:clamp_indirect"), "");
    const test::RunResult bad = runStrahl("render " + scene + " --clamp-indirect -1 -o " +
                                          (dir / "bad.exr").string());
    EXPECT_EQ(bad.status, 2) << bad.err;
    EXPECT_FALSE(fs::exists(dir / "bad.exr"));
}

// --filter-glossy is a scene patch too, and biased: said in the image.
TEST(ScenePatchCli, FilterGlossyIsAPatchAndRecordedInTheImage) {
    const fs::path dir = test::scratchDir("filter-glossy-cli");
    test::writeFile(dir / "quad.json", kDirectQuad);
    const std::string scene = (dir / "quad.json").string() + " -q --integrator path";
    ASSERT_EQ(runStrahl("render " + scene + " --filter-glossy 0.5 -o " + (dir / "flag.exr").string()).status, 0);
    ASSERT_EQ(runStrahl("render " + scene + " --set /render/filter_glossy=0.5 -o " +
                        (dir / "set.exr").string())
                  .status,
              0);
    const test::ExrFile flag = readExr(dir / "flag.exr"), set = readExr(dir / "set.exr");
    test::expectIdentical(flag, set, "--filter-glossy and --set");
    EXPECT_EQ(flag.fingerprint, set.fingerprint);
    auto in = OIIO::ImageInput::open((dir / "flag.exr").string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("strahl:filter_glossy"), "0.500000");
    const test::RunResult bad = runStrahl("render " + scene + " --filter-glossy -1 -o " +
                                          (dir / "bad.exr").string());
    EXPECT_EQ(bad.status, 2) << bad.err;
    EXPECT_FALSE(fs::exists(dir / "bad.exr"));
}

TEST(ScenePatchCli, AdaptiveSamplingFlagsArePatchesAndRecordedInTheImage) {
    const fs::path dir = test::scratchDir("adaptive-cli");
    test::writeFile(dir / "quad.json", kDirectQuad);
    const std::string scene = (dir / "quad.json").string() + " -q --integrator path --spp 8";
    ASSERT_EQ(runStrahl("render " + scene + " --adaptive-threshold 0.25 --adaptive-min-samples 4 -o " +
                        (dir / "flag.exr").string())
                  .status,
              0);
    ASSERT_EQ(runStrahl("render " + scene +
                        " --set '/render/adaptive={\"threshold\":0.25,\"min_samples\":4}' -o " +
                        (dir / "set.exr").string())
                  .status,
              0);
    const test::ExrFile flag = readExr(dir / "flag.exr"), set = readExr(dir / "set.exr");
    test::expectIdentical(flag, set, "--adaptive-threshold and --set");
    EXPECT_EQ(flag.fingerprint, set.fingerprint);
    auto in = OIIO::ImageInput::open((dir / "flag.exr").string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("strahl:adaptive_threshold"), "0.250000");
    EXPECT_EQ(in->spec().get_string_attribute("strahl:adaptive_min_samples"), "4");
    EXPECT_GE(in->spec().channelindex("samples.X"), 0);
    const test::RunResult bad = runStrahl("render " + scene + " --adaptive-threshold 2 -o " +
                                          (dir / "bad.exr").string());
    EXPECT_EQ(bad.status, 2) << bad.err;
    EXPECT_FALSE(fs::exists(dir / "bad.exr"));
}

}  // namespace
}  // namespace strahl
