// `strahl bench` as a library: the ladder meshes have the size asked for, bad
// sizes, models and folders are clear errors, one small scene is measured
// with every figure filled in and the naive tracer agreeing with Embree, the
// fits recover known growth laws, and the result files say what was measured.
// (No timing is asserted: speed is for bench/RESULTS.md, not for tests.)

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "strahl/benchmark/bench_report.h"
#include "strahl/benchmark/bench_scene.h"
#include "strahl/benchmark/bench_suite.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::contains;

TEST(BenchScene, LadderMeshesHaveAboutTheRequestedSize) {
    for (size_t n : {size_t(100), size_t(1000), size_t(10000), size_t(100000), size_t(1000000)}) {
        const TriangleMesh mesh = generateBenchMesh(n);
        SCOPED_TRACE(n);
        EXPECT_NO_THROW(mesh.validate("ladder"));
        // 2 segments (rings - 1) + 2 with whole rings and segments: within 10%.
        EXPECT_NEAR(double(mesh.triangleCount()), double(n), 0.1 * double(n));
        EXPECT_TRUE(mesh.isPadded());
    }
}

TEST(BenchScene, SizesParseAndAreBounded) {
    EXPECT_EQ(parseBenchSize("1e5"), 100000u);
    EXPECT_EQ(parseBenchSize("2500"), 2500u);
    EXPECT_EQ(test::errorMessage([] { parseBenchSize("lots"); }),
              "bench: 'lots' is not a triangle count (write e.g. 1000 or 1e6)");
    EXPECT_EQ(test::errorMessage([] { parseBenchSize("1e12"); }),
              "bench: a ladder size of 1e12 triangles is outside [100, 100000000]");
    EXPECT_EQ(test::errorMessage([] { parseBenchSize("5"); }),
              "bench: a ladder size of 5 triangles is outside [100, 100000000]");
    EXPECT_TRUE(contains(test::errorMessage([] { parseBenchSize("1.5"); }), "not a triangle count"));
}

TEST(BenchScene, SceneListNamesLadderRungsAndChecksModels) {
    const std::vector<size_t> ladder = {100, 1000, 2500};
    const std::vector<BenchSceneSpec> scenes = benchScenes(ladder, {}, "/nonexistent");
    ASSERT_EQ(scenes.size(), 3u);
    EXPECT_EQ(scenes[0].name, "ladder-1e2");
    EXPECT_EQ(scenes[1].name, "ladder-1e3");
    EXPECT_EQ(scenes[2].name, "ladder-2500");
    EXPECT_TRUE(scenes[0].generated());

    const std::vector<std::string> bunny = {"bunny"};
    EXPECT_EQ(test::errorMessage([&] { benchScenes({}, bunny, "/nonexistent/data"); }),
              "bench: the data folder /nonexistent/data does not exist (give --data DIR, or "
              "--models none)");
    const fs::path empty = test::scratchDir("bench-empty-data");
    const std::vector<std::string> teapot = {"teapot"};
    EXPECT_TRUE(contains(test::errorMessage([&] { benchScenes({}, teapot, empty); }),
                         "bench: unknown model 'teapot' (known: bunny, dragon,"));
    EXPECT_TRUE(contains(test::errorMessage([&] { benchScenes({}, bunny, empty); }),
                         "bench: model 'bunny': no file "));
}

TEST(BenchScene, ModelsFromTheSharedData) {
    STRAHL_REQUIRE_SHARED_DATA();
    const std::vector<std::string> all = {"all"};
    const std::vector<BenchSceneSpec> scenes = benchScenes({}, all, test::sharedData());
    EXPECT_EQ(scenes.size(), benchModels().size());
    for (const BenchSceneSpec& s : scenes) EXPECT_TRUE(fs::is_regular_file(s.file)) << s.name;
}

BenchOptions smallRun() {
    BenchOptions options;
    options.resolution = 48;
    options.repeats = 1;
    return options;
}

TEST(BenchSuite, MeasuresEveryFigureOfASmallScene) {
    const BenchSceneSpec spec{"ladder-1e3", 1000, {}};
    std::vector<std::string> said;
    const BenchRow row = runBenchScene(spec, smallRun(), [&](const std::string& s) { said.push_back(s); });
    EXPECT_EQ(row.scene, "ladder-1e3");
    EXPECT_TRUE(row.generated);
    EXPECT_NEAR(double(row.triangles), 1000.0, 100.0);
    EXPECT_EQ(row.primaryRays, 48u * 48u);
    // The automatic framing fits the bounding box's sphere into the image: the
    // model and its ground cover a good part of it, not all.
    EXPECT_GT(row.primaryHits, row.primaryRays / 6);
    EXPECT_LT(row.primaryHits, row.primaryRays);
    for (double mrays : {row.packetMrays, row.singleMrays, row.shadowMrays, row.diffuseMrays,
                         row.naiveMrays})
        EXPECT_GT(mrays, 0.0);
    EXPECT_TRUE(row.packetWidth == 8 || row.packetWidth == 16);
    EXPECT_GT(row.bvhMegabytes, 0.0);
    EXPECT_GT(row.meshMegabytes, 0.0);
    // 2e9 tests / 1000 triangles is more than the image: every ray is traced.
    EXPECT_EQ(row.naiveRays, row.primaryRays);
    EXPECT_GE(row.naiveAgreement, 0.999);
    EXPECT_GE(row.rasterSeconds, 0.0);
    EXPECT_GT(row.speedupSingle, 0.0);
    EXPECT_FALSE(said.empty());
}

TEST(BenchSuite, TheNaiveSampleFollowsTheBudget) {
    BenchOptions options = smallRun();
    options.naiveBudget = 1e5;  // 100 rays of a 1000-triangle scene
    options.raster = false;
    const BenchRow row = runBenchScene(BenchSceneSpec{"ladder-1e3", 1000, {}}, options);
    EXPECT_NEAR(double(row.naiveRays), 1e5 / double(row.triangles), 1.0);
    EXPECT_LT(row.rasterSeconds, 0.0);  // not measured
    options.naiveBudget = 1.0;  // never fewer than kMinNaiveRays
    EXPECT_EQ(runBenchScene(BenchSceneSpec{"ladder-1e3", 1000, {}}, options).naiveRays, kMinNaiveRays);
}

TEST(BenchFit, RecoversPowerAndLogarithmicLaws) {
    const std::vector<double> n = {1e2, 1e3, 1e4, 1e5, 1e6};
    std::vector<double> linear, logarithmic;
    for (double x : n) {
        linear.push_back(3.0 * x);
        logarithmic.push_back(20.0 + 5.0 * std::log10(x));
    }
    const PowerFit p = fitPowerLaw(n, linear);
    EXPECT_NEAR(p.slope, 1.0, 1e-12);
    EXPECT_NEAR(p.intercept, std::log10(3.0), 1e-12);
    EXPECT_NEAR(p.r2, 1.0, 1e-12);
    EXPECT_EQ(p.points, 5u);
    const LogFit l = fitLogarithmic(n, logarithmic);
    EXPECT_NEAR(l.a, 20.0, 1e-9);
    EXPECT_NEAR(l.b, 5.0, 1e-9);
    EXPECT_EQ(fitPowerLaw({1e3}, {1.0}).points, 1u);  // one point: no fit
    EXPECT_EQ(fitPowerLaw({1e3}, {1.0}).slope, 0.0);
}

std::vector<BenchRow> fakeRows() {
    std::vector<BenchRow> rows;
    for (double n : {1e2, 1e3, 1e4}) {
        BenchRow r;
        r.scene = "ladder-" + std::to_string(int(n));
        r.generated = true;
        r.triangles = size_t(n);
        r.singleMrays = 10.0;
        r.packetMrays = 20.0;
        r.naiveMrays = 1e3 / n;
        rows.push_back(r);
    }
    BenchRow model;
    model.scene = "bunny";
    model.triangles = 69451;
    model.singleMrays = 9.0;
    model.naiveMrays = 0.01;
    rows.push_back(model);
    return rows;
}

TEST(BenchReport, WritesCsvJsonAndSvg) {
    const fs::path dir = test::scratchDir("bench-report");
    const std::vector<BenchRow> rows = fakeRows();
    const BenchFits fits = fitBench(rows);
    EXPECT_NEAR(fits.naive.slope, 1.0, 1e-9);  // naive ns/ray = n ns here
    EXPECT_NEAR(fits.embree.slope, 0.0, 1e-9);
    EXPECT_EQ(fits.naive.points, 3u);           // the model is not fitted

    writeBenchResults(dir / "r.csv", rows, fits, BenchOptions{});
    const std::string csv = test::readFile(dir / "r.csv");
    EXPECT_TRUE(contains(csv, "scene,generated,triangles,")) << csv;
    EXPECT_TRUE(contains(csv, "\nbunny,0,69451,")) << csv;

    writeBenchResults(dir / "r.json", rows, fits, BenchOptions{});
    const std::string json = test::readFile(dir / "r.json");
    EXPECT_TRUE(contains(json, "\"naive_exponent\": 1.0")) << json;
    EXPECT_TRUE(contains(json, "\"scene\": \"ladder-1000\"")) << json;

    writeBenchPlot(dir / "p.svg", rows, fits);
    const std::string svg = test::readFile(dir / "p.svg");
    EXPECT_TRUE(contains(svg, "<svg")) << svg;
    EXPECT_TRUE(contains(svg, "~ n^1.00")) << svg;
    EXPECT_TRUE(contains(svg, "<title>bunny: ")) << svg;

    EXPECT_EQ(test::errorMessage([&] { writeBenchResults(dir / "r.txt", rows, fits, {}); }),
              (dir / "r.txt").string() + ": unknown results format '.txt' (use .csv or .json)");
    EXPECT_TRUE(contains(test::errorMessage([&] { writeBenchPlot(dir / "p.png", rows, fits); }),
                         "give a .svg file"));
    EXPECT_TRUE(contains(
        test::errorMessage([&] { writeBenchResults(dir / "missing/r.csv", rows, fits, {}); }),
        "cannot write"));
    EXPECT_FALSE(fs::exists(dir / "missing"));
    // Nothing but the three results (no temporary files left behind).
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
    EXPECT_EQ(files, 3);
}

}  // namespace
}  // namespace strahl
