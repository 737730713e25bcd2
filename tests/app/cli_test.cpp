// The strahl executable end to end: exit codes, one clear message per error,
// no output file left behind on failure, and identical images for 1 and 2
// threads.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "cli_runner.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::contains;
using test::readFile;
using test::writeFile;

using test::RunResult;

using test::runStrahl;

// No file at all in `dir` (neither the output nor a temporary).
bool emptyDir(const fs::path& dir) { return fs::is_empty(dir); }

const std::string kQuad = R"({
  "camera": { "eye": [0, 0, 3] },
  "film": { "width": 16, "height": 12 },
  "shapes": [ { "type": "mesh", "positions": [[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]],
                "indices": [0,1,2,0,2,3] } ],
  "lights": [ { "type": "point", "position": [0, 0, 2], "intensity": 3 } ]
})";

TEST(Cli, HelpDocumentsEveryRenderOption) {
    const RunResult r = runStrahl("render --help");
    EXPECT_EQ(r.status, 0);
    for (const char* option : {"--output", "--width", "--height", "--spp", "--threads", "--integrator",
                               "--seed", "--crop", "--quiet", "--aov", "--exr-float", "--packets",
                               "--tile", "--ocio-config", "--display", "--view"})
        EXPECT_TRUE(contains(r.out, option)) << option;
    EXPECT_EQ(runStrahl("--help").status, 0);
    EXPECT_EQ(runStrahl("--version").status, 0);
}

TEST(Cli, RendersExrAndPngAndPrintsASummary) {
    const fs::path dir = test::scratchDir("cli-render");
    writeFile(dir / "quad.json", kQuad);
    const RunResult r = runStrahl("render " + (dir / "quad.json").string() + " -o " + (dir / "a.exr").string() +
                            " -o " + (dir / "a.png").string() + " --aov depth");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "a.exr"));
    EXPECT_TRUE(fs::exists(dir / "a.png"));
    EXPECT_TRUE(contains(r.err, "summary:")) << r.err;
    EXPECT_TRUE(contains(r.err, "Mrays/s")) << r.err;
    EXPECT_TRUE(contains(r.err, "render")) << r.err;
    size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
    EXPECT_EQ(files, 3u) << "no temporary files left";
}

TEST(Cli, QuietPrintsNothingNotEvenMeshWarnings) {
    const fs::path dir = test::scratchDir("cli-quiet");
    // An OBJ whose material library is missing: a warning, not an error.
    writeFile(dir / "tri.obj", "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    writeFile(dir / "tri.json", R"({ "shapes": [ { "type": "mesh", "file": "tri.obj" } ] })");
    const std::string args = (dir / "tri.json").string() + " -o " + (dir / "a.exr").string();
    const RunResult loud = runStrahl("render " + args);
    EXPECT_EQ(loud.status, 0) << loud.err;
    EXPECT_TRUE(contains(loud.err, "strahl: warning:")) << loud.err;
    const RunResult quiet = runStrahl("render -q " + args);
    EXPECT_EQ(quiet.status, 0);
    EXPECT_EQ(quiet.err, "");
}

TEST(Cli, OneAndTwoThreadsGiveIdenticalPixels) {
    const fs::path dir = test::scratchDir("cli-threads");
    const std::string scene = (test::sourceDir() / "scenes/regression/quad_and_box.json").string();
    ASSERT_EQ(runStrahl("render -q " + scene + " --exr-float --spp 3 --threads 1 -o " + (dir / "one.exr").string()).status, 0);
    ASSERT_EQ(runStrahl("render -q " + scene + " --exr-float --spp 3 --threads 2 --tile 8 -o " + (dir / "two.exr").string()).status, 0);
    OIIO::ImageBuf a((dir / "one.exr").string()), b((dir / "two.exr").string());
    const auto cmp = OIIO::ImageBufAlgo::compare(a, b, 0.0f, 0.0f);
    EXPECT_FALSE(cmp.error);
    EXPECT_EQ(cmp.maxerror, 0.0);
}

struct BadInput {
    const char* name;
    std::string sceneText;     // written to bad.json
    std::string extraFile;     // optional companion file name
    std::string extraText;
    std::string args;          // extra command-line arguments
    std::string expectedInMessage;
    int status;
};

// Test names carry the case name; gtest need not dump the struct's bytes.
void PrintTo(const BadInput& input, std::ostream* os) { *os << input.name; }

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, FailsWithOneClearMessageAndNoOutput) {
    const BadInput& p = GetParam();
    const fs::path dir = test::scratchDir(std::string("cli-bad-") + p.name);
    const fs::path outDir = dir / "out";
    fs::create_directories(outDir);
    writeFile(dir / "bad.json", p.sceneText);
    if (!p.extraFile.empty()) writeFile(dir / p.extraFile, p.extraText);
    const std::string output = p.args.find("-o ") != std::string::npos ? "" : " -o " + (outDir / "x.exr").string();
    const RunResult r = runStrahl("render " + (dir / "bad.json").string() + output + " " + p.args);
    EXPECT_EQ(r.status, p.status) << r.err;
    EXPECT_TRUE(contains(r.err, p.expectedInMessage)) << "stderr: " << r.err;
    if (p.status == 1) {
        EXPECT_TRUE(r.err.rfind("strahl: error: ", 0) == 0) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    }
    EXPECT_TRUE(emptyDir(outDir)) << "partial output left behind";
}

std::string meshScene(const std::string& file) {
    return R"({ "shapes": [ { "type": "mesh", "file": ")" + file + R"(" } ] })";
}

const std::string kPlyHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadInput,
    ::testing::Values(
        BadInput{"syntax", "{\n  \"film\": { \"width\": 4,, }\n}", "", "", "", "bad.json:2:", 1},
        BadInput{"unknownkey", R"({ "film": { "widht": 4 } })", "", "", "", "widht", 1},
        BadInput{"wrongtype", R"({ "film": { "width": "big" } })", "", "", "", "/film/width", 1},
        BadInput{"missingmesh", meshScene("nothere.ply"), "", "", "", "nothere.ply", 1},
        BadInput{"truncatedply", meshScene("t.ply"), "t.ply", kPlyHeader + "0 0 0\n1 0 0\n", "", "t.ply", 1},
        BadInput{"nanvertex", meshScene("n.ply"), "n.ply", kPlyHeader + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "", "n.ply", 1},
        BadInput{"badindex", meshScene("i.obj"), "i.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "", "i.obj:4", 1},
        BadInput{"zerowidth", kQuad, "", "", "--width 0", "--width", 2},
        BadInput{"hugeimage", kQuad, "", "", "--width 30000 --height 30000",
                 "more than the limit of 268435456 (2^28) (set by --width 30000, --height 30000)", 1},
        BadInput{"unwritable", kQuad, "", "", "-o /nonexistent-dir/x.exr", "/nonexistent-dir/x.exr", 1},
        BadInput{"extension", kQuad, "", "", "-o out/x.bmpx", "x.bmpx", 1},
        BadInput{"integrator", kQuad, "", "", "--integrator phong", "phong", 1},
        BadInput{"crop", kQuad, "", "", "--crop 0,0,100,100", "--crop", 1}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(Cli, InfoPrintsCountsBoundsAndMemory) {
    const RunResult r = runStrahl("info " + (test::sourceDir() / "scenes/default.json").string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "triangles  2188")) << r.out;
    EXPECT_TRUE(contains(r.out, "bounds"));
    EXPECT_TRUE(contains(r.out, "memory"));
}

TEST(Cli, MissingSceneFileIsAnError) {
    const RunResult r = runStrahl("info /nonexistent/scene.json");
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.err, "/nonexistent/scene.json")) << r.err;
}

}  // namespace
}  // namespace strahl
