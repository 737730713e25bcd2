#include "commands.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <tbb/task_arena.h>

#include <nlohmann/json.hpp>

#include "existing_outputs.h"
#include "frame_pattern.h"
#include "progress_reporter.h"
#include "render_control.h"
#include "scene_loading.h"
#include "stats_file.h"
#include "strahl/core/error.h"
#include "strahl/core/process_memory.h"
#include "strahl/distributed/distributed.h"
#include "strahl/film/checkpoint.h"
#include "strahl/film/image_output.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/raster/rasterizer.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "strahl/scene/scene_document.h"

namespace strahl::app {

namespace {

// -o replaces the scene's film.outputs (its names are relative to the
// current folder).
void applyOutputs(const Options& o, SceneDesc& desc) {
    if (o.outputs.empty()) return;
    desc.film.outputs.clear();
    for (const std::string& out : o.outputs) desc.film.outputs.emplace_back(out);
}

PixelRect cropWindow(const Options& o, const SceneDesc& desc) {
    const PixelRect full{0, 0, desc.film.width, desc.film.height};
    if (!o.crop) return full;
    const PixelRect& c = *o.crop;
    if (c.x1 > full.x1 || c.y1 > full.y1)
        fail(o.cropArgument, " exceeds the ", full.x1, "x", full.y1,
             " image (need X1 <= ", full.x1, " and Y1 <= ", full.y1, ")");
    return c;
}

// The file options with their '#' frame patterns filled (frame_pattern.h);
// parseOptions has made sure there is a --frame if any has one.
Options withFrameNames(Options o) {
    const int frame = o.frame.value_or(-1);
    for (std::string& out : o.outputs) out = expandFramePattern(out, frame, "-o").string();
    for (std::optional<std::string>* file : {&o.stats, &o.checkpoint, &o.resume})
        if (*file) **file = expandFramePattern(**file, frame, "file").string();
    return o;
}

// --skip-existing: whether every output is already complete (existing_outputs.h);
// if so, says so in one line (and a "skipped" JSON event).
bool outputsComplete(const Options& o, const SceneDesc& desc, const PixelRect& crop,
                     const std::string& fingerprint, ProgressReporter& progress) {
    const ExpectedImage expected{desc.film.width, desc.film.height, crop, fingerprint};
    std::vector<std::string> names;
    for (const auto& out : desc.film.outputs) {
        const std::string why = incompleteReason(out, expected);
        if (!why.empty()) {
            // A missing output is the normal case; anything else is worth a line in the log.
            if (!o.quiet && why != "does not exist")
                std::fprintf(stderr, "--skip-existing: %s %s: rendering it again\n",
                             out.string().c_str(), why.c_str());
            return false;
        }
        names.push_back(out.string());
    }
    // The outputs of one command are written together, by one run: one that
    // records strahl:partial vouches for the others.
    if (std::none_of(desc.film.outputs.begin(), desc.film.outputs.end(),
                     [](const std::filesystem::path& p) { return recordsPartial(p); })) {
        if (!o.quiet)
            std::fprintf(stderr, "--skip-existing: JPEG and TIFF images do not record whether "
                                 "they are partial; add an .exr or .png output to make them "
                                 "skippable: rendering again\n");
        return false;
    }
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    if (!o.quiet)
        std::fprintf(stderr, "skipped: every output exists and is complete: %s\n", list.c_str());
    progress.event("skipped", {{"outputs", names}, {"exit_status", 0}});
    return true;
}

// What the stats file and the last JSON event say about a finished run.
RunReport makeReport(const Options& o, const SceneDesc& desc, const PixelRect& crop,
                     const BuildTimings& timings, const RenderStats& stats, bool raster,
                     double totalSeconds) {
    RunReport r;
    r.scene = o.scene;
    r.frame = o.frame;
    r.width = desc.film.width;
    r.height = desc.film.height;
    r.region = crop;
    r.spp = desc.render.spp;
    r.seed = desc.render.seed;
    r.integrator = desc.render.integrator;
    r.algorithm = o.algorithm;
    r.accel = raster ? "none" : o.accel;
    r.sampleBegin = o.sampleOffset.value_or(0);  // --sample-offset: a part of a split render
    r.sampleEnd = r.sampleBegin + desc.render.spp;
    r.samplesDone = raster ? desc.render.spp : stats.completedPasses;
    // tbb's default arena: the cores this process may use (its affinity mask).
    r.threads = o.threads.value_or(0) > 0 ? *o.threads : tbb::this_task_arena::max_concurrency();
    r.loadSeconds = timings.loadSeconds;
    r.bvhSeconds = timings.bvhSeconds;
    r.renderSeconds = stats.seconds;
    r.firstPixelSeconds = timings.loadSeconds + timings.bvhSeconds + stats.firstTileSeconds;
    r.totalSeconds = totalSeconds;
    r.cameraRays = stats.cameraRays;
    r.shadowRays = stats.shadowRays;
    r.bounceRays = stats.bounceRays;
    r.peakResidentBytes = peakResidentBytes();
    for (const auto& out : desc.film.outputs) r.outputs.push_back(out.string());
    if (stats.cancelled) r.stopped = signalName(InterruptGuard::signalNumber());
    if (stats.stoppedEarly) r.stopped = "time limit";
    r.exitStatus = stats.cancelled ? 128 + InterruptGuard::signalNumber() : 0;
    return r;
}

std::string humanCount(double n) {
    char buf[32];
    if (n >= 1e9) std::snprintf(buf, sizeof buf, "%.2fG", n / 1e9);
    else if (n >= 1e6) std::snprintf(buf, sizeof buf, "%.2fM", n / 1e6);
    else if (n >= 1e3) std::snprintf(buf, sizeof buf, "%.1fk", n / 1e3);
    else std::snprintf(buf, sizeof buf, "%.0f", n);
    return buf;
}

// Everything that can be checked before the scene's meshes are loaded, so a
// bad output path, integrator name, OCIO config or option combination fails
// now, not after a long load or render.
void checkBeforeLoading(const Options& o, const SceneDesc& desc, bool worker, bool raster) {
    if (!worker)
        for (const auto& out : desc.film.outputs) checkOutputPath(out);
    // A bad OCIO config must fail now, not after the render: load it if any
    // output goes through the display transform or a config was named.
    const bool displayOutput = std::any_of(
        desc.film.outputs.begin(), desc.film.outputs.end(), [](const std::filesystem::path& p) {
            std::string ext = p.extension().string();
            for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
            return ext != ".exr";
        });
    if (!worker && (displayOutput || !o.color.configFile.empty())) DisplayTransform::get(o.color);
    requireIntegratorName(desc.render.integrator);
    if (raster) requireRasterSettings(desc.render.integrator, desc.render.spp);
    if (raster && (o.checkpoint || o.resume || o.timeLimit))
        fail("--checkpoint, --resume and --time-limit apply to ray tracing, not --algorithm raster");
    if (o.distributed && (raster || o.checkpoint || o.resume || o.timeLimit))
        fail("--distributed renders every tile whole, in one go, with the ray tracer: "
             "--algorithm raster, --checkpoint, --resume and --time-limit do not apply to it");
    if (o.sampleOffset && (raster || o.distributed))
        fail("--sample-offset splits the samples of a local ray-traced render: --algorithm raster "
             "and --distributed do not apply to it");
    // Rank 0 alone cannot decide to skip: the workers would wait for it forever.
    if (o.distributed && o.skipExisting)
        fail("--skip-existing does not apply to --distributed: run it without, or check the "
             "outputs before starting the job");
}

// The metadata every output carries (docs/output.md): the settings, the
// fingerprint, and for ray tracing whether the image is partial.
ImageMetadata imageMetadata(const Options& o, const SceneDocument& document,
                            const SceneDesc& desc, const Camera& camera, const RenderStats& stats,
                            bool raster, const std::string& sceneFingerprint) {
    ImageMetadata metadata;
    metadata.renderSeconds = stats.seconds;
    metadata.spp = desc.render.spp;
    metadata.integrator = desc.render.integrator;
    metadata.camera = describeCamera(desc.camera);
    metadata.worldToCamera = camera.worldToCamera();
    metadata.extra["seed"] = std::to_string(desc.render.seed);
    metadata.extra["scene"] = desc.file.filename().string();
    metadata.extra["algorithm"] = o.algorithm;
    metadata.extra["fingerprint"] = sceneFingerprint;
    if (o.frame) metadata.extra["frame"] = std::to_string(*o.frame);
    const bool partial = stats.cancelled || stats.stoppedEarly;
    if (!raster) {
        // Every pixel has at least completedPasses samples; after an interrupt
        // the tiles that were in flight have one more.
        metadata.extra["samples"] = std::to_string(stats.completedPasses);
        metadata.extra["partial"] = partial ? "1" : "0";
        if (stats.cancelled) metadata.extra["stopped"] = signalName(InterruptGuard::signalNumber());
        if (stats.stoppedEarly) metadata.extra["stopped"] = "time limit";
        metadata.extra["accel"] = o.accel;
    }
    // A part of a split render: the samples it was asked for (a partial part
    // has fewer in some pixels, which strahl merge detects and refuses).
    if (o.sampleOffset) {
        const auto begin = static_cast<uint32_t>(*o.sampleOffset);
        metadata.part = SamplePart{{{begin, begin + static_cast<uint32_t>(desc.render.spp)}},
                                   splitFingerprint(o, document)};
    }
    return metadata;
}

// The summary and memory lines after a render (docs/cli.md); `raster` is
// null for ray tracing.
void printSummary(const SceneDesc& desc, const World& world, const BuildTimings& timings,
                  const RenderStats& stats, const RasterStats* raster) {
    if (raster) {
        std::fprintf(stderr,
                     "summary: load %.2f s, raster %.2f s | %s triangles (%s in view), %s "
                     "fragments, %s pixels covered | %s, 1 spp, rasterized\n",
                     timings.loadSeconds, raster->seconds,
                     humanCount(double(raster->triangles)).c_str(),
                     humanCount(double(raster->trianglesInView)).c_str(),
                     humanCount(double(raster->fragments)).c_str(),
                     humanCount(double(raster->coveredPixels)).c_str(),
                     desc.render.integrator.c_str());
    } else {
        const double rays = static_cast<double>(stats.totalRays());
        std::fprintf(stderr,
                     "summary: load %.2f s, bvh %.2f s, render %.2f s, first pixel after %.2f s "
                     "| %s rays (%s camera, %s shadow, %s bounce), %.1f Mrays/s | %s, %d spp, "
                     "%s\n",
                     timings.loadSeconds, timings.bvhSeconds, stats.seconds,
                     timings.loadSeconds + timings.bvhSeconds + stats.firstTileSeconds,
                     humanCount(rays).c_str(), humanCount(double(stats.cameraRays)).c_str(),
                     humanCount(double(stats.shadowRays)).c_str(),
                     humanCount(double(stats.bounceRays)).c_str(),
                     stats.seconds > 0 ? rays / stats.seconds / 1e6 : 0.0,
                     desc.render.integrator.c_str(), desc.render.spp,
                     stats.packetWidth > 1 ? ("packets of " + std::to_string(stats.packetWidth)).c_str()
                                           : "single rays");
    }
    std::fprintf(stderr, "memory: shapes %s, bvh %s, peak resident %s\n",
                     formatBytes(world.shapeMemoryBytes()).c_str(),
                     formatBytes(world.accel->memoryBytes()).c_str(),
                     formatBytes(peakResidentBytes()).c_str());
}

int renderScene(const Options& given, ProgressReporter& progress) {
    const auto started = std::chrono::steady_clock::now();
    const Options o = withFrameNames(given);
    const SceneDocument document = patchedScene(o);
    SceneDesc desc = document.parse();
    applyOutputs(o, desc);
    for (auto& out : desc.film.outputs)
        out = expandFramePattern(out, o.frame.value_or(-1), o.scene + ": film.outputs:");
    if (desc.film.outputs.empty())
        fail(o.scene, ": no output image: give -o FILE or film.outputs in the scene");
    // Distributed workers write nothing: only rank 0 checks the outputs.
    const bool worker = distributed::role() == distributed::Role::Worker;
    const bool raster = o.algorithm == "raster";
    checkBeforeLoading(o, desc, worker, raster);
    const PixelRect crop = cropWindow(o, desc);
    if (o.stats && !worker) checkStatsPath(*o.stats);
    // The sample offset decides the pixels too: regions of different sample
    // ranges must not be assembled, nor one skipped for the other.
    const std::string image = imageFingerprint(document);
    const std::string sceneFingerprint =
        image +
        (o.sampleOffset ? ", samples from " + std::to_string(*o.sampleOffset) : std::string());
    // Before anything heavy is loaded: only the scene file has been read.
    if (o.skipExisting && !worker && outputsComplete(o, desc, crop, sceneFingerprint, progress))
        return 0;
    {
        std::vector<std::string> outputs;
        for (const auto& out : desc.film.outputs) outputs.push_back(out.string());
        progress.event("start", {{"scene", o.scene},
                                 {"frame", o.frame ? nlohmann::ordered_json(*o.frame)
                                                   : nlohmann::ordered_json(nullptr)},
                                 {"resolution", {desc.film.width, desc.film.height}},
                                 {"region", {crop.x0, crop.y0, crop.x1, crop.y1}},
                                 {"spp", desc.render.spp},
                                 {"outputs", outputs}});
        progress.setPasses(0, desc.render.spp);
    }

    if (o.quiet) setMeshWarningHandler([](const std::string&) {});
    BuildOptions build = buildOptions(o);
    if (raster) {
        build.accel = AccelKind::Naive;  // the rasterizer traces no rays: no BVH to build
    } else {
        build.accel = accelFromName(o.accel);
        build.bvhStarted = [&] { progress.begin("bvh", 1); };
        build.bvhProgress = [&](double f) { progress.setFraction(f); };
    }
    BuildTimings timings;
    const World world = buildWorld(desc, build, &timings);
    if (!raster) progress.end();  // of the BVH phase

    const Camera camera = buildCamera(desc.camera, desc.film.width, desc.film.height);
    const auto integrator = makeIntegrator(desc.render.integrator, world,
                                           buildIntegratorOptions(desc, camera));
    Film film(desc.film.width, desc.film.height, crop, desc.film.aovs);

    RenderStats stats;
    RasterStats rasterStats;
    if (raster) {
        RasterOptions options;
        options.threads = o.threads.value_or(0);
        options.tileSize = o.tileSize;
        options.spp = desc.render.spp;
        options.seed = desc.render.seed;
        options.started = [&](size_t tiles) { progress.begin("raster", tiles); };
        options.tileDone = [&] { progress.advance(1); };
        progress.setPasses(0, 1);
        rasterStats = rasterizeImage(world, camera, *integrator, film, options);
        progress.end();
        progress.passDone(1);
        stats.seconds = rasterStats.seconds;
    } else {
        const std::string fingerprint = renderFingerprint(o, image, crop);
        if (o.resume) {
            readCheckpoint(film, *o.resume, fingerprint);
            if (!o.quiet)
                std::fprintf(stderr, "resuming from %s: %u of %d samples per pixel done\n",
                             o.resume->c_str(), film.sampleCount(crop.x0, crop.y0),
                             desc.render.spp);
        }
        RenderOptions options;
        options.threads = o.threads.value_or(0);
        options.tileSize = o.tileSize;
        options.spp = desc.render.spp;
        options.seed = desc.render.seed;
        options.filter = buildPixelFilter(desc.film);
        options.packets = o.packets;
        options.progress = &progress;
        options.cancel = &InterruptGuard::cancelFlag();
        options.sampleOffset = o.sampleOffset.value_or(0);
        options.samplePart = o.sampleOffset.has_value();
        const auto renderStart = std::chrono::steady_clock::now();
        auto lastCheckpoint = renderStart;
        const auto secondsSince = [](std::chrono::steady_clock::time_point t) {
            return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
        };
        const int samplesBefore = static_cast<int>(film.sampleCount(crop.x0, crop.y0));
        progress.setPasses(samplesBefore, desc.render.spp);
        options.passDone = [&](int samplesDone) {
            progress.passDone(samplesDone);
            if (o.checkpoint && secondsSince(lastCheckpoint) >= o.checkpointInterval) {
                writeCheckpoint(film, *o.checkpoint, fingerprint);
                lastCheckpoint = std::chrono::steady_clock::now();
            }
            return !(o.timeLimit && secondsSince(renderStart) >= *o.timeLimit);
        };
        if (o.distributed) {
            // Rank 0 gathers the image and goes on to write it like a local
            // render; a worker has nothing to write. SIGINT/SIGTERM keep their
            // default action: the job ends and no image is written.
            distributed::Settings settings;
            settings.fingerprint = fingerprint;
            settings.report = !o.quiet;
            stats = distributed::renderImage(world, camera, *integrator, film, options, settings);
            if (worker) return 0;
        } else {
            const InterruptGuard interrupts;
            stats = renderImage(world, camera, *integrator, film, options);
        }
        // renderImage reports every pass but the last through passDone.
        if (stats.completedPasses == desc.render.spp && samplesBefore < desc.render.spp)
            progress.passDone(desc.render.spp);
        // The state at the end, complete or not, so nothing rendered is lost:
        // an interrupted render resumes from exactly where it stopped.
        if (o.checkpoint) writeCheckpoint(film, *o.checkpoint, fingerprint);
    }

    OutputSettings output;
    output.exrFloat = desc.film.exrFloat;
    output.color = o.color;
    const ImageMetadata metadata =
        imageMetadata(o, document, desc, camera, stats, raster, sceneFingerprint);
    for (const auto& out : desc.film.outputs) {
        writeImage(film, out, output, metadata);
        if (!o.quiet) std::fprintf(stderr, "wrote %s\n", out.string().c_str());
    }
    {
        const RunReport report = makeReport(
            o, desc, crop, timings, stats, raster,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
        if (o.stats) writeStatsFile(*o.stats, report);
        progress.event(report.stopped.empty() ? "done" : "interrupted",
                       {{"status", runStatus(report)},
                        {"stopped", report.stopped.empty() ? nlohmann::ordered_json(nullptr)
                                                           : nlohmann::ordered_json(report.stopped)},
                        {"partial", !report.stopped.empty()},
                        {"passes_done", report.samplesDone},
                        {"passes_total", report.spp},
                        {"outputs", report.outputs},
                        {"stats", o.stats ? nlohmann::ordered_json(*o.stats)
                                          : nlohmann::ordered_json(nullptr)},
                        {"exit_status", report.exitStatus}});
    }

    if (stats.cancelled) {
        const int signal = InterruptGuard::signalNumber();
        std::fprintf(stderr,
                     "strahl: interrupted by %s after %d of %d samples per pixel; the images "
                     "written are partial%s\n",
                     signalName(signal).c_str(), stats.completedPasses, desc.render.spp,
                     o.checkpoint ? " (resume with --resume)" : "");
        return 128 + signal;  // the shell's convention for death by a signal
    }
    if (stats.stoppedEarly && !o.quiet)
        std::fprintf(stderr, "time limit reached: stopped after %d of %d samples per pixel\n",
                     stats.completedPasses, desc.render.spp);

    if (!o.quiet) printSummary(desc, world, timings, stats, raster ? &rasterStats : nullptr);
    return 0;
}

}  // namespace

int runRender(const Options& o) {
    // Distributed workers print nothing (rank 0 reports for the job).
    const bool json = o.jsonProgress && distributed::role() != distributed::Role::Worker;
    ProgressReporter progress(json ? ProgressReporter::Style::Json
                                   : ProgressReporter::defaultStyle(o.quiet));
    try {
        return renderScene(o, progress);
    } catch (const std::exception& e) {
        // The JSON stream ends with an event whatever happens; main prints the message.
        progress.event("error", {{"message", e.what()}, {"exit_status", 1}});
        throw;
    }
}

}  // namespace strahl::app
