#include "strahl/job/render_job.h"

#include <algorithm>
#include <cctype>
#include <chrono>

#include <tbb/task_arena.h>

#include "strahl/core/error.h"
#include "strahl/core/process_memory.h"
#include "strahl/distributed/distributed.h"
#include "strahl/film/checkpoint.h"
#include "strahl/film/image_output.h"
#include "strahl/job/denoise_film.h"
#include "strahl/job/existing_outputs.h"
#include "strahl/job/fingerprints.h"
#include "strahl/job/frame_pattern.h"
#include "strahl/job/interrupts.h"
#include "strahl/scene/scene_desc.h"

namespace strahl {

const char* algorithmName(RenderAlgorithm algorithm) {
    return algorithm == RenderAlgorithm::Raster ? "raster" : "raytrace";
}

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

// The job with its '#' frame patterns filled (frame_pattern.h).
RenderJob withFrameNames(RenderJob job) {
    const int frame = job.frame.value_or(-1);
    for (fs::path& out : job.outputs) out = expandFramePattern(out, frame, "-o");
    for (std::optional<fs::path>* file : {&job.stats, &job.checkpoint, &job.resume})
        if (*file) **file = expandFramePattern(**file, frame, "file");
    return job;
}

// The job's outputs (their frame patterns filled by withFrameNames), or else
// the scene's film.outputs with theirs filled.
std::vector<fs::path> outputFiles(const RenderJob& job, const SceneDesc& desc) {
    std::vector<fs::path> outputs = job.outputs;
    if (outputs.empty())
        for (const fs::path& out : desc.film.outputs)
            outputs.push_back(expandFramePattern(out, job.frame.value_or(-1),
                                                 job.scene.string() + ": film.outputs:"));
    if (outputs.empty())
        fail(job.scene.string(), ": no output image: give -o FILE or film.outputs in the scene");
    return outputs;
}

// --crop or --region, else the scene's film.crop (checked against the film
// when the scene was parsed, after --width and --height), else the whole film.
PixelRect cropWindow(const RenderJob& job, const SceneDesc& desc) {
    const PixelRect full{0, 0, desc.film.width, desc.film.height};
    if (!job.crop) return desc.film.crop.value_or(full);
    const PixelRect& c = *job.crop;
    if (c.x1 > full.x1 || c.y1 > full.y1)
        fail(job.cropOrigin, " exceeds the ", full.x1, "x", full.y1,
             " image (need X1 <= ", full.x1, " and Y1 <= ", full.y1, ")");
    return c;
}

// Everything that can be checked before the scene's meshes are loaded, so a
// bad output path, integrator name, OCIO config or option combination fails
// now, not after a long load or render.
void checkBeforeLoading(const RenderJob& job, const SceneDesc& desc,
                        const std::vector<fs::path>& outputs, bool worker) {
    const bool raster = job.algorithm == RenderAlgorithm::Raster;
    if (!worker)
        for (const fs::path& out : outputs) checkOutputPath(out);
    // A bad OCIO config must fail now, not after the render: load it if any
    // output goes through the display transform or a config was named.
    const bool displayOutput =
        std::any_of(outputs.begin(), outputs.end(), [](const fs::path& p) {
            std::string ext = p.extension().string();
            for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
            return ext != ".exr";
        });
    if (!worker && (displayOutput || !job.color.configFile.empty())) DisplayTransform::get(job.color);
    requireIntegratorName(desc.render.integrator);
    if (raster) requireRasterSettings(desc.render.integrator, desc.render.spp);
    if (raster && (job.checkpoint || job.resume || job.timeLimit))
        fail("--checkpoint, --resume and --time-limit apply to ray tracing, not --algorithm raster");
    if (job.distributed && (raster || job.checkpoint || job.resume || job.timeLimit))
        fail("--distributed renders one image in one go, with the ray tracer: "
             "--algorithm raster, --checkpoint, --resume and --time-limit do not apply to it");
    if (desc.render.denoise && raster)
        fail("render.denoise (--denoise) needs the ray tracer: the rasterizer renders one sample "
             "per pixel, and the denoiser needs two independent halves");
    if (desc.render.denoise && !job.sampleOffset && desc.render.spp < 2)
        fail("render.denoise (--denoise) needs at least 2 samples per pixel (one for each of the "
             "even and odd halves it compares); got ", desc.render.spp);
    if (job.sampleOffset && (raster || job.distributed))
        fail("--sample-offset splits the samples of a local ray-traced render: --algorithm raster "
             "and --distributed do not apply to it");
    if (desc.render.adaptiveThreshold > 0.0f) {
        const char* why = raster ? "--algorithm raster renders one sample per pixel"
                          : job.sampleOffset
                              ? "--sample-offset: which pixels stop depends on all of a render's "
                                "samples, so the parts of a split render would not add up to it"
                              : nullptr;
        if (why)
            fail(job.scene.string(), ": /render/adaptive: adaptive sampling does not apply to ",
                 why, "; turn it off (threshold 0) for this render");
    }
    // Rank 0 alone cannot decide to skip: the workers would wait for it forever.
    if (job.distributed && job.skipExisting)
        fail("--skip-existing does not apply to --distributed: run it without, or check the "
             "outputs before starting the job");
}

// skipExisting: whether every output is already complete (existing_outputs.h).
bool outputsComplete(const std::vector<fs::path>& outputs, const SceneDesc& desc,
                     const PixelRect& crop, const std::string& fingerprint, JobObserver& observer) {
    const ExpectedImage expected{desc.film.width, desc.film.height, crop, fingerprint};
    std::vector<std::string> names;
    for (const fs::path& out : outputs) {
        const std::string why = incompleteReason(out, expected);
        if (!why.empty()) {
            // A missing output is the normal case; anything else is worth a line in the log.
            if (why != "does not exist")
                observer.note("--skip-existing: " + out.string() + " " + why +
                              ": rendering it again");
            return false;
        }
        names.push_back(out.string());
    }
    // The outputs of one command are written together, by one run: one that
    // records strahl:partial vouches for the others.
    if (std::none_of(outputs.begin(), outputs.end(),
                     [](const fs::path& p) { return recordsPartial(p); })) {
        observer.note("--skip-existing: JPEG and TIFF images do not record whether they are "
                      "partial; add an .exr or .png output to make them skippable: rendering "
                      "again");
        return false;
    }
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    observer.note("skipped: every output exists and is complete: " + list);
    observer.skipped(names);
    return true;
}

// What the stats file and the observer's finished() say about a run.
RunReport makeReport(const RenderJob& job, const SceneDesc& desc, const PixelRect& crop,
                     const std::vector<fs::path>& outputs, const JobResult& result) {
    const bool raster = job.algorithm == RenderAlgorithm::Raster;
    const RenderStats& stats = result.render;
    RunReport r;
    r.scene = job.scene.string();
    r.frame = job.frame;
    r.width = desc.film.width;
    r.height = desc.film.height;
    r.region = crop;
    r.spp = desc.render.spp;
    r.seed = desc.render.seed;
    r.integrator = desc.render.integrator;
    r.algorithm = algorithmName(job.algorithm);
    r.accel = raster ? "none" : accelName(job.build.accel);
    r.sampleBegin = job.sampleOffset.value_or(0);
    r.sampleEnd = r.sampleBegin + desc.render.spp;
    r.samplesDone = raster ? desc.render.spp : stats.completedPasses;
    // tbb's default arena: the cores this process may use (its affinity mask).
    r.threads = job.build.threads > 0 ? job.build.threads
                                      : tbb::this_task_arena::max_concurrency();
    r.loadSeconds = result.timings.loadSeconds;
    r.bvhSeconds = result.timings.bvhSeconds;
    r.renderSeconds = stats.seconds;
    r.denoiseSeconds = result.denoiseSeconds;
    r.firstPixelSeconds =
        result.timings.loadSeconds + result.timings.bvhSeconds + stats.firstTileSeconds;
    r.cameraRays = stats.cameraRays;
    r.shadowRays = stats.shadowRays;
    r.bounceRays = stats.bounceRays;
    r.peakResidentBytes = peakResidentBytes();
    for (const fs::path& out : outputs) r.outputs.push_back(out.string());
    if (stats.cancelled) r.stopped = signalName(InterruptGuard::signalNumber());
    if (stats.stoppedEarly) r.stopped = "time limit";
    r.exitStatus = stats.cancelled ? 128 + InterruptGuard::signalNumber() : 0;
    return r;
}

// The metadata every output carries (docs/output.md): the settings, the
// fingerprints, and for ray tracing whether the image is partial.
ImageMetadata imageMetadata(const RenderJob& job, const SceneDocument& document,
                            const SceneDesc& desc, const CameraDesc& cameraDesc,
                            const Camera& camera, const RenderStats& stats,
                            const std::string& fingerprint) {
    ImageMetadata metadata;
    metadata.renderSeconds = stats.seconds;
    metadata.spp = desc.render.spp;
    metadata.integrator = desc.render.integrator;
    metadata.camera = describeCamera(cameraDesc);
    metadata.worldToCamera = camera.worldToCamera();
    metadata.extra["seed"] = std::to_string(desc.render.seed);
    metadata.extra["scene"] = desc.file.filename().string();
    metadata.extra["algorithm"] = algorithmName(job.algorithm);
    metadata.extra["fingerprint"] = fingerprint;
    if (job.frame) metadata.extra["frame"] = std::to_string(*job.frame);
    // Biased settings are said in the image itself (docs/output.md).
    if (desc.render.clampDirect > 0.0f)
        metadata.extra["clamp_direct"] = std::to_string(desc.render.clampDirect);
    if (desc.render.clampIndirect > 0.0f)
        metadata.extra["clamp_indirect"] = std::to_string(desc.render.clampIndirect);
    if (desc.render.filterGlossy > 0.0f)
        metadata.extra["filter_glossy"] = std::to_string(desc.render.filterGlossy);
    if (desc.render.adaptiveThreshold > 0.0f) {
        metadata.extra["adaptive_threshold"] = std::to_string(desc.render.adaptiveThreshold);
        metadata.extra["adaptive_min_samples"] = std::to_string(desc.render.adaptiveMinSamples);
    }
    const bool partial = stats.cancelled || stats.stoppedEarly;
    if (job.algorithm == RenderAlgorithm::RayTrace) {
        // Every pixel has at least completedPasses samples; after an interrupt
        // the tiles that were in flight have one more. With adaptive sampling
        // it is the most a pixel has, and the samples AOV has each one's.
        metadata.extra["samples"] = std::to_string(stats.completedPasses);
        metadata.extra["partial"] = partial ? "1" : "0";
        if (stats.cancelled) metadata.extra["stopped"] = signalName(InterruptGuard::signalNumber());
        if (stats.stoppedEarly) metadata.extra["stopped"] = "time limit";
        metadata.extra["accel"] = accelName(job.build.accel);
    }
    // A part of a split render: the samples it was asked for (a partial part
    // has fewer in some pixels, which strahl merge detects and refuses).
    if (job.sampleOffset) {
        const auto begin = static_cast<uint32_t>(*job.sampleOffset);
        metadata.part = SamplePart{{{begin, begin + static_cast<uint32_t>(desc.render.spp)}},
                                   splitFingerprint(job.build.accel, document)};
    }
    return metadata;
}

// The options of both renderers: threads, tiles, samples, progress.
RenderOptions renderOptions(const RenderJob& job, const SceneDesc& desc, JobObserver& observer) {
    RenderOptions options;
    options.threads = job.build.threads;
    options.tileSize = job.tileSize;
    options.spp = desc.render.spp;
    options.seed = desc.render.seed;
    options.filter = buildPixelFilter(desc.film);
    options.packets = job.packets;
    options.progress = &observer;
    options.sampleOffset = job.sampleOffset.value_or(0);
    options.samplePart = job.sampleOffset.has_value();
    options.adaptive.threshold = desc.render.adaptiveThreshold;
    options.adaptive.minSamples = desc.render.adaptiveMinSamples;
    return options;
}

// Ray tracing, locally or distributed, with checkpoints, resume, the time
// limit and SIGINT/SIGTERM.
void rayTrace(const RenderJob& job, const SceneDesc& desc, const World& world,
              const Camera& camera, const Integrator& integrator, Film& film,
              const std::string& fingerprint, JobObserver& observer, JobResult& result) {
    const PixelRect crop = film.crop();
    const int spp = desc.render.spp;
    if (job.resume) {
        readCheckpoint(film, *job.resume, fingerprint);
        observer.note("resuming from " + job.resume->string() + ": " +
                      std::to_string(film.sampleCount(crop.x0, crop.y0)) + " of " +
                      std::to_string(spp) + " samples per pixel done");
    }
    RenderOptions options = renderOptions(job, desc, observer);
    options.cancel = &InterruptGuard::cancelFlag();
    const auto renderStart = Clock::now();
    auto lastCheckpoint = renderStart;
    const int samplesBefore = static_cast<int>(film.sampleCount(crop.x0, crop.y0));
    observer.passes(samplesBefore, spp);
    options.passDone = [&](int samplesDone) {
        observer.passDone(samplesDone);
        if (job.checkpoint && secondsSince(lastCheckpoint) >= job.checkpointInterval) {
            writeCheckpoint(film, *job.checkpoint, fingerprint);
            lastCheckpoint = Clock::now();
        }
        return !(job.timeLimit && secondsSince(renderStart) >= *job.timeLimit);
    };
    if (job.distributed) {
        // Rank 0 gathers the image and goes on to write it like a local
        // render; a worker has nothing to write. SIGINT/SIGTERM keep their
        // default action: the job ends and no image is written.
        distributed::Settings settings;
        settings.fingerprint = fingerprint;
        settings.report = !job.quiet;
        result.render = distributed::renderImage(world, camera, integrator, film, options, settings);
        if (result.worker) return;
    } else {
        const InterruptGuard interrupts;
        result.render = renderImage(world, camera, integrator, film, options);
    }
    // renderImage reports every pass but the last through passDone.
    if ((result.render.completedPasses == spp || result.render.converged) && samplesBefore < spp)
        observer.passDone(result.render.completedPasses);
    if (result.render.converged)
        observer.note(concat("adaptive sampling: every pixel converged after ",
                             result.render.completedPasses, " of ", spp, " samples"));
    // The state at the end, complete or not, so nothing rendered is lost: an
    // interrupted render resumes from exactly where it stopped.
    if (job.checkpoint) writeCheckpoint(film, *job.checkpoint, fingerprint);
}

void rasterize(const RenderJob& job, const SceneDesc& desc, const World& world,
               const Camera& camera, const Integrator& integrator, Film& film,
               JobObserver& observer, JobResult& result) {
    observer.passes(0, 1);
    result.raster = rasterizeImage(world, camera, integrator, film,
                                   renderOptions(job, desc, observer));
    observer.passDone(1);
    result.render.seconds = result.raster->seconds;
}

}  // namespace

JobResult runRenderJob(const RenderJob& given, JobObserver& observer) {
    const auto started = Clock::now();
    const RenderJob job = withFrameNames(given);
    SceneDocument document = SceneDocument::read(job.scene, job.defines);
    for (const ScenePatch& patch : job.patches) document.apply(patch);
    const SceneDesc desc = document.parse();
    // Reading the scene file is part of the load (an imported pbrt file
    // with inline meshes takes seconds).
    const double sceneSeconds = std::chrono::duration<double>(Clock::now() - started).count();
    const std::vector<fs::path> outputs = outputFiles(job, desc);
    JobResult result;
    result.integrator = desc.render.integrator;
    // Distributed workers write nothing: only rank 0 checks the outputs.
    result.worker = distributed::role() == distributed::Role::Worker;
    const bool raster = job.algorithm == RenderAlgorithm::Raster;
    checkBeforeLoading(job, desc, outputs, result.worker);
    const PixelRect crop = cropWindow(job, desc);
    if (job.stats && !result.worker) checkStatsPath(*job.stats);
    // The sample offset decides the pixels too: regions of different sample
    // ranges must not be assembled, nor one skipped for the other.
    const std::string image = imageFingerprint(document);
    const std::string fingerprint =
        image + (job.sampleOffset ? ", samples from " + std::to_string(*job.sampleOffset)
                                  : std::string());
    // Before anything heavy is loaded: only the scene file has been read.
    if (job.skipExisting && !result.worker &&
        outputsComplete(outputs, desc, crop, fingerprint, observer)) {
        result.skipped = true;
        return result;
    }
    {
        JobObserver::Start start{job.scene.string(), job.frame, desc.film.width,
                                 desc.film.height, crop, desc.render.spp, {}};
        for (const fs::path& out : outputs) start.outputs.push_back(out.string());
        observer.started(start);
        observer.passes(0, desc.render.spp);
    }

    BuildOptions build = job.build;
    if (raster) {
        build.accel = AccelKind::Naive;  // the rasterizer traces no rays: no BVH to build
    } else {
        build.bvhStarted = [&] { observer.begin("bvh", 1); };
        build.bvhProgress = [&](double f) { observer.fraction(f); };
    }
    const BuiltScene scene = buildScene(desc, build, &result.timings);
    result.timings.loadSeconds += sceneSeconds;
    const World& world = scene.world;
    if (!raster) observer.end();  // of the BVH phase
    result.shapeBytes = world.shapeMemoryBytes();
    result.bvhBytes = world.accel->memoryBytes();

    const Camera camera = buildCamera(scene.camera, desc.film.width, desc.film.height);
    const auto integrator =
        makeIntegrator(desc.render.integrator, world, buildIntegratorOptions(desc, camera));
    std::vector<AovKind> aovs = desc.film.aovs;
    if (desc.render.denoise)  // the denoiser's features, written as EXR layers too
        for (AovKind kind : {AovKind::Normal, AovKind::Depth, AovKind::Albedo, AovKind::Variance})
            if (std::find(aovs.begin(), aovs.end(), kind) == aovs.end()) aovs.push_back(kind);
    // Adaptive sampling writes how many samples each pixel took.
    if (desc.render.adaptiveThreshold > 0.0f && !raster &&
        std::find(aovs.begin(), aovs.end(), AovKind::Samples) == aovs.end())
        aovs.push_back(AovKind::Samples);
    Film film(desc.film.width, desc.film.height, crop, aovs);
    if (desc.render.denoise) film.keepHalves(static_cast<uint32_t>(job.sampleOffset.value_or(0)));
    if (desc.render.adaptiveThreshold > 0.0f && !raster) film.trackConvergence();
    if (raster) {
        rasterize(job, desc, world, camera, *integrator, film, observer, result);
    } else {
        rayTrace(job, desc, world, camera, *integrator, film,
                 checkpointFingerprint(image, crop, job.tileSize, job.sampleOffset), observer,
                 result);
        if (result.worker) return result;
    }

    OutputSettings output;
    output.exrFloat = desc.film.exrFloat;
    output.color = job.color;
    ImageMetadata metadata =
        imageMetadata(job, document, desc, scene.camera, camera, result.render, fingerprint);
    std::optional<std::vector<float>> denoised;
    if (desc.render.denoise && job.sampleOffset) {
        observer.note("--denoise with --sample-offset: the part keeps the sample halves; denoise "
                      "after strahl merge with strahl denoise");
    } else if (desc.render.denoise && result.render.completedPasses < 2) {
        observer.note("not denoised: every pixel needs at least 2 samples, the render stopped "
                      "after " + std::to_string(result.render.completedPasses));
    } else if (desc.render.denoise) {
        const auto denoiseStart = Clock::now();
        DenoiseSettings settings;
        settings.threads = job.build.threads;
        denoised = denoise(denoiseInputOf(film), settings, job.scene.string());
        const double seconds = secondsSince(denoiseStart);
        result.denoiseSeconds = seconds;
        metadata.extra["denoiser"] = "nfor";
        observer.note(concat("denoised (NFOR) in ", seconds, " s"));
    }
    for (const fs::path& out : outputs) {
        writeImage(film, out, output, metadata, denoised ? &*denoised : nullptr);
        observer.note("wrote " + out.string());
    }
    result.report = makeReport(job, desc, crop, outputs, result);
    result.report.totalSeconds = secondsSince(started);
    if (job.stats) {
        result.report.statsFile = job.stats->string();
        writeStatsFile(*job.stats, result.report);
    }
    observer.finished(result.report);
    return result;
}

}  // namespace strahl
