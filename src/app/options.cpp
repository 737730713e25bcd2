#include "options.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>

#include "image_files.h"
#include "strahl/job/frame_pattern.h"
#include "strahl/core/error.h"
#include "strahl/core/process_memory.h"
#include "strahl/film/film.h"
#include "strahl/integrator/integrator.h"
#include "strahl/raster/rasterizer.h"
#include "strahl/scene/scene_desc.h"
#include "strahl/scene/scene_document.h"

namespace strahl::app {

namespace {

constexpr const char* kDescription =
    "strahl " STRAHL_VERSION " - an Embree-accelerated ray tracer.\n\n"
    "  strahl render SCENE.json -o image.exr -o image.png   render a scene\n"
    "  strahl render scene.xml -D spp=64 -o image.exr        render a Mitsuba 3 scene\n"
    "  strahl convert scene.xml -o scene.json                 a Mitsuba 3 scene as strahl JSON\n"
    "  strahl render scene.pbrt -o image.exr                  render a pbrt-v4 scene\n"
    "  strahl info SCENE.json                                primitive counts, bounds, memory\n"
    "  strahl bench --out results.csv --plot cost.svg        Embree vs naive vs raster\n"
    "  strahl assemble r*.exr -o image.exr                   stitch --region renders\n"
    "  strahl merge part*.exr -o image.exr                   add up --sample-offset renders\n"
    "  strahl denoise noisy.exr -o clean.exr -o clean.png     denoise a --denoise render\n\n"
    "The scene format is documented in docs/scene-format.md (Mitsuba 3 scenes: docs/mitsuba.md,\n"
    "pbrt-v4 scenes: docs/pbrt.md),\n"
    "the options in docs/cli.md.\n"
    "Exit status: 0 success, 1 error (bad scene, mesh or output), 2 bad command line.";

// "--crop X0,Y0,X1,Y1" in pixels, half-open, y = 0 at the top.
std::string parseCrop(const std::string& text, std::optional<PixelRect>& crop) {
    PixelRect r;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &r.x0, &r.y0, &r.x1, &r.y1, &tail) != 4)
        return "--crop expects X0,Y0,X1,Y1 (four integers), got '" + text + "'";
    if (r.empty() || r.x0 < 0 || r.y0 < 0)
        return "--crop " + text + " is empty or negative (need 0 <= X0 < X1 and 0 <= Y0 < Y1)";
    crop = r;
    return {};
}

// "--region X0 Y0 X1 Y1": the same rectangle as --crop, as four arguments
// (the spelling farm managers' templates generate).
std::string parseRegion(const std::vector<std::string>& values, std::optional<PixelRect>& crop) {
    std::string text;
    for (const std::string& v : values) text += (text.empty() ? "" : " ") + v;
    int numbers[4] = {};
    for (size_t i = 0; i < 4; ++i) {
        char tail = 0;
        if (values.size() != 4 ||
            std::sscanf(values[i].c_str(), "%d%c", &numbers[i], &tail) != 1)
            return "--region expects X0 Y0 X1 Y1 (four integers), got '" + text + "'";
    }
    const PixelRect r{numbers[0], numbers[1], numbers[2], numbers[3]};
    if (r.empty() || r.x0 < 0 || r.y0 < 0)
        return "--region " + text + " is empty or negative (need 0 <= X0 < X1 and 0 <= Y0 < Y1)";
    crop = r;
    return {};
}

// Output names with '#' runs need --frame (docs/farm.md): an error on the
// command line itself, before anything is read.
std::string checkFramePatterns(const Options& o) {
    if (o.frame) return {};
    std::vector<std::pair<std::string, std::string>> files;
    for (const std::string& out : o.outputs) files.emplace_back("-o", out);
    if (o.stats) files.emplace_back("--stats", *o.stats);
    if (o.checkpoint) files.emplace_back("--checkpoint", *o.checkpoint);
    if (o.resume) files.emplace_back("--resume", *o.resume);
    for (const auto& [option, file] : files)
        if (hasFramePattern(file))
            return option + " " + file + ": the name has a '#' frame pattern but no --frame N "
                   "was given";
    return {};
}

// The BVH build and memory options that `render` and `info` share.
void addMemoryOptions(CLI::App& command, Options& o) {
    command
        .add_option("--bvh-quality", o.bvhQuality,
                    "Embree BVH build: low (Morton: fastest build), medium (binned SAH, "
                    "default) or high (spatial splits: fastest rays, slowest build)")
        ->check(CLI::IsMember({"low", "medium", "high"}));
    // A flag function, not a flag on the optional: it runs only when one of the
    // two is given (unset means "by scene size"); --no-compact counts -1.
    command.add_flag_function(
        "--compact,!--no-compact", [&o](std::int64_t count) { o.compact = count > 0; },
        "Embree's BVH layout. --compact: indexed triangles, about half the "
        "peak memory and a faster build, for rays 10-15% slower; --no-compact: "
        "the fastest rays. Default: compact above 4M stored triangles or with "
        "--memory-limit, else not (docs/memory.md)");
    command.add_flag_function(
        "--quads,!--no-quads", [&o](std::int64_t count) { o.quads = count > 0; },
        "Trace meshes whose triangles come in pairs sharing an edge (quad faces, "
        "tessellated grids) as Embree quads: the same surface in half the "
        "primitives. --quads: every mesh at least half paired; --no-quads: none. "
        "Default: meshes of 512K triangles or more, 90% paired, where quads "
        "save a fifth of the BVH memory and trace faster (docs/geometry.md)");
    command.add_option("--memory-limit", o.memoryLimit,
                       "Stop with a clear error (exit 1) instead of being killed when loading "
                       "the scene or building the BVH would take the process past SIZE of "
                       "resident memory: 8G, 512M, 1.5G (binary units) or bytes")
        ->check([](const std::string& text) {
            try {
                parseByteSize(text, "--memory-limit");
                return std::string();
            } catch (const Error& e) {
                return std::string(e.what());
            }
        });
}

// --set POINTER=VALUE (repeatable): any scene setting, as a patch of the scene
// document (docs/cli.md#scene-patches). Malformed arguments are usage errors.
void addSetOption(CLI::App& command, Options& o) {
    command
        .add_option("--set", o.sets,
                    "Set any scene key before parsing, by JSON pointer: --set /render/spp=64, "
                    "--set /camera/fov=30, --set /film/aovs='[\"normal\"]' (repeat; after the "
                    "other flags, later wins; VALUE is JSON, or else a string)")
        ->type_name("POINTER=VALUE")
        ->check([](const std::string& argument) {
            try {
                parseSetArgument(argument);
                return std::string();
            } catch (const Error& e) {
                // "--set ARG: why" -> "'ARG': why" (CLI11 puts "--set: " in front).
                const std::string message = e.what(), origin = "--set " + argument + ": ";
                return "'" + argument + "': " + message.substr(message.rfind(origin, 0) == 0 ? origin.size() : 0);
            }
        });
}

// -D NAME=VALUE (repeatable): the value of a Mitsuba scene's <default name=NAME>
// parameter, as Mitsuba's own -D (docs/mitsuba.md).
void addDefineOption(CLI::App& command, Options& o) {
    command
        .add_option("-D,--define", o.defines,
                    "Mitsuba 3 scenes: give the <default> parameter NAME the value VALUE, as "
                    "mitsuba -D does (repeat)")
        ->type_name("NAME=VALUE")
        ->check([](const std::string& argument) {
            const size_t equals = argument.find('=');
            if (equals == std::string::npos || equals == 0)
                return "'" + argument + "': expected NAME=VALUE, such as spp=64";
            return std::string();
        });
}

}  // namespace

SceneDefines sceneDefines(const Options& o) {
    SceneDefines defines;
    for (const std::string& d : o.defines) {
        const size_t equals = d.find('=');
        defines[d.substr(0, equals)] = d.substr(equals + 1);  // a later -D wins
    }
    return defines;
}

std::optional<int> parseOptions(int argc, char** argv, Options& o) {
    CLI::App app{kDescription, "strahl"};
    // A bad command line is one line like every other error (exit status 2).
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("strahl: error: ") + e.what() + "\n";
    });
    app.set_version_flag("--version", "strahl " STRAHL_VERSION);
    app.require_subcommand(1);

    CLI::App* render = app.add_subcommand("render", "Render a scene to one or more image files");
    render->add_option("scene", o.scene,
                       "Scene file: strahl JSON (docs/scene-format.md), Mitsuba 3 XML "
                       "(.xml, docs/mitsuba.md) or pbrt-v4 (.pbrt, docs/pbrt.md)")
        ->required();
    render->add_option("-o,--output", o.outputs,
                       "Output image; repeat for several. .exr is scene-linear with AOVs; "
                       ".png/.jpg/.tif go through the OCIO display transform. "
                       "Default: the scene's film.outputs");
    render->add_option("--width", o.width, "Image width in pixels (overrides film.width)")
        ->check(CLI::Range(1, kMaxFilmSide));
    render->add_option("--height", o.height, "Image height in pixels (overrides film.height)")
        ->check(CLI::Range(1, kMaxFilmSide));
    render->add_option("--spp", o.spp, "Samples per pixel (overrides render.spp)")
        ->check(CLI::Range(1, 65536));
    render->add_option("--threads", o.threads, "Worker threads; 0 = all cores (default)")
        ->check(CLI::Range(0, 4096));
    std::string integratorHelp = "Integrator (overrides render.integrator):";
    for (std::string_view n : integratorNames()) integratorHelp += " " + std::string(n);
    render->add_option("--integrator", o.integrator, integratorHelp);
    render->add_option("--seed", o.seed, "Random seed (overrides render.seed)");
    render->add_option("--max-depth", o.maxDepth,
                       "Path tracer: maximum bounces (overrides render.max_depth, default 8)")
        ->check(CLI::Range(0, 1024));
    render->add_option("--clamp-direct", o.clampDirect,
                       "Path tracer: the most one sample's direct light (after one reflection) "
                       "may bring, largest channel; cuts fireflies, biased; 0 = off (overrides "
                       "render.clamp_direct)")
        ->check(CLI::Range(0.0f, 1e30f));
    render->add_option("--clamp-indirect", o.clampIndirect,
                       "Path tracer: the same for indirect light (two or more reflections); 0 = "
                       "off (overrides render.clamp_indirect)")
        ->check(CLI::Range(0.0f, 1e30f));
    render->add_option("--filter-glossy", o.filterGlossy,
                       "Path tracer: Cycles' filter glossy: after diffuse or rough bounces, "
                       "glossy and sharp lobes are roughened (more, the larger the value: 1 is "
                       "Cycles' usual) so caustic fireflies go; biased; 0 = off (overrides "
                       "render.filter_glossy)")
        ->check(CLI::Range(0.0f, 1e30f));
    render->add_option("--adaptive-threshold", o.adaptiveThreshold,
                       "Adaptive sampling: a pixel stops once its noise (the relative standard "
                       "error of its mean, absolute below 0.1, over its 3x3 neighbourhood) is "
                       "below this; --spp is then the most a pixel takes, and the samples AOV "
                       "counts them; 0.05 is a good start, 0 = off (sets "
                       "render.adaptive.threshold; docs/adaptive.md)")
        ->check(CLI::Range(0.0f, 1.0f));
    render->add_option("--adaptive-min-samples", o.adaptiveMinSamples,
                       "Adaptive sampling: samples every pixel takes before it may stop "
                       "(default 16; sets render.adaptive.min_samples)")
        ->check(CLI::Range(2, 65536));
    render->add_flag("--denoise", o.denoiseRender,
                     "Write the NFOR-denoised beauty as the main image (and to PNG/JPEG/TIFF); "
                     "EXRs keep the noisy beauty, the features and the even/odd sample halves as "
                     "layers. Needs at least 2 spp; a --sample-offset part keeps the halves for "
                     "strahl merge, then strahl denoise (sets render.denoise; docs/denoising.md)");
    std::string cropText;
    render->add_option("--crop", cropText,
                       "Render only pixels X0<=x<X1, Y0<=y<Y1 (y=0 at the top): X0,Y0,X1,Y1");
    std::vector<std::string> regionValues;
    render->add_option("--region", regionValues,
                       "Render only this pixel rectangle, X0<=x<X1, Y0<=y<Y1 (y=0 at the top): "
                       "the four integers X0 Y0 X1 Y1; same as --crop. Stitch the regions' EXRs "
                       "with strahl assemble")
        ->expected(4)
        ->type_name("INT");
    render->add_option("--aov", o.aovs, "AOV written to EXR outputs: normal, depth, albedo "
                                        "(repeat; overrides film.aovs)")
        ->check(CLI::IsMember(std::vector<std::string>(aovNames().begin(), aovNames().end())));
    render->add_flag("--exr-float", o.exrFloat, "Write 32-bit float EXR channels instead of half");
    addSetOption(*render, o);
    addDefineOption(*render, o);
    render->add_flag("-q,--quiet", o.quiet, "No progress display, summary or mesh warnings");
    std::string packets = "auto";
    render->add_option("--packets", packets,
                       "Camera-ray tracing: auto (16-wide with AVX-512, else 8), 16, 8, or single "
                       "(one ray at a time, for comparison)")
        ->check(CLI::IsMember({"auto", "16", "8", "single"}));
    render->add_option("--accel", o.accel,
                       "Accelerator: embree (BVH, default) or naive (tests every primitive for "
                       "every ray: the reference the BVH is checked and benchmarked against)")
        ->check(CLI::IsMember({"embree", "naive"}));
    std::string algorithmHelp =
        "raytrace (image order, default) or raster (object order: a z-buffer rasterizer for "
        "triangle meshes, 1 spp, integrators";
    for (std::string_view n : rasterIntegratorNames()) algorithmHelp += " " + std::string(n);
    render->add_option("--algorithm", o.algorithm, algorithmHelp + "; see docs/rasterizer.md)")
        ->check(CLI::IsMember({"raytrace", "raster"}));
    addMemoryOptions(*render, o);
    render->add_option("--tile", o.tileSize, "Tile size in pixels (default 32)")
        ->check(CLI::Range(4, 4096));
    render->add_option("--checkpoint", o.checkpoint,
                       "Write the render's state to FILE after a sample pass every "
                       "--checkpoint-interval seconds, on SIGINT/SIGTERM and at the end; continue "
                       "it with --resume FILE (docs/reliability.md)");
    render->add_option("--checkpoint-interval", o.checkpointInterval,
                       "Seconds between checkpoints (default 60)")
        ->check(CLI::Range(0.0, 1e9));
    render->add_option("--resume", o.resume,
                       "Continue the render saved in this checkpoint; the result is bit-identical "
                       "to an uninterrupted render (same scene and settings required)");
    render->add_option("--time-limit", o.timeLimit,
                       "Stop after the first whole sample pass that ends past this many seconds "
                       "of rendering, and write the image (exit 0; metadata says how many samples)")
        ->check(CLI::Range(0.0, 1e9));
    // Sample indices are 31-bit: the offset leaves room for the largest --spp (65536).
    render->add_option("--sample-offset", o.sampleOffset,
                       "Render sample indices K .. K+spp-1 of every pixel: one part of a render "
                       "split across machines; the EXR carries exact sums, and strahl merge adds "
                       "the parts into exactly the image of one render (docs/farm.md)")
        ->check(CLI::Range(0, 2147483647 - 65536))
        ->type_name("K");
    render->add_flag("--distributed", o.distributed,
                     "Render over MPI: mpirun -np N strahl render ... --distributed; rank 0 "
                     "schedules tiles and writes the outputs, the other N-1 ranks render; the "
                     "image is bit-identical to a local render (docs/distributed.md)");
    render->add_option("--frame", o.frame,
                       "Frame number: fills every run of '#' in output, --stats and checkpoint "
                       "names, zero-padded to the run's length (beauty.####.exr -> "
                       "beauty.0042.exr), and is stored in the EXR metadata; the scene itself "
                       "does not change (docs/farm.md)")
        ->check(CLI::Range(0, 999999999));
    render->add_flag("--skip-existing", o.skipExisting,
                     "If every output already exists and is complete (not marked partial), "
                     "print one line and exit 0 without rendering");
    std::string progressFormat = "text";
    render->add_option("--progress-format", progressFormat,
                       "text (progress bar or lines on stderr, default) or json (one JSON object "
                       "per line on stdout: start, progress, pass, done, ... see docs/cli.md)")
        ->check(CLI::IsMember({"text", "json"}));
    render->add_option("--stats", o.stats,
                       "Write the run's statistics (settings, timings, rays, peak memory, "
                       "outputs, exit status) to this JSON file at the end, also after an "
                       "interrupt or a time limit");
    addDisplayOptions(*render, o.color);

    CLI::App* info = app.add_subcommand("info", "Print primitive counts, bounds and memory");
    info->add_option("scene", o.scene, "Scene file")->required();
    addSetOption(*info, o);
    addDefineOption(*info, o);
    addMemoryOptions(*info, o);

    CLI::App* convert = app.add_subcommand(
        "convert", "Write a scene (a Mitsuba 3 .xml, a pbrt-v4 .pbrt) as the strahl JSON scene it imports as");
    convert->add_option("scene", o.scene, "Scene file (Mitsuba 3 .xml, pbrt-v4 .pbrt or strahl JSON)")->required();
    convert->add_option("-o,--output", o.convertOutput,
                        "The strahl JSON scene to write; its file names are relative to its "
                        "folder")
        ->required();
    addSetOption(*convert, o);
    addDefineOption(*convert, o);
    convert->add_flag("-q,--quiet", o.quiet, "No line saying where the scene went");

    CLI::App* bench = addBenchCommand(app, o.bench);
    CLI::App* assemble = addAssembleCommand(app, o.assemble);
    CLI::App* merge = addMergeCommand(app, o.merge);
    CLI::App* denoise = addDenoiseCommand(app, o.denoise);

    try {
        app.parse(argc, argv);
        if (!cropText.empty() && !regionValues.empty())
            throw CLI::ValidationError("--region",
                                       "--region and --crop name the same rectangle: give one");
        if (!cropText.empty()) {
            const std::string problem = parseCrop(cropText, o.crop);
            if (!problem.empty()) throw CLI::ValidationError("--crop", problem);
            o.cropArgument = "--crop " + cropText;
        }
        if (!regionValues.empty()) {
            const std::string problem = parseRegion(regionValues, o.crop);
            if (!problem.empty()) throw CLI::ValidationError("--region", problem);
            o.cropArgument = "--region " + regionValues[0] + " " + regionValues[1] + " " +
                             regionValues[2] + " " + regionValues[3];
        }
        if (render->parsed()) {
            const std::string problem = checkFramePatterns(o);
            if (!problem.empty()) throw CLI::ValidationError("--frame", problem);
        }
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);  // prints help, version or the error
        return code == 0 ? 0 : 2;
    }
    o.command = render->parsed()     ? Command::Render
                : convert->parsed()  ? Command::Convert
                : bench->parsed()    ? Command::Bench
                : assemble->parsed() ? Command::Assemble
                : merge->parsed()    ? Command::Merge
                : denoise->parsed()  ? Command::Denoise
                                     : Command::Info;
    o.jsonProgress = progressFormat == "json";
    if (packets == "16") o.packets = PacketMode::Packet16;
    else if (packets == "8") o.packets = PacketMode::Packet8;
    else if (packets == "single") o.packets = PacketMode::Single;
    return std::nullopt;
}

}  // namespace strahl::app
