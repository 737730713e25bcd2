#pragma once
// The command line of strahl: the usage text and the Options it fills. No
// rendering logic lives here (render_command.cpp turns Options into a
// RenderJob, which the library runs).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "assemble_command.h"
#include "bench_command.h"
#include "denoise_command.h"
#include "merge_command.h"
#include "strahl/core/pixel_rect.h"
#include "strahl/film/display_transform.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene_document.h"

namespace strahl::app {

enum class Command { None, Render, Info, Convert, Bench, Assemble, Merge, Denoise };

struct Options {
    Command command = Command::None;
    std::string scene;
    // render
    std::vector<std::string> outputs;  // overrides the scene's film.outputs
    std::optional<int> width, height, spp, threads, maxDepth;
    std::optional<float> clampDirect, clampIndirect, filterGlossy;
    std::optional<float> adaptiveThreshold;  // --adaptive-threshold
    std::optional<int> adaptiveMinSamples;   // --adaptive-min-samples
    bool denoiseRender = false;  // --denoise
    std::optional<std::string> integrator;
    std::optional<uint64_t> seed;
    std::optional<PixelRect> crop;  // from --crop or --region (the farm's spelling)
    std::string cropArgument;        // the option as given ("--region 0 0 8 8"), for messages
    std::vector<std::string> aovs;  // overrides film.aovs when given
    bool exrFloat = false;
    std::vector<std::string> sets;  // --set POINTER=VALUE: scene patches, after the flags above
    std::vector<std::string> defines;  // -D NAME=VALUE: a Mitsuba scene's <default> parameters
    std::string convertOutput;         // convert: the strahl JSON scene to write
    bool quiet = false;
    PacketMode packets = PacketMode::Auto;
    int tileSize = 32;
    std::string accel = "embree";  // embree | naive
    // render and info: Embree's BVH build (docs/memory.md)
    std::string bvhQuality = "medium";       // low | medium | high
    std::optional<bool> compact;             // --compact/--no-compact; unset: by scene size (useCompactBvh)
    std::optional<bool> quads;               // --quads/--no-quads; unset: by mesh (QuadPolicy::Auto)
    std::optional<std::string> memoryLimit;  // e.g. "8G": a clean stop instead of a kill
    std::string algorithm = "raytrace";  // raytrace | raster
    ColorSettings color;
    std::optional<std::string> checkpoint;  // file written every checkpointInterval s and at the end
    double checkpointInterval = 60.0;
    std::optional<std::string> resume;      // checkpoint to continue from
    std::optional<double> timeLimit;        // seconds of rendering; stops at a whole sample pass
    // sample splitting (docs/farm.md): render sample indices K .. K+spp-1
    std::optional<int> sampleOffset;
    bool distributed = false;               // render over MPI ranks (docs/distributed.md)
    // farm (docs/farm.md)
    std::optional<int> frame;               // fills the '#' runs of output names; metadata only
    bool skipExisting = false;              // exit 0 at once if every output is complete
    bool jsonProgress = false;              // --progress-format json: JSON lines on stdout
    std::optional<std::string> stats;       // statistics JSON written at the end
    // bench
    BenchCommandOptions bench;
    // assemble
    AssembleOptions assemble;
    // merge
    MergeOptions merge;
    // denoise
    DenoiseOptions denoise;
};

// The -D arguments as a map (a later one for the same name wins).
SceneDefines sceneDefines(const Options& options);

// Parses argv. Returns an exit code to stop with (0 after --help/--version,
// 2 after a usage error, with the message printed), or nullopt to go on.
std::optional<int> parseOptions(int argc, char** argv, Options& options);

}  // namespace strahl::app
