// Instancing from the command line: `strahl info` reports groups, how often
// each is placed and the stored and instanced triangle counts; `strahl render`
// renders an instanced scene with either accelerator; a cyclic group is one
// clear error with exit status 1 and no output file.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_runner.h"
#include "sanitizers/sanitized.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::contains;
using test::RunResult;
using test::runStrahl;

const fs::path kInstances = test::sourceDir() / "scenes/regression/instances.json";

TEST(InstanceCli, InfoListsGroupsAndPlacements) {
    const RunResult r = runStrahl("info " + kInstances.string());
    ASSERT_EQ(r.status, 0) << r.err;
    // Nested: "row" (3 charms) placed twice, plus one charm: 7 placements of
    // the one group with shapes of its own.
    EXPECT_TRUE(contains(r.out, "groups     1, 7 instances\n")) << r.out;
    EXPECT_TRUE(contains(r.out, "group 'charm', placed 7 times\n")) << r.out;
    EXPECT_TRUE(contains(r.out, "[0] pyramid")) << r.out;
    EXPECT_TRUE(contains(r.out, "implicit torus R=0.3 r=0.09")) << r.out;
    // Floor 2 + pyramid 6 stored; 2 + 7 * 6 rendered.
    EXPECT_TRUE(contains(r.out, "triangles  8 stored, 44 instanced\n")) << r.out;
}

TEST(InstanceCli, RendersWithBothAccelerators) {
    const fs::path dir = test::scratchDir("instance-cli-render");
    for (const char* accel : {"embree", "naive"}) {
        const fs::path out = dir / (std::string(accel) + ".exr");
        // Fewer pixels under the sanitizers, where the naive tracer is slow.
        const std::string size = test::fullOrSanitized<std::string>(" --width 48 --height 36",
                                                                    " --width 16 --height 12");
        const RunResult r = runStrahl("render " + kInstances.string() + " --accel " + accel + size +
                                      " --quiet -o " + out.string());
        EXPECT_EQ(r.status, 0) << accel << ": " << r.err;
        EXPECT_TRUE(fs::exists(out)) << accel;
    }
}

TEST(InstanceCli, ACyclicGroupIsOneClearError) {
    const fs::path dir = test::scratchDir("instance-cli-cycle");
    const fs::path outDir = dir / "out";
    fs::create_directories(outDir);
    test::writeFile(dir / "scene.json", R"({
      "groups": [ { "name": "a", "shapes": [ { "type": "instance", "group": "b" } ] },
                  { "name": "b", "shapes": [ { "type": "instance", "group": "a" } ] } ],
      "shapes": [ { "type": "instance", "group": "a" } ] })");
    const RunResult r =
        runStrahl("render " + (dir / "scene.json").string() + " -o " + (outDir / "x.exr").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.err, "scene.json: /groups/0: group 'a' places itself (a -> b -> a)"))
        << r.err;
    EXPECT_TRUE(fs::is_empty(outDir));
}

}  // namespace
}  // namespace strahl
