// The path-tracing bench as a library: the Cornell box of the repository is
// rendered with the overrides asked for and every figure filled in; a scene
// whose data is absent is a skipped row naming the file; unknown names and
// missing scene files are clear errors; Sponza runs when ../shared/data is
// there; the JSON results carry the path rows. (No speed is asserted.)

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "strahl/benchmark/path_bench.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::contains;

// 32x32 at 2 spp: every figure is exercised in well under a second.
PathBenchOptions tinyRun(std::vector<std::string> scenes) {
    PathBenchOptions options;
    options.scenesDir = test::sourceDir() / "scenes";
    options.scenes = std::move(scenes);
    options.resolution = 32;
    options.spp = 2;
    return options;
}

// The figures every measured row must have, whatever the scene.
void expectMeasured(const PathBenchRow& r, const PathBenchOptions& options) {
    EXPECT_FALSE(r.skipped) << r.skipReason;
    EXPECT_EQ(r.width, options.resolution);
    EXPECT_EQ(r.height, options.resolution);
    EXPECT_EQ(r.spp, options.spp);
    EXPECT_EQ(r.maxDepth, options.maxDepth);
    EXPECT_GT(r.triangles, 0u);
    EXPECT_GE(r.loadSeconds, 0.0);
    EXPECT_GE(r.bvhSeconds, 0.0);
    EXPECT_GT(r.renderSeconds, 0.0);
    EXPECT_GT(r.firstTileSeconds, 0.0);
    EXPECT_LE(r.firstTileSeconds, r.renderSeconds);
    EXPECT_GT(r.firstPixelSeconds(), 0.0);
    EXPECT_LE(r.firstPixelSeconds(), r.loadSeconds + r.bvhSeconds + r.renderSeconds);
    // One camera ray per sample, traced in packets.
    EXPECT_EQ(r.cameraRays, uint64_t(options.resolution) * uint64_t(options.resolution) *
                                uint64_t(options.spp));
    EXPECT_TRUE(r.packetWidth == 8 || r.packetWidth == 16) << r.packetWidth;
    EXPECT_DOUBLE_EQ(r.samples(), double(r.cameraRays));
    EXPECT_GT(r.samplesPerSecond(), 0.0);
    EXPECT_GT(r.mraysPerSecond(), 0.0);
    EXPECT_GE(r.raysPerSample(), 1.0);
}

TEST(PathBench, RendersTheCornellBoxWithEveryFigureFilledIn) {
    const PathBenchOptions options = tinyRun({"cornell"});
    std::vector<std::string> said;
    const std::vector<PathBenchRow> rows =
        runPathBench(options, [&](const std::string& s) { said.push_back(s); });
    ASSERT_EQ(rows.size(), 1u);
    const PathBenchRow& r = rows[0];
    EXPECT_EQ(r.scene, "cornell");
    EXPECT_EQ(r.file.filename(), "default.json");
    expectMeasured(r, options);
    // A box lit from inside, open towards the camera: most paths bounce
    // several times, with a shadow ray at every diffuse vertex.
    EXPECT_GT(r.shadowRays, r.cameraRays);
    EXPECT_GT(r.bounceRays, r.cameraRays);
    EXPECT_GT(r.raysPerSample(), 3.0);
    EXPECT_FALSE(said.empty());

    // The same scene twice in one run: the ratio is defined, the bench is not
    // (both renders are cold); a scene not measured has no ratio.
    EXPECT_FALSE(pathCostRatio(rows, "sponza", "cornell").has_value());
    const auto self = pathCostRatio(rows, "cornell", "cornell");
    ASSERT_TRUE(self.has_value());
    EXPECT_DOUBLE_EQ(self->perSample, 1.0);
    EXPECT_DOUBLE_EQ(self->perRay, 1.0);
}

TEST(PathBench, DepthZeroSeesOnlyEmitters) {
    PathBenchOptions options = tinyRun({"cornell"});
    options.maxDepth = 0;
    const std::vector<PathBenchRow> rows = runPathBench(options);
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0].maxDepth, 0);
    // No light sampling and no bounce: the camera rays alone.
    EXPECT_EQ(rows[0].shadowRays, 0u);
    EXPECT_EQ(rows[0].bounceRays, 0u);
    EXPECT_DOUBLE_EQ(rows[0].raysPerSample(), 1.0);
}

TEST(PathBench, AbsentDataIsASkippedRowNamingTheFile) {
    // A scenes folder shaped like the repository's, whose Sponza refers to a
    // mesh that is not there.
    const fs::path dir = test::scratchDir("path-bench-skip");
    test::writeFile(dir / "default.json",
                    test::readFile(test::sourceDir() / "scenes/default.json"));
    test::writeFile(dir / "showcase/sponza.json",
                    "// no data\n{ \"shapes\": [ { \"type\": \"mesh\", \"file\": "
                    "\"../missing/sponza.obj\" } ] }\n");
    PathBenchOptions options = tinyRun({"sponza"});
    options.scenesDir = dir;
    const std::vector<PathBenchRow> rows = runPathBench(options);
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_TRUE(rows[0].skipped);
    EXPECT_EQ(rows[0].skipReason, (dir / "missing/sponza.obj").string() + " not found");
    EXPECT_EQ(rows[0].renderSeconds, 0.0);
    EXPECT_EQ(rows[0].samplesPerSecond(), 0.0);

    std::FILE* table = std::tmpfile();
    ASSERT_NE(table, nullptr);
    printPathBenchTable(table, rows);
    std::rewind(table);
    std::string text(4096, '\0');
    text.resize(std::fread(text.data(), 1, text.size(), table));
    std::fclose(table);
    EXPECT_TRUE(contains(text, "sponza    skipped: " + (dir / "missing/sponza.obj").string() +
                                   " not found"))
        << text;
    EXPECT_FALSE(contains(text, "cost ratio")) << text;
}

TEST(PathBench, UnknownScenesAndFoldersAreClearErrors) {
    EXPECT_EQ(test::errorMessage([] { pathBenchFiles(tinyRun({"teapot"})); }),
              "bench: unknown path scene 'teapot' (known: cornell, sponza, none)");
    PathBenchOptions nowhere = tinyRun({"cornell"});
    nowhere.scenesDir = "/nonexistent/scenes";
    EXPECT_EQ(test::errorMessage([&] { runPathBench(nowhere); }),
              "bench: the scenes folder /nonexistent/scenes does not exist (give --scenes DIR, "
              "or --path none)");
    PathBenchOptions empty = tinyRun({"cornell"});
    empty.scenesDir = test::scratchDir("path-bench-empty");
    EXPECT_TRUE(contains(test::errorMessage([&] { pathBenchFiles(empty); }),
                         "bench: path scene 'cornell': no file "));
    EXPECT_TRUE(pathBenchFiles(tinyRun({})).empty());
    PathBenchOptions noSamples = tinyRun({"cornell"});
    noSamples.spp = 0;
    EXPECT_TRUE(contains(test::errorMessage([&] { runPathBench(noSamples); }),
                         "samples per pixel must be at least 1"));
}

TEST(PathBench, SponzaFromTheSharedData) {
    STRAHL_REQUIRE_SHARED_DATA();
    // 1 spp: Sponza's load (mesh and textures) dominates anyway.
    PathBenchOptions options = tinyRun({"cornell", "sponza"});
    options.spp = 1;
    const std::vector<PathBenchRow> rows = runPathBench(options);
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[1].scene, "sponza");
    expectMeasured(rows[1], options);
    // Dabrovic's Sponza has about 66k triangles; the Cornell box a few hundred.
    EXPECT_GT(rows[1].triangles, 50000u);
    EXPECT_GT(rows[1].triangles, rows[0].triangles);
    const auto ratio = pathCostRatio(rows, "sponza", "cornell");
    ASSERT_TRUE(ratio.has_value());
    EXPECT_GT(ratio->perSample, 0.0);
    EXPECT_GT(ratio->perRay, 0.0);
}

TEST(PathBench, JsonResultsCarryThePathRows) {
    const fs::path dir = test::scratchDir("path-bench-report");
    const PathBenchOptions options = tinyRun({"cornell"});
    std::vector<PathBenchRow> rows = runPathBench(options);
    PathBenchRow skipped;
    skipped.scene = "sponza";
    skipped.skipped = true;
    skipped.skipReason = "/x/sponza.obj not found";
    rows.push_back(skipped);

    writeBenchResults(dir / "r.json", {}, BenchFits{}, BenchOptions{}, rows, options);
    const std::string json = test::readFile(dir / "r.json");
    EXPECT_TRUE(contains(json, "\"path_options\": {\n    \"resolution\": 32,\n    \"spp\": 2"))
        << json;
    EXPECT_TRUE(contains(json, "\"scene\": \"cornell\"")) << json;
    EXPECT_TRUE(contains(json, "\"samples_per_s\": ")) << json;
    EXPECT_TRUE(contains(json, "\"first_pixel_s\": ")) << json;
    EXPECT_TRUE(contains(json, "\"reason\": \"/x/sponza.obj not found\"")) << json;
    EXPECT_FALSE(contains(json, "path_cost_ratio")) << json;  // sponza was not measured

    // CSV: the ladder and model table only.
    writeBenchResults(dir / "r.csv", {}, BenchFits{}, BenchOptions{}, rows, options);
    const std::string csv = test::readFile(dir / "r.csv");
    EXPECT_TRUE(contains(csv, "scene,generated,triangles,")) << csv;
    EXPECT_FALSE(contains(csv, "cornell")) << csv;
}

}  // namespace
}  // namespace strahl
