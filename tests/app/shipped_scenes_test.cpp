// The scenes the project ships load without a single warning: a new user's
// first command (README command 1 renders scenes/default.json) must print
// nothing alarming about files that came with strahl. Scenes that only
// reference ../shared/data are the shared set's business, not ours, and
// scenes/scale is left to bench_scale (minutes per load).

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "cli_runner.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

// Scenes under scenes/ that read only files of the repository.
std::vector<fs::path> selfContainedScenes() {
    std::vector<fs::path> scenes;
    for (const auto& entry : fs::recursive_directory_iterator(test::sourceDir() / "scenes")) {
        const fs::path& path = entry.path();
        if ((path.extension() != ".json" && path.extension() != ".pbrt") ||
            path.parent_path().filename() == "scale")
            continue;
        if (test::readFile(path).find("shared/data") != std::string::npos) continue;
        scenes.push_back(path);
    }
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

TEST(ShippedScenes, LoadWithoutWarnings) {
    const std::vector<fs::path> scenes = selfContainedScenes();
    ASSERT_FALSE(scenes.empty());
    EXPECT_NE(std::find(scenes.begin(), scenes.end(), test::sourceDir() / "scenes" / "default.json"),
              scenes.end());
    for (const fs::path& scene : scenes) {
        const test::RunResult r = test::runStrahl("info " + scene.string());
        EXPECT_EQ(r.status, 0) << scene << ":\n" << r.err;
        EXPECT_EQ(r.err.find("warning"), std::string::npos) << scene << ":\n" << r.err;
    }
}

TEST(ShippedScenes, TheDefaultSceneRendersWithoutWarnings) {
    // README command 1's render, at a size a test can afford.
    const fs::path dir = test::scratchDir("shipped-default");
    const test::RunResult r =
        test::runStrahl("render " + (test::sourceDir() / "scenes" / "default.json").string() + " -o " +
                        (dir / "default.exr").string() + " -o " + (dir / "default.png").string() +
                        " --width 32 --height 32 --spp 2");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(dir / "default.exr"));
    EXPECT_TRUE(fs::exists(dir / "default.png"));
}

}  // namespace
}  // namespace strahl
