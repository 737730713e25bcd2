// The farm-facing CLI (docs/farm.md): frame-numbered output names, --skip-existing,
// --region and `strahl assemble` (bit-identical to a full render), JSON progress
// lines and the --stats file; every error path with its message, exit status
// and no output file.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/app_test_helpers.h"
#include "app/cli_runner.h"
#include "app/exr_file.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::contains;
using test::runStrahl;

// Path-traced, with glass, metals, implicit and parametric shapes: every pixel
// is a long sum, so any difference in sample order would show in the bits.
using test::kGlossyRoom;
const std::string kFarmFlags = " --width 48 --height 36 --spp 4 -q";

using test::ExrFile;
using test::expectIdentical;
using test::readExr;

size_t filesIn(const fs::path& dir) {
    return static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

size_t lines(const std::string& text) {
    return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

// A one-line error with this exit status and message, and nothing written.
void expectError(const test::RunResult& r, int status, const std::string& message,
                 const fs::path& dir, size_t filesBefore) {
    EXPECT_EQ(r.status, status) << r.err;
    EXPECT_TRUE(contains(r.err, message)) << "expected '" << message << "' in\n" << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_EQ(filesIn(dir), filesBefore) << "an error left a file behind";
}

test::RunResult render(const std::string& args) {
    return runStrahl("render " + kGlossyRoom + kFarmFlags + " " + args);
}

TEST(FarmHelp, HelpListsTheFarmOptionsAndAssemble) {
    test::RunResult r = runStrahl("render --help");
    EXPECT_EQ(r.status, 0);
    for (const char* option :
         {"--region", "--frame", "--skip-existing", "--progress-format", "--stats"})
        EXPECT_TRUE(contains(r.out, option)) << option;
    r = runStrahl("assemble --help");
    EXPECT_EQ(r.status, 0);
    for (const char* option : {"--output", "--allow-gaps", "--allow-partial", "--quiet"})
        EXPECT_TRUE(contains(r.out, option)) << option;
    EXPECT_TRUE(contains(runStrahl("--help").out, "strahl assemble"));
}

// ---------------------------------------------------------------- frame names

TEST(FarmFrame, HashRunsBecomeTheZeroPaddedFrameNumber) {
    const fs::path dir = test::scratchDir("farm-frame");
    test::RunResult r = render("--frame 42 -o " + (dir / "beauty.####.exr").string() + " -o " +
                               (dir / "beauty.#.png").string());
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_TRUE(fs::exists(dir / "beauty.0042.exr"));
    EXPECT_TRUE(fs::exists(dir / "beauty.42.png"));  // more digits than #'s: printed in full
    EXPECT_EQ(readExr(dir / "beauty.0042.exr").frame, "42");

    r = render("--frame 123456 -o " + (dir / "big.####.exr").string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "big.123456.exr"));
    EXPECT_EQ(filesIn(dir), 3u);
}

TEST(FarmFrame, APatternWithoutFrameIsAUsageError) {
    const fs::path dir = test::scratchDir("farm-frame-missing");
    expectError(render("-o " + (dir / "beauty.####.exr").string()), 2,
                "beauty.####.exr: the name has a '#' frame pattern but no --frame N was given",
                dir, 0);
    expectError(render("-o " + (dir / "a.exr").string() + " --stats " +
                       (dir / "s.##.json").string()),
                2, "--stats", dir, 0);
    expectError(render("--frame -1 -o " + (dir / "a.#.exr").string()), 2, "--frame", dir, 0);
}

// A scene of its own, with a mesh file next to it and a '#' pattern in
// film.outputs (resolved against the scene's folder).
fs::path writeMeshScene(const fs::path& dir) {
    test::writeFile(dir / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
    const fs::path scene = dir / "scene.json";
    test::writeFile(scene, R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 60 },
      "film": { "width": 16, "height": 12, "outputs": ["out/frame.###.exr"] },
      "render": { "integrator": "eyelight", "spp": 1 },
      "shapes": [ { "type": "mesh", "file": "tri.obj" } ]
    })");
    fs::create_directories(dir / "out");
    return scene;
}

TEST(FarmFrame, SceneOutputPatternsNeedAFrameToo) {
    const fs::path dir = test::scratchDir("farm-frame-scene");
    const fs::path scene = writeMeshScene(dir);
    test::RunResult r = runStrahl("render " + scene.string() + " -q");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "film.outputs")) << r.err;
    EXPECT_TRUE(contains(r.err, "no --frame N was given")) << r.err;
    EXPECT_EQ(filesIn(dir / "out"), 0u);

    r = runStrahl("render " + scene.string() + " -q --frame 7");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "out/frame.007.exr"));
}

// ---------------------------------------------------------------- skip existing

TEST(FarmSkipExisting, SkipsCompleteOutputsWithoutLoadingTheScene) {
    const fs::path dir = test::scratchDir("farm-skip");
    const fs::path scene = writeMeshScene(dir);
    const std::string args = "render " + scene.string() + " --frame 3 --skip-existing";
    test::RunResult r = runStrahl(args + " -q");
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_TRUE(fs::exists(dir / "out/frame.003.exr"));
    const auto written = fs::last_write_time(dir / "out/frame.003.exr");

    // The mesh is now broken: a render would fail loading it, so a skip proves
    // that nothing but the scene file was read.
    test::writeFile(dir / "tri.obj", "f 1 2 3\n");
    r = runStrahl(args);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "skipped: every output exists and is complete: " +
                         (dir / "out/frame.003.exr").string() + "\n");
    EXPECT_EQ(fs::last_write_time(dir / "out/frame.003.exr"), written);

    r = runStrahl(args + " --progress-format json");
    EXPECT_EQ(r.status, 0) << r.err;
    const json event = json::parse(r.out);
    EXPECT_EQ(event["event"], "skipped");
    EXPECT_EQ(event["outputs"][0], (dir / "out/frame.003.exr").string());
    EXPECT_EQ(event["exit_status"], 0);

    // Another frame does not exist yet: rendered, and the broken mesh is an error.
    r = runStrahl("render " + scene.string() + " --frame 4 --skip-existing -q");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "tri.obj")) << r.err;
}

TEST(FarmSkipExisting, RendersAgainWhatIsPartialOrMadeWithOtherSettings) {
    const fs::path dir = test::scratchDir("farm-skip-partial");
    const fs::path out = dir / "a.exr";
    // A time limit of 0 s stops after one of 16 passes: a partial image.
    ASSERT_EQ(runStrahl("render " + kGlossyRoom +
                        " --width 48 --height 36 --spp 16 -q --time-limit 0 -o " + out.string())
                  .status,
              0);
    ASSERT_EQ(readExr(out).partial, "1");
    const std::string args = "render " + kGlossyRoom +
                             " --width 48 --height 36 --spp 16 --skip-existing -o " + out.string();
    test::RunResult r = runStrahl(args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "a.exr is partial (stopped by time limit): rendering it again"))
        << r.err;
    EXPECT_EQ(readExr(out).partial, "0");

    r = runStrahl(args);  // now complete
    EXPECT_TRUE(contains(r.err, "skipped")) << r.err;

    // Other samples per pixel: another image (strahl:fingerprint), rendered.
    r = runStrahl("render " + kGlossyRoom + " --width 48 --height 36 --spp 8 --skip-existing -o " +
                  out.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "was rendered with other settings")) << r.err;
    EXPECT_TRUE(contains(r.err, "wrote")) << r.err;

    // A damaged file is not complete either.
    test::writeFile(out, "not an image");
    r = runStrahl("render " + kGlossyRoom + " --width 48 --height 36 --spp 8 --skip-existing -o " +
                  out.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "cannot be read")) << r.err;
    EXPECT_EQ(readExr(out).partial, "0");
}

TEST(FarmSkipExisting, JpegAloneCannotVouchForItself) {
    const fs::path dir = test::scratchDir("farm-skip-jpeg");
    const std::string jpeg = " -o " + (dir / "a.jpg").string();
    ASSERT_EQ(render(jpeg).status, 0);
    test::RunResult r = runStrahl("render " + kGlossyRoom + " --width 48 --height 36 --spp 4 "
                                  "--skip-existing" + jpeg);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "JPEG and TIFF images do not record whether they are partial"))
        << r.err;
    EXPECT_TRUE(contains(r.err, "wrote")) << r.err;
    // With an EXR next to it, the pair is skipped.
    const std::string both = jpeg + " -o " + (dir / "a.exr").string();
    ASSERT_EQ(render(both).status, 0);
    r = runStrahl("render " + kGlossyRoom + " --width 48 --height 36 --spp 4 --skip-existing" +
                  both);
    EXPECT_TRUE(contains(r.err, "skipped: every output exists and is complete")) << r.err;
}

// ---------------------------------------------------------------- regions

TEST(FarmRegion, BadRegionsAreOneErrorAndWriteNothing) {
    const fs::path dir = test::scratchDir("farm-region");
    const std::string out = " -o " + (dir / "r.exr").string();
    // Known from the command line alone: exit 2.
    expectError(render("--region 10 0 10 10" + out), 2,
                "--region 10 0 10 10 is empty or negative", dir, 0);
    expectError(render("--region -4 0 10 10" + out), 2, "is empty or negative", dir, 0);
    expectError(render("--region 1 a 3 4" + out), 2,
                "--region expects X0 Y0 X1 Y1 (four integers), got '1 a 3 4'", dir, 0);
    expectError(render("--region 0 0 8 8 --crop 0,0,8,8" + out), 2,
                "--region and --crop name the same rectangle", dir, 0);
    // Outside the image: known once the scene's size is, exit 1, before loading.
    expectError(render("--region 40 0 49 10" + out), 1,
                "--region 40 0 49 10 exceeds the 48x36 image (need X1 <= 48 and Y1 <= 36)", dir,
                0);
    expectError(render("--region 60 40 70 50" + out), 1, "exceeds the 48x36 image", dir, 0);
}

TEST(FarmRegion, RegionIsTheCropWindowOfTheFullImage) {
    const fs::path dir = test::scratchDir("farm-region-crop");
    ASSERT_EQ(render("--region 8 4 40 20 -o " + (dir / "region.exr").string()).status, 0);
    ASSERT_EQ(render("--crop 8,4,40,20 -o " + (dir / "crop.exr").string()).status, 0);
    const ExrFile region = readExr(dir / "region.exr");
    EXPECT_EQ(region.x, 8);
    EXPECT_EQ(region.y, 4);
    EXPECT_EQ(region.width, 32);
    EXPECT_EQ(region.height, 16);
    EXPECT_EQ(region.fullWidth, 48);
    EXPECT_EQ(region.fullHeight, 36);
    expectIdentical(region, readExr(dir / "crop.exr"));
}

TEST(FarmRegion, TheScenesFilmCropIsTheCropUnlessTheCommandLineGivesOne) {
    const fs::path dir = test::scratchDir("farm-film-crop");
    const std::string sceneCrop = " --set /film/crop=[8,4,40,20]";
    ASSERT_EQ(render(sceneCrop + " -o " + (dir / "scene.exr").string()).status, 0);
    ASSERT_EQ(render("--crop 8,4,40,20 -o " + (dir / "cli.exr").string()).status, 0);
    expectIdentical(readExr(dir / "scene.exr"), readExr(dir / "cli.exr"));
    // --region overrides it.
    ASSERT_EQ(render(sceneCrop + " --region 0 0 8 8 -o " + (dir / "region.exr").string()).status, 0);
    EXPECT_EQ(readExr(dir / "region.exr").width, 8);
    // A film made smaller than the scene's crop from the command line: the
    // crop is checked against the size the command line gives.
    expectError(runStrahl("render " + kGlossyRoom + " --height 36 --spp 4 --width 30" + sceneCrop +
                          " -o " + (dir / "small.exr").string()),
                1, "/film/crop/2: must be between 9 and 30, got 40", dir, 3);
}

// ---------------------------------------------------------------- assemble

// Three regions that tile the 48 x 36 image; names as in the farm docs.
const std::vector<std::string> kRegions = {"0 0 16 36", "16 0 48 20", "16 20 48 36"};

std::vector<fs::path> renderRegions(const fs::path& dir, const std::string& flags) {
    std::vector<fs::path> files;
    for (size_t i = 0; i < kRegions.size(); ++i) {
        files.push_back(dir / ("region" + std::to_string(i) + ".exr"));
        const test::RunResult r =
            render(flags + " --region " + kRegions[i] + " -o " + files.back().string());
        EXPECT_EQ(r.status, 0) << r.err;
    }
    return files;
}

std::string joined(const std::vector<fs::path>& files) {
    std::string list;
    for (const fs::path& f : files) {
        // Two appends, not `" " + f.string()`: GCC 12 warns (-Wrestrict, a
        // false positive) about the temporary that expression builds.
        list += ' ';
        list += f.string();
    }
    return list;
}

class FarmAssemble : public ::testing::TestWithParam<std::string> {};

TEST_P(FarmAssemble, RegionsStitchToTheFullRenderBitForBit) {
    const std::string flags = GetParam();
    const fs::path dir = test::scratchDir("farm-assemble");
    ASSERT_EQ(render(flags + " -o " + (dir / "full.exr").string()).status, 0);
    const std::vector<fs::path> regions = renderRegions(dir, flags);
    const test::RunResult r =
        runStrahl("assemble" + joined(regions) + " -o " + (dir / "assembled.exr").string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "assembled 3 regions into")) << r.err;
    const ExrFile full = readExr(dir / "full.exr");
    const ExrFile assembled = readExr(dir / "assembled.exr");
    EXPECT_EQ(assembled.x, 0);
    EXPECT_EQ(assembled.y, 0);
    EXPECT_EQ(assembled.width, 48);
    EXPECT_EQ(assembled.height, 36);
    EXPECT_EQ(assembled.partial, "0");
    EXPECT_EQ(assembled.fingerprint, full.fingerprint);
    expectIdentical(full, assembled);
}

INSTANTIATE_TEST_SUITE_P(Formats, FarmAssemble,
                         ::testing::Values(" --exr-float --aov albedo --aov variance --aov depth",
                                           " --aov normal --aov objectid"),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                             return std::string(p.index == 0 ? "Float" : "Half");
                         });

TEST(FarmAssembleErrors, OverlapGapMismatchMissingAndPartialAreOneClearError) {
    const fs::path dir = test::scratchDir("farm-assemble-errors");
    const std::vector<fs::path> regions = renderRegions(dir, "");
    const std::string out = " -o " + (dir / "out.exr").string();
    size_t files = filesIn(dir);

    ASSERT_EQ(render("--region 10 0 20 10 -o " + (dir / "overlap.exr").string()).status, 0);
    ++files;
    expectError(runStrahl("assemble" + joined(regions) + " " + (dir / "overlap.exr").string() + out),
                1,
                regions[0].string() + " and " + (dir / "overlap.exr").string() +
                    " overlap in pixels 10 0 16 10",
                dir, files);

    expectError(runStrahl("assemble " + regions[0].string() + " " + regions[1].string() + out), 1,
                "the regions leave 512 of 1728 pixels uncovered: 16 20 48 36", dir, files);

    ASSERT_EQ(render("--seed 99 --region 16 20 48 36 -o " + (dir / "seed.exr").string()).status, 0);
    ++files;
    expectError(runStrahl("assemble " + regions[0].string() + " " + regions[1].string() + " " +
                          (dir / "seed.exr").string() + out),
                1, "seed.exr: different strahl:fingerprint", dir, files);

    ASSERT_EQ(render("--aov depth --region 16 20 48 36 -o " + (dir / "aov.exr").string()).status, 0);
    ++files;
    expectError(runStrahl("assemble " + regions[0].string() + " " + regions[1].string() + " " +
                          (dir / "aov.exr").string() + out),
                1, "aov.exr: different channels (R,G,B and R,G,B,depth.Z)", dir, files);

    expectError(runStrahl("assemble " + regions[0].string() + " " + (dir / "nope.exr").string() +
                          out),
                1, "nope.exr: no such file", dir, files);

    test::writeFile(dir / "text.exr", "not an image");
    ++files;
    expectError(runStrahl("assemble " + regions[0].string() + " " + (dir / "text.exr").string() +
                          out),
                1, "text.exr: cannot read", dir, files);

    expectError(runStrahl("assemble" + joined(regions) + " -o " + (dir / "out.png").string()), 1,
                "out.png: assemble writes EXR only", dir, files);
    expectError(runStrahl("assemble" + joined(regions)), 2, "--output is required", dir, files);
}

TEST(FarmAssembleErrors, GapsAndPartialRegionsOnlyOnRequestAndMarkedPartial) {
    const fs::path dir = test::scratchDir("farm-assemble-partial");
    const std::vector<fs::path> regions = renderRegions(dir, "");
    const fs::path out = dir / "out.exr";

    test::RunResult r = runStrahl("assemble " + regions[0].string() + " " + regions[1].string() +
                                  " --allow-gaps -o " + out.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "strahl: warning: the regions leave 512 of 1728 pixels uncovered"))
        << r.err;
    ExrFile image = readExr(out);
    EXPECT_EQ(image.partial, "1");
    ASSERT_EQ(image.pixels.size(), 48u * 36u * 3u);
    EXPECT_EQ(image.pixels[(30 * 48 + 40) * 3], 0.0f);  // pixel (40, 30) is in the gap
    fs::remove(out);

    // A time-limited region: partial. An error unless --allow-partial.
    const fs::path cut = dir / "cut.exr";
    ASSERT_EQ(
        runStrahl("render " + kGlossyRoom +
                  " --width 48 --height 36 --spp 4 -q --time-limit 0 --region 16 20 48 36 -o " +
                  cut.string())
            .status,
        0);
    const size_t files = filesIn(dir);
    expectError(runStrahl("assemble " + regions[0].string() + " " + regions[1].string() + " " +
                          cut.string() + " -o " + out.string()),
                1, "cut.exr: is partial (strahl:partial = 1, stopped by time limit, 1 of 4", dir,
                files);
    r = runStrahl("assemble " + regions[0].string() + " " + regions[1].string() + " " +
                  cut.string() + " --allow-partial -o " + out.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(readExr(out).partial, "1");
}

// ---------------------------------------------------------------- JSON progress, stats

std::vector<json> jsonLines(const std::string& text) {
    std::vector<json> events;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        EXPECT_NO_THROW(events.push_back(json::parse(line))) << "not a JSON line: " << line;
    }
    return events;
}

TEST(FarmProgress, JsonLinesOnStdoutFromStartToDone) {
    const fs::path dir = test::scratchDir("farm-progress");
    const fs::path out = dir / "a.0005.exr";
    const test::RunResult r = runStrahl("render " + kGlossyRoom +
                                        " --width 48 --height 36 --spp 4 --frame 5 -o " +
                                        (dir / "a.####.exr").string() + " --progress-format json");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "summary:")) << "the human-readable text stays on stderr";
    const std::vector<json> events = jsonLines(r.out);
    ASSERT_GE(events.size(), 6u) << r.out;

    EXPECT_EQ(events.front()["event"], "start");
    EXPECT_EQ(events.front()["scene"], kGlossyRoom);
    EXPECT_EQ(events.front()["frame"], 5);
    EXPECT_EQ(events.front()["resolution"], json::array({48, 36}));
    EXPECT_EQ(events.front()["region"], json::array({0, 0, 48, 36}));
    EXPECT_EQ(events.front()["spp"], 4);

    std::vector<int> passes;
    double lastElapsed = 0.0;
    for (const json& e : events) {
        ASSERT_TRUE(e.contains("elapsed")) << e;
        EXPECT_GE(e["elapsed"].get<double>(), lastElapsed) << e;
        lastElapsed = e["elapsed"].get<double>();
        if (e["event"] == "pass" || e["event"] == "progress") {
            EXPECT_GE(e["fraction"].get<double>(), 0.0) << e;
            EXPECT_LE(e["fraction"].get<double>(), 1.0) << e;
            EXPECT_TRUE(e.contains("eta") && e.contains("phase")) << e;
            EXPECT_EQ(e["passes_total"], 4) << e;
        }
        if (e["event"] == "pass") passes.push_back(e["passes_done"].get<int>());
    }
    EXPECT_EQ(passes, (std::vector<int>{1, 2, 3, 4}));

    const json& done = events.back();
    EXPECT_EQ(done["event"], "done");
    EXPECT_EQ(done["status"], "complete");
    EXPECT_EQ(done["partial"], false);
    EXPECT_EQ(done["passes_done"], 4);
    EXPECT_EQ(done["outputs"], json::array({out.string()}));
    EXPECT_EQ(done["exit_status"], 0);
    EXPECT_TRUE(fs::exists(out));
}

TEST(FarmProgress, AnErrorEndsTheJsonStreamToo) {
    const fs::path dir = test::scratchDir("farm-progress-error");
    const test::RunResult r = runStrahl("render " + kGlossyRoom +
                                        " --width 48 --height 36 --region 0 0 64 8 -o " +
                                        (dir / "a.exr").string() + " --progress-format json");
    EXPECT_EQ(r.status, 1);
    const std::vector<json> events = jsonLines(r.out);
    ASSERT_EQ(events.size(), 1u) << r.out;
    EXPECT_EQ(events[0]["event"], "error");
    EXPECT_TRUE(contains(events[0]["message"].get<std::string>(), "exceeds the 48x36 image"));
    EXPECT_EQ(events[0]["exit_status"], 1);
    EXPECT_EQ(filesIn(dir), 0u);
}

json readJsonFile(const fs::path& file) {
    const std::string text = test::readFile(file);
    try {
        return json::parse(text);
    } catch (const std::exception& e) {
        ADD_FAILURE() << file << ": " << e.what() << "\n" << text;
        return {};
    }
}

TEST(FarmStats, TheStatsFileHasEveryDocumentedField) {
    const fs::path dir = test::scratchDir("farm-stats");
    const fs::path image = dir / "a.exr";
    const test::RunResult r = runStrahl(
        "render " + kGlossyRoom +
        " --width 48 --height 36 --spp 4 --threads 2 -q --region 8 0 48 36 --frame 9 -o " +
        image.string() + " --stats " + (dir / "stats.#.json").string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(filesIn(dir), 2u) << "no temporary file is left";
    const json s = readJsonFile(dir / "stats.9.json");
    EXPECT_EQ(s["strahl_version"], STRAHL_VERSION);
    EXPECT_EQ(s["scene"], kGlossyRoom);
    EXPECT_EQ(s["frame"], 9);
    EXPECT_EQ(s["resolution"], json::array({48, 36}));
    EXPECT_EQ(s["region"], json::array({8, 0, 48, 36}));
    EXPECT_EQ(s["spp"], 4);
    EXPECT_EQ(s["seed"], 7);  // the scene's render.seed
    EXPECT_EQ(s["integrator"], "path");
    EXPECT_EQ(s["algorithm"], "raytrace");
    EXPECT_EQ(s["accel"], "embree");
    EXPECT_EQ(s["samples"], json({{"begin", 0}, {"end", 4}, {"done", 4}}));
    EXPECT_EQ(s["threads"], 2);
    for (const char* key : {"load", "bvh", "render", "first_pixel", "denoise", "total"})
        EXPECT_GE(s["timings"][key].get<double>(), 0.0) << key;
    EXPECT_GE(s["timings"]["total"].get<double>(), s["timings"]["render"].get<double>());
    const json& rays = s["rays"];
    EXPECT_EQ(rays["camera"], 40 * 36 * 4);  // one camera ray per sample of the region
    EXPECT_EQ(rays["total"].get<uint64_t>(), rays["camera"].get<uint64_t>() +
                                                 rays["shadow"].get<uint64_t>() +
                                                 rays["bounce"].get<uint64_t>());
    EXPECT_GT(rays["per_second"].get<uint64_t>(), 0u);
    EXPECT_GT(s["peak_resident_bytes"].get<uint64_t>(), 1u << 20);
    EXPECT_EQ(s["outputs"], json::array({image.string()}));
    EXPECT_EQ(s["status"], "complete");
    EXPECT_EQ(s["partial"], false);
    EXPECT_TRUE(s["stopped"].is_null());
    EXPECT_EQ(s["exit_status"], 0);
}

TEST(FarmStats, AnUnwritableStatsPathFailsBeforeTheRender) {
    const fs::path dir = test::scratchDir("farm-stats-bad");
    const std::string out = " -o " + (dir / "a.exr").string();
    expectError(render(out + " --stats " + (dir / "missing/s.json").string()), 1,
                "s.json: cannot write the statistics: folder '" + (dir / "missing").string() +
                    "' does not exist",
                dir, 0);
    expectError(render(out + " --stats " + dir.string()), 1, "--stats names a folder, not a file",
                dir, 0);
    if (geteuid() != 0) {  // root writes anywhere
        fs::create_directories(dir / "ro");
        fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec);
        expectError(render(out + " --stats " + (dir / "ro/s.json").string()), 1,
                    "cannot write the statistics in folder", dir, 1);
        fs::permissions(dir / "ro", fs::perms::owner_all);
    }
}

TEST(FarmStats, ATimeLimitIsMarkedInStatsAndTheLastEvent) {
    const fs::path dir = test::scratchDir("farm-stats-limit");
    const test::RunResult r = runStrahl("render " + kGlossyRoom +
                                        " --width 48 --height 36 --spp 16 -q --time-limit 0 -o " +
                                        (dir / "a.exr").string() + " --stats " +
                                        (dir / "s.json").string() + " --progress-format json");
    ASSERT_EQ(r.status, 0) << r.err;
    const json s = readJsonFile(dir / "s.json");
    EXPECT_EQ(s["status"], "time limit");
    EXPECT_EQ(s["partial"], true);
    EXPECT_EQ(s["stopped"], "time limit");
    EXPECT_EQ(s["samples"]["done"], 1);
    EXPECT_EQ(s["exit_status"], 0);
    const std::vector<json> events = jsonLines(r.out);
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events.back()["event"], "interrupted");
    EXPECT_EQ(events.back()["stopped"], "time limit");
    EXPECT_EQ(events.back()["passes_done"], 1);
}

TEST(FarmStats, AnInterruptIsMarkedInStatsAndTheLastEvent) {
    const fs::path dir = test::scratchDir("farm-stats-interrupt");
    const fs::path checkpoint = dir / "c.ckpt";
    // A checkpoint after every pass; its appearance says the render is under way.
    const pid_t pid = fork();
    if (pid == 0) {
        const std::string command =
            std::string(STRAHL_BINARY) + " render " + kGlossyRoom +
            " --width 48 --height 36 --spp 256 -q -o " + (dir / "a.exr").string() +
            " --stats " + (dir / "s.json").string() + " --checkpoint " + checkpoint.string() +
            " --checkpoint-interval 0 --progress-format json >" + (dir / "out.txt").string() +
            " 2>" + (dir / "err.txt").string();
        execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    for (int i = 0; i < 2000 && !fs::exists(checkpoint); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    kill(pid, SIGINT);
    int raw = 0;
    waitpid(pid, &raw, 0);
    const int status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    if (status == 0) GTEST_SKIP() << "the render finished before the signal arrived";
    ASSERT_EQ(status, 130) << test::readFile(dir / "err.txt");
    const json s = readJsonFile(dir / "s.json");
    EXPECT_EQ(s["status"], "interrupted");
    EXPECT_EQ(s["stopped"], "SIGINT");
    EXPECT_EQ(s["partial"], true);
    EXPECT_EQ(s["exit_status"], 130);
    EXPECT_LT(s["samples"]["done"].get<int>(), 256);
    const std::vector<json> events = jsonLines(test::readFile(dir / "out.txt"));
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events.back()["event"], "interrupted");
    EXPECT_EQ(events.back()["stopped"], "SIGINT");
    EXPECT_EQ(events.back()["exit_status"], 130);
}

}  // namespace
}  // namespace strahl
