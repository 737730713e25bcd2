// The BVH and memory options of `strahl render` and `strahl info`
// (docs/memory.md): every quality and compact mode renders, a memory limit
// the scene cannot fit stops with one clear message and no image, a bad size
// is a usage error, and both commands report peak resident memory.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "app/app_test_helpers.h"
#include "app/cli_runner.h"
#include "strahl/scene/scene_builder.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::RunResult;
using test::runStrahl;
using testing::HasSubstr;

using test::kDefaultScene;
const std::string kSmallRender = " --width 32 --height 24 --spp 1";

TEST(MemoryCli, EveryBvhQualityAndCompactModeRenders) {
    const fs::path dir = test::scratchDir("memory-cli-quality");
    for (const char* flags : {"--bvh-quality low", "--bvh-quality medium", "--bvh-quality high",
                              "--compact", "--no-compact", "--bvh-quality low --no-compact"}) {
        const fs::path out = dir / "a.exr";
        fs::remove(out);
        const RunResult r = runStrahl("render " + kDefaultScene + kSmallRender + " " + flags + " -o " + out.string());
        EXPECT_EQ(r.status, 0) << flags << ": " << r.err;
        EXPECT_TRUE(fs::exists(out)) << flags;
        EXPECT_THAT(r.err, HasSubstr("memory: shapes ")) << flags;
        EXPECT_THAT(r.err, HasSubstr(", peak resident ")) << flags;
    }
}

TEST(MemoryCli, ALimitTheSceneCannotFitStopsCleanlyWithoutAnImage) {
    const fs::path dir = test::scratchDir("memory-cli-limit");
    const fs::path out = dir / "a.exr";
    // 1 MiB: less than the process itself holds once the scene is loaded.
    const RunResult r = runStrahl("render " + kDefaultScene + kSmallRender +
                                  " -q --memory-limit 1M -o " + out.string());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr("default.json: loading the scene took "));
    EXPECT_THAT(r.err, HasSubstr("more than the memory limit of 1.00 MiB"));
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out));
    // A generous limit changes nothing.
    const RunResult ok = runStrahl("render " + kDefaultScene + kSmallRender + " --memory-limit 16G -o " + out.string());
    EXPECT_EQ(ok.status, 0) << ok.err;
    EXPECT_TRUE(fs::exists(out));
}

TEST(MemoryCli, BadSizesAndQualitiesAreUsageErrors) {
    for (const char* flags : {"--memory-limit 8X", "--memory-limit 0", "--memory-limit lots",
                              "--bvh-quality best"}) {
        const RunResult r =
            runStrahl("render " + kDefaultScene + kSmallRender + " " + flags + " -o /tmp/x.exr");
        EXPECT_EQ(r.status, 2) << flags << ": " << r.err;
        EXPECT_THAT(r.err, HasSubstr("strahl: error: ")) << flags;
    }
}

TEST(MemoryCli, InfoReportsBvhMemoryPerTriangleAndPeakResident) {
    const RunResult r = runStrahl("info " + kDefaultScene + " --bvh-quality low");
    EXPECT_EQ(r.status, 0) << r.err;
    // The default scene is small: not compact unless asked for (useCompactBvh).
    EXPECT_THAT(r.out, HasSubstr("(low, not compact (auto), "));
    // Each flag and the layout it leads to.
    for (const auto& [flag, layout] :
         {std::pair{" --no-compact", "(medium, not compact, "},
          std::pair{" --compact", "(medium, compact, "},
          std::pair{" --memory-limit 16G", "(medium, compact (auto), "}}) {
        const RunResult run = runStrahl("info " + kDefaultScene + flag);
        EXPECT_EQ(run.status, 0) << flag << ": " << run.err;
        EXPECT_THAT(run.out, HasSubstr(layout)) << flag;
    }
    EXPECT_THAT(r.out, HasSubstr(" per stored triangle with its mesh data), peak resident "));
}

TEST(MemoryCli, CompactBvhByDefaultOnlyAboveTheThresholdOrWithAMemoryLimit) {
    BuildOptions automatic;
    EXPECT_FALSE(useCompactBvh(automatic, 0));
    EXPECT_FALSE(useCompactBvh(automatic, kCompactBvhAboveTriangles));
    EXPECT_TRUE(useCompactBvh(automatic, kCompactBvhAboveTriangles + 1));
    BuildOptions limited;
    limited.memoryLimitBytes = size_t(1) << 33;
    EXPECT_TRUE(useCompactBvh(limited, 12));
    BuildOptions full;
    full.compact = false;
    full.memoryLimitBytes = limited.memoryLimitBytes;
    EXPECT_FALSE(useCompactBvh(full, kCompactBvhAboveTriangles * 4));
    BuildOptions compact;
    compact.compact = true;
    EXPECT_TRUE(useCompactBvh(compact, 12));
}

}  // namespace
}  // namespace strahl
