// `strahl bench` from the command line: a small run prints the table and
// writes the results and the plot; an unknown model, a missing data folder, an
// impossible size and an output folder that does not exist are one clear
// message and exit status 1, before anything is measured.

#include <gtest/gtest.h>

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

const std::string kSmallBench = "bench --ladder 1e2,1e3 --models none --resolution 32 --repeats 1 --path none -q ";

TEST(BenchCli, ASmallRunPrintsTheTableAndWritesItsFiles) {
    const fs::path dir = test::scratchDir("bench-cli");
    const RunResult r = runStrahl(kSmallBench + "--out " + (dir / "r.csv").string() + " --plot " +
                                  (dir / "cost.svg").string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "ladder-1e2")) << r.out;
    EXPECT_TRUE(contains(r.out, "ladder-1e3")) << r.out;
    EXPECT_TRUE(contains(r.out, "growth over the ladder (2 sizes): naive cost ~ n^")) << r.out;
    EXPECT_TRUE(contains(test::readFile(dir / "r.csv"), "\nladder-1e3,1,"));
    EXPECT_TRUE(contains(test::readFile(dir / "cost.svg"), "<svg"));
    EXPECT_TRUE(r.err.empty()) << r.err;  // -q: no progress lines
}

TEST(BenchCli, BadInputIsOneClearError) {
    const fs::path dir = test::scratchDir("bench-cli-bad");
    struct Case {
        std::string args, message;
    };
    const Case cases[] = {
        {"bench --ladder none --models teapot --data " + dir.string(),
         "strahl: error: bench: unknown model 'teapot' (known: bunny,"},
        {"bench --ladder none --models bunny --data /nonexistent/data",
         "strahl: error: bench: the data folder /nonexistent/data does not exist"},
        {"bench --ladder 1e12 --models none", "strahl: error: bench: a ladder size of 1e12 "
                                              "triangles is outside [100, 100000000]"},
        {"bench --ladder many --models none", "strahl: error: bench: 'many' is not a triangle count"},
        {"bench --ladder none --models none --path none", "strahl: error: bench: nothing to measure"},
        {kSmallBench + "--out " + (dir / "missing/r.csv").string(),
         "strahl: error: --out " + (dir / "missing/r.csv").string() + ": the folder "},
        {kSmallBench + "--plot " + (dir / "cost.png").string(), "give a .svg file"},
    };
    for (const Case& c : cases) {
        const RunResult r = runStrahl(c.args);
        EXPECT_EQ(r.status, 1) << c.args;
        EXPECT_TRUE(contains(r.err, c.message)) << c.args << "\n" << r.err;
        EXPECT_TRUE(r.out.empty()) << c.args << ": measured before failing\n" << r.out;
    }
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(BenchCli, ResolutionOutOfRangeIsAUsageError) {
    const RunResult r = runStrahl("bench --resolution 0");
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(contains(r.err, "--resolution")) << r.err;
}

}  // namespace
}  // namespace strahl
