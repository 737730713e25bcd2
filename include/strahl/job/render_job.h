#pragma once
// One render, from a scene file to image files: read the scene and apply its
// patches, check what can be checked before anything heavy is loaded, skip
// if the outputs are already there (skipExisting), load the meshes and build
// the BVH, render (ray traced, locally or over MPI, or rasterized), write
// checkpoints, stop at the time limit or on SIGINT/SIGTERM, write the images
// with their metadata and the statistics file. `strahl render` turns its
// command line into a RenderJob and shows what the JobObserver hears; a
// script or test can run one the same way (as pbrt's cmd/pbrt.cpp hands its
// options to cpu/render.cpp).

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "strahl/core/pixel_rect.h"
#include "strahl/film/display_transform.h"
#include "strahl/job/run_report.h"
#include "strahl/raster/rasterizer.h"
#include "strahl/render/progress.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_document.h"

namespace strahl {

// Ray tracing (the path tracer and the other integrators, with a BVH) or
// object-order rasterization of the first hits (docs/rasterizer.md).
enum class RenderAlgorithm { RayTrace, Raster };
const char* algorithmName(RenderAlgorithm algorithm);  // "raytrace" | "raster"

struct RenderJob {
    std::filesystem::path scene;  // strahl JSON, or another format's (scene_document.h)
    SceneDefines defines;         // -D: a Mitsuba scene's <default> parameters
    // Applied in order to the scene document before it is parsed: every
    // scene setting a command line changes (docs/cli.md#scene-patches).
    std::vector<ScenePatch> patches;
    // When not empty, the images to write instead of the scene's
    // film.outputs, relative to the current folder (not the scene's).
    std::vector<std::filesystem::path> outputs;
    // Fills the '#' runs of every file name (frame_pattern.h) and is written
    // into the metadata; a name with a '#' run and no frame is an error.
    std::optional<int> frame;
    // The pixels to render, within the film; `cropOrigin` names it in
    // messages ("--crop 0 0 8 8"). None: the whole film.
    std::optional<PixelRect> crop;
    std::string cropOrigin;

    RenderAlgorithm algorithm = RenderAlgorithm::RayTrace;
    // Loading and the BVH; build.threads is also the render's thread count
    // (0: every core this process may use). The job sets the callbacks.
    BuildOptions build;
    int tileSize = 32;
    PacketMode packets = PacketMode::Auto;
    ColorSettings color;  // display outputs (PNG, JPEG, TIFF) and a config to check

    // Ray tracing only (docs/reliability.md): the film is written to
    // `checkpoint` every checkpointInterval seconds and at the end; `resume`
    // continues a checkpoint of the same render; rendering stops after the
    // first whole sample pass that ends past timeLimit seconds.
    std::optional<std::filesystem::path> checkpoint;
    double checkpointInterval = 60.0;
    std::optional<std::filesystem::path> resume;
    std::optional<double> timeLimit;
    // A part of a render split by sample ranges (docs/farm.md): sample
    // indices sampleOffset .. sampleOffset + spp - 1.
    std::optional<int> sampleOffset;
    // Over the MPI ranks (docs/distributed.md): rank 0 gathers and writes, a
    // worker renders the tiles it is given and writes nothing.
    bool distributed = false;
    // Return at once, writing nothing, if every output exists, is complete
    // and has this render's fingerprint (existing_outputs.h).
    bool skipExisting = false;
    std::optional<std::filesystem::path> stats;  // the RunReport as JSON
    bool quiet = false;  // the distributed scheduler prints no summary line
};

// What a job reports while it runs. The progress of its long phases comes as
// a ProgressSink ("bvh": 1 unit, with fraction(); "render": tiles x passes;
// "raster": tiles); the rest through the calls below, on the calling thread.
// Every call has an empty default, so an observer overrides what it shows.
class JobObserver : public ProgressSink {
public:
    struct Start {
        std::string scene;
        std::optional<int> frame;
        int width = 0, height = 0;  // the film
        PixelRect region;           // the pixels rendered
        int spp = 0;
        std::vector<std::string> outputs;
    };

    void begin(const std::string&, uint64_t) override {}
    void advance(uint64_t) override {}
    void end() override {}
    // The BVH build's progress, 0..1.
    virtual void fraction(double) {}
    // The scene is read and checked; nothing heavy is loaded yet.
    virtual void started(const Start&) {}
    // Samples per pixel: `done` of `total` (at the start and after a resume),
    // then passDone after every finished sample pass.
    virtual void passes(int /*done*/, int /*total*/) {}
    virtual void passDone(int /*done*/) {}
    // skipExisting found every output complete: nothing was rendered.
    virtual void skipped(const std::vector<std::string>& /*outputs*/) {}
    // One line for a log: an output written, a checkpoint resumed, why an
    // existing output is rendered again.
    virtual void note(const std::string&) {}
    // The images (and stats file) are written; `report` is what they say.
    virtual void finished(const RunReport&) {}
};

struct JobResult {
    bool skipped = false;   // skipExisting: nothing was rendered or written
    bool worker = false;    // a distributed worker: it wrote nothing
    RunReport report;       // also what the stats file holds; exitStatus is the process's
    RenderStats render;     // ray tracing (raster: only seconds)
    std::optional<RasterStats> raster;
    BuildTimings timings;
    std::string integrator;  // the scene's, after patches
    size_t shapeBytes = 0, bvhBytes = 0;  // the World's memory
    double denoiseSeconds = 0.0;          // render.denoise: the denoiser's time
};

// Runs the job. Throws strahl::Error naming the file and place for anything
// the user must fix (before any output is written, except the checkpoint of
// an interrupted render). A render stopped by SIGINT/SIGTERM returns
// normally with report.stopped set and report.exitStatus = 128 + signal; its
// images are written and marked partial.
JobResult runRenderJob(const RenderJob& job, JobObserver& observer);

}  // namespace strahl
