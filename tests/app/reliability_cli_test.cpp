// Unattended rendering through the CLI: bit-identical images for any thread
// count and tile size; SIGINT/SIGTERM write a partial image and exit 128 + the
// signal; a checkpointed, interrupted and resumed render equals the
// uninterrupted one bit for bit; --time-limit stops at a whole sample pass.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "app/app_test_helpers.h"
#include "app/cli_runner.h"
#include "app/exr_file.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::runStrahl;

// A path-traced scene with every geometry kind and glass (long, varied paths),
// small enough for tests, rendered to float EXR with AOVs.
using test::kGlossyRoom;
const std::string kReliabilityFlags =
    " --width 48 --height 36 --exr-float -q --aov variance --aov albedo";

using test::ExrFile;
using test::expectIdentical;
using test::readExr;

ExrFile renderWith(const fs::path& dir, const std::string& name, const std::string& flags) {
    const fs::path out = dir / (name + ".exr");
    const test::RunResult r = runStrahl("render " + kGlossyRoom + kReliabilityFlags + " -o " + out.string() + flags);
    EXPECT_EQ(r.status, 0) << r.err;
    return readExr(out);
}

TEST(Determinism, SameImageForAnyThreadCountAndTileSize) {
    const fs::path dir = test::scratchDir("determinism");
    const ExrFile reference = renderWith(dir, "t1", " --spp 8 --threads 1 --tile 32");
    expectIdentical(reference, renderWith(dir, "t2", " --spp 8 --threads 2 --tile 32"), "2 threads");
    expectIdentical(reference, renderWith(dir, "t2x8", " --spp 8 --threads 2 --tile 8"),
                    "2 threads, 8-pixel tiles");
    expectIdentical(reference, renderWith(dir, "t1x12", " --spp 8 --threads 1 --tile 12"),
                    "1 thread, 12-pixel tiles");
    expectIdentical(reference, renderWith(dir, "single", " --spp 8 --packets single"),
                    "single rays");
    EXPECT_EQ(reference.partial, "0");
    EXPECT_EQ(reference.samples, "8");
}

// Starts strahl in the background; the caller signals it and waits.
pid_t startStrahl(const std::string& args, const fs::path& errFile) {
    const pid_t pid = fork();
    if (pid == 0) {
        const std::string command =
            std::string(STRAHL_BINARY) + " " + args + " 2>" + errFile.string();
        execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    return pid;
}

int waitExit(pid_t pid) {
    int raw = 0;
    waitpid(pid, &raw, 0);
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// Waits until `file` exists (the first checkpoint: the render is under way).
bool waitForFile(const fs::path& file) {
    for (int i = 0; i < 2000; ++i) {
        if (fs::exists(file)) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
}

class Interrupt : public ::testing::TestWithParam<int> {};

TEST_P(Interrupt, WritesAPartialImageAndResumesToTheSameImageBitForBit) {
    const int signal = GetParam();
    const fs::path dir = test::scratchDir("interrupt-" + std::to_string(signal));
    const ExrFile full = renderWith(dir, "full", " --spp 64");

    // Interval 0: a checkpoint after every pass; its appearance tells that the
    // render is under way. 64 spp at 48 x 36 lasts long enough to be caught.
    const fs::path checkpoint = dir / "render.ckpt", partial = dir / "partial.exr";
    const pid_t pid = startStrahl("render " + kGlossyRoom + kReliabilityFlags + " --spp 64 -o " +
                                      partial.string() + " --checkpoint " + checkpoint.string() +
                                      " --checkpoint-interval 0",
                                  dir / "err.txt");
    ASSERT_TRUE(waitForFile(checkpoint)) << test::readFile(dir / "err.txt");
    kill(pid, signal);
    const int status = waitExit(pid);
    const std::string err = test::readFile(dir / "err.txt");
    if (status == 0) GTEST_SKIP() << "the render finished before the signal arrived";
    EXPECT_EQ(status, 128 + signal) << err;
    EXPECT_TRUE(test::contains(err, signal == SIGINT ? "interrupted by SIGINT" : "by SIGTERM"))
        << err;

    const ExrFile cut = readExr(partial);
    EXPECT_EQ(cut.partial, "1");
    EXPECT_EQ(cut.stopped, signal == SIGINT ? "SIGINT" : "SIGTERM");
    EXPECT_LT(std::stoi(cut.samples), 64);

    const fs::path resumed = dir / "resumed.exr";
    const test::RunResult r =
        runStrahl("render " + kGlossyRoom + kReliabilityFlags + " --spp 64 -o " + resumed.string() +
                  " --resume " + checkpoint.string());
    ASSERT_EQ(r.status, 0) << r.err;
    const ExrFile done = readExr(resumed);
    EXPECT_EQ(done.partial, "0");
    EXPECT_EQ(done.samples, "64");
    expectIdentical(full, done, "resumed after " + cut.samples + " samples");
}

INSTANTIATE_TEST_SUITE_P(Signals, Interrupt, ::testing::Values(SIGINT, SIGTERM),
                         [](const ::testing::TestParamInfo<int>& p) {
                             return std::string(p.param == SIGINT ? "SIGINT" : "SIGTERM");
                         });

TEST(Checkpoint, ResumingAFinishedCheckpointRendersNothingAndGivesTheSameImage) {
    const fs::path dir = test::scratchDir("checkpoint-complete");
    const fs::path checkpoint = dir / "c.ckpt";
    const ExrFile full = renderWith(dir, "full", " --spp 4 --checkpoint " + checkpoint.string());
    ASSERT_TRUE(fs::exists(checkpoint));
    expectIdentical(full, renderWith(dir, "again", " --spp 4 --resume " + checkpoint.string()),
                    "resumed from a complete checkpoint");
}

TEST(Checkpoint, OtherSettingsOrAForeignFileAreOneClearError) {
    const fs::path dir = test::scratchDir("checkpoint-errors");
    const fs::path checkpoint = dir / "c.ckpt";
    renderWith(dir, "full", " --spp 2 --checkpoint " + checkpoint.string());
    const fs::path out = dir / "other.exr";
    test::RunResult r = runStrahl("render " + kGlossyRoom + kReliabilityFlags + " --spp 3 -o " +
                                  out.string() + " --resume " + checkpoint.string());
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(test::contains(r.err, "the checkpoint was made with other settings")) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out));

    test::writeFile(dir / "junk.ckpt", "not a checkpoint");
    r = runStrahl("render " + kGlossyRoom + kReliabilityFlags + " --spp 2 -o " + out.string() +
                  " --resume " + (dir / "junk.ckpt").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(test::contains(r.err, "junk.ckpt: not a strahl checkpoint")) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

TEST(TimeLimit, StopsAtAWholeSamplePassAndWritesTheImage) {
    const fs::path dir = test::scratchDir("time-limit");
    // A limit of 0 s stops after the first pass.
    const ExrFile cut = renderWith(dir, "cut", " --spp 16 --time-limit 0");
    EXPECT_EQ(cut.partial, "1");
    EXPECT_EQ(cut.samples, "1");
    EXPECT_EQ(cut.stopped, "time limit");
    // Stopped by the time limit with a checkpoint, then resumed, the render
    // completes to the uninterrupted image.
    const fs::path checkpoint = dir / "t.ckpt";
    renderWith(dir, "cut2", " --spp 16 --time-limit 0 --checkpoint " + checkpoint.string());
    expectIdentical(renderWith(dir, "full", " --spp 16"),
                    renderWith(dir, "rest", " --spp 16 --resume " + checkpoint.string()),
                    "time-limited render resumed");
}

}  // namespace
}  // namespace strahl
