// `strahl render --distributed` under mpirun on this machine (loopback /
// shared memory): the gathered image equals a single-process render bit for
// bit, and every failure — too few ranks, a worker's error, a worker started
// with other settings, a rank killed mid-render — ends the job with a message
// on rank 0, a non-zero status, no hang and no output file.
//
// Each job runs under `timeout` so that a hang fails the test (status 124)
// instead of stalling ctest. mpirun needs --allow-run-as-root when CI runs as
// root (set through its environment variables here, not globally) and
// --oversubscribe for more ranks than cores.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/exr_file.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

constexpr int kTimedOut = 124;  // timeout(1)'s status for a command it had to kill

// A small path-traced scene with glass, metals, implicit and parametric shapes;
// 50 x 37 is a multiple of no tile size used here, so edge tiles are partial.
const std::string kScene = (test::sourceDir() / "scenes/statistical/glossy_room.json").string();
const std::string kImage =
    " --width 50 --height 37 --exr-float -q --aov normal --aov depth --aov albedo "
    "--aov position --aov objectid --aov variance";
const std::string kSamples = " --spp 4";

struct JobResult {
    int status = -1;
    std::string err;
};

// Runs a shell command, keeping its exit status and stderr.
JobResult runShell(const std::string& command) {
    const fs::path err = fs::temp_directory_path() / ("strahl-mpi-stderr-" + std::to_string(getpid()));
    const int raw = std::system((command + " >/dev/null 2>" + err.string()).c_str());
    JobResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.err = test::readFile(err);
    fs::remove(err);
    return r;
}

// `launch` follows mpirun's own options: "-np 3 <strahl> render ..." or an
// MPMD line with ':'; `env` (VAR=value ...) is set for mpirun and its ranks.
JobResult mpirun(const std::string& launch, const std::string& env = "") {
    return runShell("env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + env +
                    " timeout 90 " + STRAHL_MPIEXEC + " --oversubscribe --bind-to none " + launch);
}

// "<strahl> render SCENE <image flags> <flags> -o OUT --distributed"
// (--spp 4 unless `flags` sets it.)
std::string strahlRender(const fs::path& out, const std::string& flags,
                         const std::string& scene = kScene) {
    const std::string samples = test::contains(flags, "--spp") ? "" : kSamples;
    return std::string(STRAHL_BINARY) + " render " + scene + kImage + samples + flags + " -o " +
           out.string() + " --distributed";
}

using test::ExrFile;
using test::expectIdentical;
using test::readExr;

ExrFile renderLocally(const fs::path& dir, const std::string& flags = "") {
    const fs::path out = dir / "local.exr";
    const std::string command = std::string(STRAHL_BINARY) + " render " + kScene + kImage +
                                (test::contains(flags, "--spp") ? flags : kSamples + flags) + " --threads 2 -o " +
                                out.string();
    const JobResult r = runShell(command);
    EXPECT_EQ(r.status, 0) << r.err;
    return readExr(out);
}

// Nothing at all in `dir`: no image, no temporary file.
void expectEmpty(const fs::path& dir) {
    for (const auto& entry : fs::directory_iterator(dir))
        ADD_FAILURE() << "left behind: " << entry.path();
}

TEST(Distributed, ThreeRanksGiveTheSingleProcessImageBitForBit) {
    const fs::path dir = test::scratchDir("distributed-identical");
    const ExrFile local = renderLocally(dir);
    ASSERT_EQ(local.channels.size(), 3u + 3 + 1 + 3 + 3 + 1 + 3);  // beauty and the six AOVs

    // 2 workers with 2 render threads each; 8-pixel tiles: 35 tiles, the last
    // column 2 pixels wide and the last row 5 high.
    const fs::path out = dir / "mpi3.exr";
    JobResult r = mpirun("-np 3 " + strahlRender(out, " --threads 2 --tile 8"));
    ASSERT_EQ(r.status, 0) << r.err;
    const ExrFile three = readExr(out);
    expectIdentical(local, three, "mpirun -np 3, 8-pixel tiles");
    EXPECT_EQ(three.partial, "0");
    EXPECT_EQ(three.samples, "4");

    // One worker, one thread, 16-pixel tiles.
    const fs::path out2 = dir / "mpi2.exr";
    r = mpirun("-np 2 " + strahlRender(out2, " --threads 1 --tile 16"));
    ASSERT_EQ(r.status, 0) << r.err;
    expectIdentical(local, readExr(out2), "mpirun -np 2, 16-pixel tiles");
}

TEST(Distributed, RankZeroDenoisesTheGatheredImage) {
    // The film's sample halves travel with the tiles, and rank 0 denoises:
    // the image of a local render with --denoise, bit for bit.
    const fs::path dir = test::scratchDir("distributed-denoise");
    const fs::path local = dir / "local.exr", out = dir / "mpi.exr";
    const JobResult l = runShell(std::string(STRAHL_BINARY) + " render " + kScene + kImage +
                                 kSamples + " --denoise --threads 2 -o " + local.string());
    ASSERT_EQ(l.status, 0) << l.err;
    const JobResult r = mpirun("-np 3 " + strahlRender(out, " --denoise --threads 1 --tile 8"));
    ASSERT_EQ(r.status, 0) << r.err;
    expectIdentical(readExr(local), readExr(out), "mpirun -np 3 --denoise");
}

TEST(Distributed, AdaptiveSamplingGivesTheSingleProcessImageBitForBit) {
    // Rank 0 takes the decisions between rounds on the gathered film and
    // sends the running tiles' pixel state out again: the local image, the
    // per-pixel sample counts (the `samples` AOV) included. 64 spp from 4:
    // 19 rounds (decisions at 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16,
    // 18, 20, ...), and a threshold at which some pixels stop early and
    // others run to the end.
    const fs::path dir = test::scratchDir("distributed-adaptive");
    const std::string adaptive = " --spp 64 --adaptive-threshold 0.08 --adaptive-min-samples 4";
    const ExrFile local = renderLocally(dir, adaptive);
    const auto samples = std::find(local.channels.begin(), local.channels.end(), "samples.X");
    ASSERT_NE(samples, local.channels.end()) << "no samples AOV";
    const size_t channel = static_cast<size_t>(samples - local.channels.begin());
    const size_t pixels = local.pixels.size() / local.channels.size();
    float fewest = 1e9f, most = 0.0f;
    for (size_t p = 0; p < pixels; ++p) {
        const float n = local.pixels[p * local.channels.size() + channel];
        fewest = std::min(fewest, n);
        most = std::max(most, n);
    }
    EXPECT_LT(fewest, 64.0f) << "no pixel stopped early: the test would not exercise the rounds";
    EXPECT_EQ(most, 64.0f) << "every pixel stopped early";

    const fs::path out = dir / "mpi3.exr";
    JobResult r = mpirun("-np 3 " + strahlRender(out, adaptive + " --threads 1 --tile 8"));
    ASSERT_EQ(r.status, 0) << r.err;
    expectIdentical(local, readExr(out), "mpirun -np 3 adaptive, 8-pixel tiles");
    const fs::path out2 = dir / "mpi2.exr";
    r = mpirun("-np 2 " + strahlRender(out2, adaptive + " --denoise --threads 2 --tile 16"));
    ASSERT_EQ(r.status, 0) << r.err;
    const fs::path localDenoised = dir / "local-denoised.exr";
    const JobResult l = runShell(std::string(STRAHL_BINARY) + " render " + kScene + kImage +
                                 adaptive + " --denoise --threads 2 -o " + localDenoised.string());
    ASSERT_EQ(l.status, 0) << l.err;
    expectIdentical(readExr(localDenoised), readExr(out2), "mpirun -np 2 adaptive --denoise");
}

TEST(Distributed, OneRankIsAnError) {
    const fs::path dir = test::scratchDir("distributed-one-rank");
    const JobResult r = mpirun("-np 1 " + strahlRender(dir / "a.exr", ""));
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(test::contains(r.err, "strahl: error: --distributed needs at least 2 MPI "
                                      "processes (rank 0 schedules, the others render), got 1"))
        << r.err;
    expectEmpty(dir);
}

TEST(Distributed, AWorkersErrorIsReportedByRankZero) {
    const fs::path dir = test::scratchDir("distributed-worker-error");
    const fs::path missing = dir / "missing.json";
    // MPMD: ranks 0 and 1 get the scene, rank 2 a file that does not exist.
    const JobResult r = mpirun("-np 2 " + strahlRender(dir / "a.exr", "") + " : -np 1 " +
                         strahlRender(dir / "a.exr", "", missing.string()));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(test::contains(r.err, "strahl: rank 2: " + missing.string() + ": cannot open"))
        << r.err;
    expectEmpty(dir);
}

TEST(Distributed, AWorkerWithOtherSettingsIsAnError) {
    const fs::path dir = test::scratchDir("distributed-other-settings");
    const JobResult r = mpirun("-np 2 " + strahlRender(dir / "a.exr", "") + " : -np 1 " +
                         strahlRender(dir / "a.exr", " --seed 99"));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(test::contains(r.err, "strahl: error: rank 2 was started with other settings "
                                      "than rank 0"))
        << r.err;
    expectEmpty(dir);
}

TEST(Distributed, ARankKilledMidRenderEndsTheJobWithoutOutput) {
    for (const char* fault : {"1:3", "2:0", "0:5"}) {  // a worker, another, the scheduler
        const fs::path dir = test::scratchDir("distributed-killed");
        const JobResult r = mpirun("-x STRAHL_DISTRIBUTED_FAULT -np 3 " +
                                 strahlRender(dir / "a.exr", " --threads 1 --tile 8"),
                             std::string("STRAHL_DISTRIBUTED_FAULT=") + fault);
        EXPECT_NE(r.status, 0) << fault << ": " << r.err;
        EXPECT_NE(r.status, kTimedOut) << fault << ": the job hung";
        EXPECT_TRUE(test::contains(r.err, "STRAHL_DISTRIBUTED_FAULT: killing this rank"))
            << fault << ": " << r.err;
        expectEmpty(dir);
    }
}

TEST(Distributed, UnsupportedCombinationsAreErrors) {
    const fs::path dir = test::scratchDir("distributed-unsupported");
    for (const std::string& flags : {" --checkpoint " + (dir / "c.ckpt").string(),
                                    std::string(" --time-limit 5")}) {
        const JobResult r = mpirun("-np 2 " + strahlRender(dir / "a.exr", flags));
        EXPECT_EQ(r.status, 1) << flags << ": " << r.err;
        EXPECT_TRUE(test::contains(r.err, "strahl: error: --distributed renders one image in one "
                                          "go, with the ray tracer"))
            << flags << ": " << r.err;
        expectEmpty(dir);
    }
}

}  // namespace
}  // namespace strahl
