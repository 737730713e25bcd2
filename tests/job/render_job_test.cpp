// The render job as a library call (job/render_job.h): outputs and stats,
// the time limit, checkpoints and resume, SIGINT, --skip-existing, frame
// names and the rasterizer, without spawning the binary. The CLI tests in
// tests/app check the same behaviour through the command line.

#include "strahl/job/render_job.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/exr_file.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::ExrFile;
using test::expectIdentical;
using test::readExr;

// Path tracing through every geometry kind and glass, small enough for tests.
const fs::path kScene = test::sourceDir() / "scenes/statistical/glossy_room.json";

// What a job told its observer, in order.
struct RecordingObserver final : JobObserver {
    std::vector<std::string> events;  // "start", "skipped", "finished", "pass N"
    std::vector<std::string> notes;
    std::vector<std::string> skippedOutputs;
    std::vector<std::string> phases;
    std::function<void(int)> onPass;  // called after each passDone

    void begin(const std::string& phase, uint64_t) override { phases.push_back(phase); }
    void started(const Start&) override { events.push_back("start"); }
    void passDone(int done) override {
        events.push_back("pass " + std::to_string(done));
        if (onPass) onPass(done);
    }
    void skipped(const std::vector<std::string>& outputs) override {
        events.push_back("skipped");
        skippedOutputs = outputs;
    }
    void note(const std::string& line) override { notes.push_back(line); }
    void finished(const RunReport&) override { events.push_back("finished"); }

    bool noted(const std::string& part) const {
        for (const std::string& n : notes)
            if (test::contains(n, part)) return true;
        return false;
    }
};

ScenePatch patch(const std::string& pointer, const std::string& json) {
    return {pointer, json, pointer + "=" + json};
}

// The glossy room at 48 x 36 with `spp` samples into dir/name.exr (float).
RenderJob roomJob(const fs::path& dir, const std::string& name, int spp) {
    RenderJob job;
    job.scene = kScene;
    job.patches = {patch("/film/width", "48"), patch("/film/height", "36"),
                   patch("/film/exr_float", "true"), patch("/render/spp", std::to_string(spp))};
    job.outputs = {dir / (name + ".exr")};
    return job;
}

TEST(RenderJob, WritesTheOutputsAndTheStatsFile) {
    const fs::path dir = test::scratchDir("job-outputs");
    RenderJob job = roomJob(dir, "image", 2);
    job.stats = dir / "stats.json";
    RecordingObserver observer;
    const JobResult result = runRenderJob(job, observer);

    EXPECT_FALSE(result.skipped);
    EXPECT_EQ(result.report.exitStatus, 0);
    EXPECT_EQ(result.report.samplesDone, 2);
    EXPECT_EQ(result.report.stopped, "");
    EXPECT_GT(result.report.cameraRays, 0u);
    EXPECT_EQ(result.integrator, "path");
    EXPECT_EQ(observer.events,
              (std::vector<std::string>{"start", "pass 1", "pass 2", "finished"}));
    EXPECT_EQ(observer.phases, (std::vector<std::string>{"bvh", "render"}));
    EXPECT_TRUE(observer.noted("wrote " + (dir / "image.exr").string()));

    const ExrFile image = readExr(dir / "image.exr");
    EXPECT_EQ(image.width, 48);
    EXPECT_EQ(image.samples, "2");
    EXPECT_EQ(image.partial, "0");
    EXPECT_TRUE(test::contains(image.fingerprint, "scene glossy_room.json fnv1a ")) << image.fingerprint;

    const auto stats = nlohmann::json::parse(test::readFile(dir / "stats.json"));
    EXPECT_EQ(stats["status"], "complete");
    EXPECT_EQ(stats["samples"]["done"], 2);
    EXPECT_EQ(stats["resolution"], nlohmann::json({48, 36}));
    EXPECT_EQ(stats["outputs"][0], (dir / "image.exr").string());
    EXPECT_EQ(result.report.statsFile, (dir / "stats.json").string());
}

TEST(RenderJob, TimeLimitStopsAfterAWholePassAndMarksTheImagePartial) {
    const fs::path dir = test::scratchDir("job-time-limit");
    RenderJob job = roomJob(dir, "cut", 8);
    job.timeLimit = 0.0;  // past the limit after the first pass
    RecordingObserver observer;
    const JobResult result = runRenderJob(job, observer);
    EXPECT_EQ(result.report.stopped, "time limit");
    EXPECT_EQ(runStatus(result.report), "time limit");
    EXPECT_EQ(result.report.samplesDone, 1);
    EXPECT_EQ(result.report.exitStatus, 0);
    const ExrFile image = readExr(dir / "cut.exr");
    EXPECT_EQ(image.partial, "1");
    EXPECT_EQ(image.stopped, "time limit");
    EXPECT_EQ(image.samples, "1");
}

TEST(RenderJob, ACheckpointedStoppedAndResumedRenderEqualsOneUninterrupted) {
    const fs::path dir = test::scratchDir("job-resume");
    RecordingObserver observer;
    runRenderJob(roomJob(dir, "full", 4), observer);

    RenderJob cut = roomJob(dir, "cut", 4);
    cut.checkpoint = dir / "render.ckpt";
    cut.timeLimit = 0.0;
    EXPECT_EQ(runRenderJob(cut, observer).report.samplesDone, 1);
    ASSERT_TRUE(fs::exists(dir / "render.ckpt"));

    RenderJob rest = roomJob(dir, "resumed", 4);
    rest.resume = dir / "render.ckpt";
    RecordingObserver resumed;
    const JobResult result = runRenderJob(rest, resumed);
    EXPECT_TRUE(resumed.noted("resuming from " + (dir / "render.ckpt").string() +
                              ": 1 of 4 samples per pixel done"));
    EXPECT_EQ(result.report.samplesDone, 4);
    expectIdentical(readExr(dir / "full.exr"), readExr(dir / "resumed.exr"), "resumed");

    // Another seed is another image: the checkpoint refuses it.
    RenderJob other = roomJob(dir, "other", 4);
    other.patches.push_back(patch("/render/seed", "99"));
    other.resume = dir / "render.ckpt";
    const std::string message = test::errorMessage([&] { runRenderJob(other, observer); });
    EXPECT_TRUE(test::contains(message, "the checkpoint was made with other settings")) << message;
    EXPECT_FALSE(fs::exists(dir / "other.exr"));
}

TEST(RenderJob, SigintStopsTheRenderWritesThePartialImageAndTheCheckpoint) {
    const fs::path dir = test::scratchDir("job-sigint");
    RenderJob job = roomJob(dir, "stopped", 8);
    job.checkpoint = dir / "stopped.ckpt";
    job.checkpointInterval = 1e9;  // only the one written at the end
    RecordingObserver observer;
    observer.onPass = [](int done) {
        if (done == 2) std::raise(SIGINT);  // caught by the job, as from a terminal
    };
    const JobResult result = runRenderJob(job, observer);
    EXPECT_EQ(result.report.stopped, "SIGINT");
    EXPECT_EQ(result.report.exitStatus, 128 + SIGINT);
    EXPECT_TRUE(result.render.cancelled);
    EXPECT_GE(result.report.samplesDone, 2);
    EXPECT_LT(result.report.samplesDone, 8);
    const ExrFile image = readExr(dir / "stopped.exr");
    EXPECT_EQ(image.partial, "1");
    EXPECT_EQ(image.stopped, "SIGINT");
    EXPECT_TRUE(fs::exists(dir / "stopped.ckpt"));
}

TEST(RenderJob, AdaptiveSamplingResumesFromACheckpointWithItsStoppedPixels) {
    const fs::path dir = test::scratchDir("job-adaptive");
    const auto adaptiveJob = [&](const std::string& name) {
        RenderJob job = roomJob(dir, name, 24);
        job.patches.push_back(patch("/render/adaptive", R"({"threshold": 0.05, "min_samples": 4})"));
        return job;
    };
    RecordingObserver observer;
    runRenderJob(adaptiveJob("full"), observer);
    const ExrFile full = readExr(dir / "full.exr");
    ASSERT_TRUE(std::find(full.channels.begin(), full.channels.end(), "samples.X") !=
                full.channels.end());
    EXPECT_EQ(full.partial, "0");

    // SIGINT after pass 6 (two rounds of decisions), then --resume.
    RenderJob cut = adaptiveJob("cut");
    cut.checkpoint = dir / "adaptive.ckpt";
    cut.checkpointInterval = 1e9;
    RecordingObserver interrupted;
    interrupted.onPass = [](int done) {
        if (done == 6) std::raise(SIGINT);
    };
    EXPECT_EQ(runRenderJob(cut, interrupted).report.stopped, "SIGINT");
    RenderJob rest = adaptiveJob("resumed");
    rest.resume = dir / "adaptive.ckpt";
    runRenderJob(rest, observer);
    expectIdentical(full, readExr(dir / "resumed.exr"), "resumed adaptive render");
}

TEST(RenderJob, SkipExistingRendersNothingWhenEveryOutputIsThereAndComplete) {
    const fs::path dir = test::scratchDir("job-skip");
    RecordingObserver first;
    RenderJob job = roomJob(dir, "image", 2);
    runRenderJob(job, first);
    const auto written = fs::last_write_time(dir / "image.exr");

    job.skipExisting = true;
    RecordingObserver again;
    const JobResult skipped = runRenderJob(job, again);
    EXPECT_TRUE(skipped.skipped);
    EXPECT_EQ(again.events, std::vector<std::string>{"skipped"});
    EXPECT_EQ(again.skippedOutputs, std::vector<std::string>{(dir / "image.exr").string()});
    EXPECT_EQ(fs::last_write_time(dir / "image.exr"), written);

    // Another setting is another image: rendered again, with the reason noted.
    job.patches.push_back(patch("/render/seed", "5"));
    RecordingObserver changed;
    EXPECT_FALSE(runRenderJob(job, changed).skipped);
    EXPECT_TRUE(changed.noted("--skip-existing: " + (dir / "image.exr").string()))
        << (changed.notes.empty() ? "" : changed.notes[0]);
}

TEST(RenderJob, FrameNumbersFillTheHashRunsOfEveryFileName) {
    const fs::path dir = test::scratchDir("job-frames");
    RenderJob job = roomJob(dir, "beauty.###", 1);
    job.stats = dir / "stats.####.json";
    RecordingObserver observer;
    const std::string message = test::errorMessage([&] { runRenderJob(job, observer); });
    EXPECT_TRUE(test::contains(message, "no --frame")) << message;

    job.frame = 7;
    const JobResult result = runRenderJob(job, observer);
    EXPECT_TRUE(fs::exists(dir / "beauty.007.exr"));
    EXPECT_TRUE(fs::exists(dir / "stats.0007.json"));
    EXPECT_EQ(result.report.frame, 7);
    EXPECT_EQ(readExr(dir / "beauty.007.exr").frame, "7");
}

TEST(RenderJob, TheRasterizerTakesTheSameJob) {
    const fs::path dir = test::scratchDir("job-raster");
    test::writeFile(dir / "quad.json", R"({
      "film": { "width": 16, "height": 12 },
      "render": { "integrator": "eyelight", "spp": 1 },
      "shapes": [ { "type": "mesh", "positions": [[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]],
                    "indices": [0,1,2, 0,2,3] } ] })");
    RenderJob job;
    job.scene = dir / "quad.json";
    job.outputs = {dir / "raster.exr"};
    job.algorithm = RenderAlgorithm::Raster;
    RecordingObserver observer;
    const JobResult result = runRenderJob(job, observer);
    ASSERT_TRUE(result.raster.has_value());
    EXPECT_GT(result.raster->coveredPixels, 0u);
    EXPECT_EQ(result.report.algorithm, "raster");
    EXPECT_EQ(result.report.accel, "none");
    EXPECT_EQ(observer.phases, std::vector<std::string>{"raster"});
    EXPECT_EQ(observer.events, (std::vector<std::string>{"start", "pass 1", "finished"}));

    // The options the rasterizer cannot honour are refused before loading.
    job.timeLimit = 1.0;
    const std::string message = test::errorMessage([&] { runRenderJob(job, observer); });
    EXPECT_TRUE(test::contains(message, "apply to ray tracing, not --algorithm raster")) << message;
}

}  // namespace
}  // namespace strahl
