// `strahl render --algorithm raster` end to end: it writes the same outputs as
// the ray tracer (and nearly the same pixels), prints its own summary, gives
// the same bits for any thread count, and refuses — exit status 1, one line,
// no output file — what it cannot draw: integrators that trace beyond the
// first hit, more than one sample per pixel, implicit surfaces, instances.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "app/cli_runner.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::contains;
using test::RunResult;
using test::runStrahl;

std::string regressionScenePath(const std::string& name) {
    return (test::sourceDir() / "scenes/regression" / (name + ".json")).string();
}

size_t filesIn(const fs::path& dir) {
    return static_cast<size_t>(
        std::distance(fs::directory_iterator(dir), fs::directory_iterator{}));
}

TEST(RasterCli, HelpDocumentsTheAlgorithmOption) {
    const RunResult r = runStrahl("render --help");
    EXPECT_EQ(r.status, 0);
    EXPECT_TRUE(contains(r.out, "--algorithm")) << r.out;
    EXPECT_TRUE(contains(r.out, "raster")) << r.out;
}

TEST(RasterCli, RendersTheOutputsAndAgreesWithTheRayTracer) {
    const fs::path dir = test::scratchDir("raster-cli-render");
    const std::string scene =
        regressionScenePath("quad_and_box") + " --integrator eyelight --spp 1 --exr-float";
    const RunResult r =
        runStrahl("render " + scene + " --algorithm raster --aov depth -o " +
                  (dir / "raster.exr").string() + " -o " + (dir / "raster.png").string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "raster.exr"));
    EXPECT_TRUE(fs::exists(dir / "raster.png"));
    EXPECT_EQ(filesIn(dir), 2u) << "no temporary files left";
    EXPECT_TRUE(contains(r.err, "summary:")) << r.err;
    EXPECT_TRUE(contains(r.err, "raster")) << r.err;
    EXPECT_TRUE(contains(r.err, "pixels covered")) << r.err;
    EXPECT_TRUE(contains(r.err, "rasterized")) << r.err;

    const RunResult traced =
        runStrahl("render -q " + scene + " -o " + (dir / "traced.exr").string());
    ASSERT_EQ(traced.status, 0) << traced.err;
    OIIO::ImageBuf a((dir / "raster.exr").string()), b((dir / "traced.exr").string());
    EXPECT_EQ(a.spec().get_string_attribute("strahl:algorithm"), "raster");
    EXPECT_EQ(b.spec().get_string_attribute("strahl:algorithm"), "raytrace");
    // Compare the beauty only: the raster image also has the depth AOV.
    OIIO::ImageBuf rgbA = OIIO::ImageBufAlgo::channels(a, 3, {0, 1, 2});
    OIIO::ImageBuf rgbB = OIIO::ImageBufAlgo::channels(b, 3, {0, 1, 2});
    const auto cmp = OIIO::ImageBufAlgo::compare(rgbA, rgbB, 1e-4f, 1e-4f);
    ASSERT_FALSE(cmp.error);
    const double pixels = double(a.spec().width) * a.spec().height;
    // Only pixel centres on or within rounding of an edge may differ (see
    // raster_agreement_test.cpp and docs/rasterizer.md).
    EXPECT_LE(double(cmp.nfail), 0.001 * pixels) << cmp.nfail << " pixels differ";
}

TEST(RasterCli, OneAndTwoThreadsGiveIdenticalPixels) {
    const fs::path dir = test::scratchDir("raster-cli-threads");
    const std::string scene =
        regressionScenePath("cornell_primid") + " -q --algorithm raster --exr-float";
    ASSERT_EQ(runStrahl("render " + scene + " --threads 1 -o " + (dir / "one.exr").string()).status,
              0);
    ASSERT_EQ(
        runStrahl("render " + scene + " --threads 2 --tile 8 -o " + (dir / "two.exr").string())
            .status,
        0);
    OIIO::ImageBuf a((dir / "one.exr").string()), b((dir / "two.exr").string());
    const auto cmp = OIIO::ImageBufAlgo::compare(a, b, 0.0f, 0.0f);
    EXPECT_FALSE(cmp.error);
    EXPECT_EQ(cmp.maxerror, 0.0);
}

struct Refusal {
    const char* name;
    std::string args;  // after "render"
    std::string expectedInMessage;
};

void PrintTo(const Refusal& refusal, std::ostream* os) {
    *os << refusal.name;
}

class RasterCliRefuses : public ::testing::TestWithParam<Refusal> {};

TEST_P(RasterCliRefuses, WithOneLineAndNoOutput) {
    const Refusal& p = GetParam();
    const fs::path dir = test::scratchDir(std::string("raster-cli-refuses-") + p.name);
    const RunResult r = runStrahl("render " + p.args + " --algorithm raster -o " +
                                  (dir / "x.exr").string() + " -o " + (dir / "x.png").string());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(r.err.rfind("strahl: error: ", 0) == 0) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_TRUE(contains(r.err, p.expectedInMessage)) << r.err;
    EXPECT_EQ(filesIn(dir), 0u) << "output left behind";
}

INSTANTIATE_TEST_SUITE_P(
    Cases, RasterCliRefuses,
    ::testing::Values(
        // The scene's own integrator, direct, traces shadow rays.
        Refusal{"direct", regressionScenePath("cornell_direct") + " --spp 1",
                "cannot shade integrator 'direct'"},
        // quad_and_box asks for 4 spp; so does the command line here.
        Refusal{"scenespp", regressionScenePath("quad_and_box") + " --integrator normal",
                "spp must be 1, got 4"},
        Refusal{"spp", regressionScenePath("cornell_primid") + " --spp 2", "spp must be 1, got 2"},
        Refusal{"implicit", regressionScenePath("implicit_direct") + " --integrator eyelight",
                "triangle meshes only"},
        Refusal{"instances", regressionScenePath("instances") + " --integrator eyelight",
                "top-level meshes only"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(RasterCli, UnknownAlgorithmIsAUsageError) {
    const RunResult r =
        runStrahl("render " + regressionScenePath("cornell_primid") + " --algorithm zbuffer");
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(contains(r.err, "--algorithm")) << r.err;
}

}  // namespace
}  // namespace strahl
