// Image files that exist but are not images, from the command line: an
// environment map or a material texture that OpenImageIO cannot read makes
// `strahl render` exit with status 1 and one error line naming the light or
// material and the file, before anything is rendered, and no output file is
// written.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "cli_runner.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::contains;
using test::RunResult;
using test::runStrahl;

const std::string kQuadMembers = R"(
  "camera": { "eye": [0, 0, 3] },
  "film": { "width": 16, "height": 12 },
  "render": { "integrator": "path", "spp": 1 },
  "shapes": [ { "type": "mesh", "material": "m",
                "positions": [[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]], "indices": [0,1,2,0,2,3],
                "uvs": [[0,0],[1,0],[1,1],[0,1]] } ])";

// Renders `dir`/scene.json (kQuadMembers plus `sections`) to an EXR and a PNG in
// `dir`/out, with `file` (a text file) next to the scene.
RunResult renderWithFakeImage(const fs::path& dir, const std::string& file,
                              const std::string& sections) {
    test::writeFile(dir / file, "this is a text file, not an image\n");
    test::writeFile(dir / "scene.json", "{" + sections + "," + kQuadMembers + "}");
    fs::create_directories(dir / "out");
    return runStrahl("render " + (dir / "scene.json").string() + " -o " +
                     (dir / "out/x.exr").string() + " -o " + (dir / "out/x.png").string());
}

void expectOneErrorLine(const RunResult& r, const std::string& part) {
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(r.err.rfind("strahl: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_TRUE(contains(r.err, part)) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(ShadingCli, EnvironmentThatIsNotAnImageIsOneErrorAndNoOutput) {
    const fs::path dir = test::scratchDir("shading-cli-environment");
    const RunResult r = renderWithFakeImage(
        dir, "sky.hdr",
        R"("materials": [ { "name": "m" } ],
           "lights": [ { "type": "environment", "file": "sky.hdr" } ])");
    expectOneErrorLine(r, "scene.json: /lights/0: " + (dir / "sky.hdr").string() +
                              ": cannot read the environment image: ");
    EXPECT_TRUE(fs::is_empty(dir / "out")) << "output written despite the error";
}

TEST(ShadingCli, TextureThatIsNotAnImageIsOneErrorAndNoOutput) {
    const fs::path dir = test::scratchDir("shading-cli-texture");
    const RunResult r = renderWithFakeImage(
        dir, "wood.png", R"("materials": [ { "name": "m", "color": { "texture": "wood.png" } } ])");
    expectOneErrorLine(r, "scene.json: /materials/0: " + (dir / "wood.png").string() +
                              ": cannot read the texture: ");
    EXPECT_TRUE(fs::is_empty(dir / "out")) << "output written despite the error";
}

}  // namespace
}  // namespace strahl
