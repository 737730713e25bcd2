// `strahl render`: the command line as a RenderJob (the library runs it), its
// progress and events shown by a ProgressReporter, and the closing lines.

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "progress_reporter.h"
#include "scene_loading.h"
#include "strahl/core/process_memory.h"
#include "strahl/distributed/distributed.h"
#include "strahl/job/interrupts.h"
#include "strahl/job/render_job.h"
#include "strahl/meshio/mesh_file.h"

namespace strahl::app {

namespace {

RenderJob renderJob(const Options& o) {
    RenderJob job;
    job.scene = o.scene;
    job.defines = sceneDefines(o);
    job.patches = scenePatches(o);
    // -o is not a patch: its names are relative to the current folder, and
    // where an image goes is not part of what it is.
    for (const std::string& out : o.outputs) job.outputs.emplace_back(out);
    job.frame = o.frame;
    job.crop = o.crop;
    job.cropOrigin = o.cropArgument;
    job.algorithm = o.algorithm == "raster" ? RenderAlgorithm::Raster : RenderAlgorithm::RayTrace;
    job.build = buildOptions(o);
    job.build.accel = accelFromName(o.accel);
    job.tileSize = o.tileSize;
    job.packets = o.packets;
    job.color = o.color;
    if (o.checkpoint) job.checkpoint = *o.checkpoint;
    job.checkpointInterval = o.checkpointInterval;
    if (o.resume) job.resume = *o.resume;
    job.timeLimit = o.timeLimit;
    job.sampleOffset = o.sampleOffset;
    job.distributed = o.distributed;
    job.skipExisting = o.skipExisting;
    if (o.stats) job.stats = *o.stats;
    job.quiet = o.quiet;
    return job;
}

std::string humanCount(double n) {
    char buf[32];
    if (n >= 1e9) std::snprintf(buf, sizeof buf, "%.2fG", n / 1e9);
    else if (n >= 1e6) std::snprintf(buf, sizeof buf, "%.2fM", n / 1e6);
    else if (n >= 1e3) std::snprintf(buf, sizeof buf, "%.1fk", n / 1e3);
    else std::snprintf(buf, sizeof buf, "%.0f", n);
    return buf;
}

// The summary and memory lines after a render (docs/cli.md).
void printSummary(const JobResult& r) {
    if (r.raster) {
        const RasterStats& raster = *r.raster;
        std::fprintf(stderr,
                     "summary: load %.2f s, raster %.2f s | %s triangles (%s in view), %s "
                     "fragments, %s pixels covered | %s, 1 spp, rasterized\n",
                     r.timings.loadSeconds, raster.seconds,
                     humanCount(double(raster.triangles)).c_str(),
                     humanCount(double(raster.trianglesInView)).c_str(),
                     humanCount(double(raster.fragments)).c_str(),
                     humanCount(double(raster.coveredPixels)).c_str(), r.integrator.c_str());
    } else {
        const RenderStats& stats = r.render;
        const double rays = static_cast<double>(stats.totalRays());
        std::fprintf(stderr,
                     "summary: load %.2f s, bvh %.2f s, render %.2f s, first pixel after %.2f s "
                     "| %s rays (%s camera, %s shadow, %s bounce), %.1f Mrays/s | %s, %d spp, "
                     "%s\n",
                     r.timings.loadSeconds, r.timings.bvhSeconds, stats.seconds,
                     r.timings.loadSeconds + r.timings.bvhSeconds + stats.firstTileSeconds,
                     humanCount(rays).c_str(), humanCount(double(stats.cameraRays)).c_str(),
                     humanCount(double(stats.shadowRays)).c_str(),
                     humanCount(double(stats.bounceRays)).c_str(),
                     stats.seconds > 0 ? rays / stats.seconds / 1e6 : 0.0, r.integrator.c_str(),
                     r.report.spp,
                     stats.packetWidth > 1
                         ? ("packets of " + std::to_string(stats.packetWidth)).c_str()
                         : "single rays");
    }
    std::fprintf(stderr, "memory: shapes %s, bvh %s, peak resident %s\n",
                 formatBytes(r.shapeBytes).c_str(), formatBytes(r.bvhBytes).c_str(),
                 formatBytes(peakResidentBytes()).c_str());
}

// The lines after the outputs are written, and the exit status.
int finish(const Options& o, const JobResult& r) {
    if (r.skipped || r.worker) return 0;
    const RenderStats& stats = r.render;
    const int spp = r.report.spp;
    if (stats.cancelled) {
        std::fprintf(stderr,
                     "strahl: interrupted by %s after %d of %d samples per pixel; the images "
                     "written are partial%s\n",
                     r.report.stopped.c_str(), stats.completedPasses, spp,
                     o.checkpoint ? " (resume with --resume)" : "");
        return r.report.exitStatus;  // 128 + the signal: the shell's convention
    }
    if (stats.stoppedEarly && !o.quiet)
        std::fprintf(stderr, "time limit reached: stopped after %d of %d samples per pixel\n",
                     stats.completedPasses, spp);
    if (!o.quiet) printSummary(r);
    return 0;
}

}  // namespace

int runRender(const Options& o) {
    // Distributed workers print nothing (rank 0 reports for the job).
    const bool json = o.jsonProgress && distributed::role() != distributed::Role::Worker;
    ProgressReporter progress(json ? ProgressReporter::Style::Json
                                   : ProgressReporter::defaultStyle(o.quiet),
                              o.quiet);
    try {
        if (o.quiet) setMeshWarningHandler([](const std::string&) {});
        return finish(o, runRenderJob(renderJob(o), progress));
    } catch (const std::exception& e) {
        // The JSON stream ends with an event whatever happens; main prints the message.
        progress.event("error", {{"message", e.what()}, {"exit_status", 1}});
        throw;
    }
}

}  // namespace strahl::app
