// The strahl executable on scenes with implicit shapes: bad surfaces fail with
// exit status 1, one message naming the scene file and the shape's JSON
// pointer, and no output file; `--accel naive` renders the same pixels as
// Embree; `--accel bogus` is a usage error; `strahl info` lists implicit
// shapes with their cell counts.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "strahl/geometry/implicit_shape.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
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

// A small scene: a floor triangle pair, then `implicitShapes` (JSON objects,
// comma-separated), lit by a point light.
std::string scene(const std::string& implicitShapes) {
    return R"({
  "camera": { "eye": [0, 2, 5], "look_at": [0, 0.5, 0], "fov": 40 },
  "film": { "width": 24, "height": 16 },
  "render": { "integrator": "direct" },
  "shapes": [
    { "type": "mesh", "name": "floor",
      "positions": [[-5, 0, -5], [5, 0, -5], [5, 0, 5], [-5, 0, 5]], "indices": [0, 2, 1, 0, 3, 2] },
    )" + implicitShapes +
           R"(
  ],
  "lights": [ { "type": "point", "position": [2, 4, 3], "intensity": 20 } ]
})";
}

const std::string kTorus =
    R"({ "type": "implicit", "name": "torus", "surface": { "type": "torus" }, "cells": 12,
         "transform": [ { "rotate": { "axis": [1, 0, 0], "angle": -70 } }, { "translate": [-0.8, 0.6, 0] } ] })";
const std::string kFormula =
    R"({ "type": "implicit", "name": "ball",
         "surface": { "type": "formula", "f": "x^2 + y^2 + z^2 - r^2", "parameters": { "r": 0.5 } },
         "box": [[-1, -1, -1], [1, 1, 1]], "cells": 6, "transform": [ { "translate": [0.8, 0.5, 0] } ] })";

struct BadScene {
    const char* name;
    std::string shape;  // the implicit shape, /shapes/1 of the scene
    std::string expected;  // after "<scene path>: " in the message
};

void PrintTo(const BadScene& s, std::ostream* os) { *os << s.name; }

class ImplicitCliBadScene : public ::testing::TestWithParam<BadScene> {};

TEST_P(ImplicitCliBadScene, ExitsWithOneMessageNamingFileAndShapeAndWritesNothing) {
    const BadScene& p = GetParam();
    const fs::path dir = test::scratchDir(std::string("implicit-cli-") + p.name);
    const fs::path outDir = dir / "out";
    fs::create_directories(outDir);
    const fs::path file = dir / "bad.json";
    writeFile(file, scene(p.shape));
    const RunResult r = runStrahl("render " + file.string() + " -o " + (outDir / "x.exr").string() +
                            " -o " + (outDir / "x.png").string());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(r.err, "strahl: error: " + file.string() + ": " + p.expected + "\n");
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(fs::is_empty(outDir)) << "output left behind";

    // `info` reports the same problem the same way.
    const RunResult info = runStrahl("info " + file.string());
    EXPECT_EQ(info.status, 1);
    EXPECT_EQ(info.err, r.err);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ImplicitCliBadScene,
    ::testing::Values(
        BadScene{"syntax",
                 R"({ "type": "implicit", "surface": { "type": "formula", "f": "x^2 + * y" },
                      "box": [[-1, -1, -1], [1, 1, 1]] })",
                 "/shapes/1/surface/f: column 7: expected an operand (a number, a name or '('), "
                 "found '*'"},
        BadScene{"unknownvariable",
                 R"({ "type": "implicit", "surface": { "type": "formula", "f": "x^2 + y^2 + w^2 - 1" },
                      "box": [[-1, -1, -1], [1, 1, 1]] })",
                 "/shapes/1/surface/f: column 13: unknown name 'w'; variables: x, y, z; "
                 "parameters: none; constants: e, pi; functions: abs, atan, cos, exp, log, max, "
                 "min, pow, sin, sqr, sqrt, tan"},
        BadScene{"nobox",
                 R"({ "type": "implicit", "surface": { "type": "formula", "f": "x + y" } })",
                 "/shapes/1: the surface formula \"x + y\" has no finite bounds of its own: give "
                 "the shape a \"box\""},
        BadScene{"negativeradius",
                 R"({ "type": "implicit", "surface": { "type": "torus", "minor_radius": -1 } })",
                 "/shapes/1/surface: parameter 'minor_radius' must be > 0 (got -1)"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(ImplicitCli, BuildErrorNamesTheShapeAndWritesNothing) {
    // Found only when the shape is built (after parsing): the box misses the
    // sphere. The builder names the scene by its file name.
    const fs::path dir = test::scratchDir("implicit-cli-build");
    const fs::path outDir = dir / "out";
    fs::create_directories(outDir);
    writeFile(dir / "bad.json",
              scene(R"({ "type": "implicit", "surface": { "type": "sphere" },
                         "box": [[5, 5, 5], [6, 6, 6]] })"));
    const RunResult r =
        runStrahl("render " + (dir / "bad.json").string() + " -o " + (outDir / "x.exr").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err,
              "strahl: error: bad.json: /shapes/1: the surface sphere r=1 has no point inside the "
              "shape's box (they do not overlap)\n");
    EXPECT_TRUE(fs::is_empty(outDir));
}

TEST(ImplicitCli, NaiveAccelRendersTheSamePixelsAsEmbree) {
    const fs::path dir = test::scratchDir("implicit-cli-naive");
    const fs::path file = dir / "scene.json";
    writeFile(file, scene(kTorus + ",\n" + kFormula));
    const std::string common = "render -q " + file.string() + " --exr-float --threads 2 -o ";
    const RunResult naive = runStrahl(common + (dir / "naive.exr").string() + " --accel naive");
    ASSERT_EQ(naive.status, 0) << naive.err;
    EXPECT_EQ(naive.err, "");
    const RunResult embree = runStrahl(common + (dir / "embree.exr").string() + " --accel embree");
    ASSERT_EQ(embree.status, 0) << embree.err;
    OIIO::ImageBuf a((dir / "naive.exr").string()), b((dir / "embree.exr").string());
    // The implicit shapes run the same code in both tracers; the floor mesh
    // goes through Embree's triangle kernel or the naive watertight test,
    // which agree to float rounding (~1e-7), not bit for bit. The in-process
    // test tests/render/implicit_agreement_test.cpp checks the exact part.
    const auto cmp = OIIO::ImageBufAlgo::compare(a, b, 1e-5f, 1e-5f);
    ASSERT_EQ(a.spec().width, 24);
    ASSERT_EQ(b.spec().width, 24);
    EXPECT_EQ(a.spec().get_string_attribute("strahl:accel"), "naive");
    EXPECT_EQ(b.spec().get_string_attribute("strahl:accel"), "embree");
    EXPECT_EQ(cmp.nfail, 0u) << "max error " << cmp.maxerror << " at (" << cmp.maxx << ", "
                             << cmp.maxy << ")";
    EXPECT_LE(cmp.maxerror, 1e-5);
    // The image is not trivially black: the shapes are lit.
    const auto stats = OIIO::ImageBufAlgo::computePixelStats(a);
    ASSERT_FALSE(stats.max.empty());
    EXPECT_GT(stats.max[0], 0.01f);
}

TEST(ImplicitCli, UnknownAccelIsAUsageError) {
    const fs::path dir = test::scratchDir("implicit-cli-accel");
    const fs::path outDir = dir / "out";
    fs::create_directories(outDir);
    writeFile(dir / "scene.json", scene(kTorus));
    const RunResult r = runStrahl("render " + (dir / "scene.json").string() + " --accel bogus -o " +
                            (outDir / "x.exr").string());
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(contains(r.err, "--accel")) << r.err;
    EXPECT_TRUE(contains(r.err, "bogus")) << r.err;
    EXPECT_TRUE(fs::is_empty(outDir));
}

TEST(ImplicitCli, InfoListsImplicitShapesWithTheirCellCounts) {
    const fs::path dir = test::scratchDir("implicit-cli-info");
    const fs::path file = dir / "scene.json";
    writeFile(file, scene(kTorus + ",\n" + kFormula));
    const RunResult r = runStrahl("info " + file.string());
    ASSERT_EQ(r.status, 0) << r.err;

    // The counts the builder makes of the same scene.
    const World world = buildWorld(parseSceneFile(file), BuildOptions{});
    ASSERT_EQ(world.shapes.size(), 3u);
    const uint32_t torusCells = world.shapes[1].user->primitiveCount();
    const uint32_t ballCells = world.shapes[2].user->primitiveCount();
    ASSERT_GT(torusCells, 0u);
    ASSERT_GT(ballCells, 0u);

    auto lineWith = [&](const std::string& part) {
        std::istringstream lines(r.out);
        for (std::string line; std::getline(lines, line);)
            if (contains(line, part)) return line;
        return std::string();
    };
    const std::string torus = lineWith("[1] torus");
    EXPECT_TRUE(contains(torus, " " + std::to_string(torusCells) + " cells")) << r.out;
    EXPECT_TRUE(contains(torus, "implicit torus R=1 r=0.25")) << r.out;
    const std::string ball = lineWith("[2] ball");
    EXPECT_TRUE(contains(ball, " " + std::to_string(ballCells) + " cells")) << r.out;
    EXPECT_TRUE(contains(ball, "implicit formula \"x^2 + y^2 + z^2 - r^2\"")) << r.out;
    EXPECT_TRUE(contains(lineWith("[0] floor"), "2 triangles")) << r.out;
    EXPECT_TRUE(contains(r.out, "user prims " + std::to_string(torusCells + ballCells))) << r.out;
    EXPECT_TRUE(contains(r.out, "triangles  2\n")) << r.out;
}

}  // namespace
}  // namespace strahl
