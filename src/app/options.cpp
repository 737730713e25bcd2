#include "options.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>

#include "strahl/core/error.h"
#include "strahl/film/film.h"
#include "strahl/integrator/integrator.h"
#include "strahl/raster/rasterizer.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::app {

namespace {

constexpr const char* kDescription =
    "strahl " STRAHL_VERSION " - an Embree-accelerated ray tracer.\n\n"
    "  strahl render SCENE.json -o image.exr -o image.png   render a scene\n"
    "  strahl info SCENE.json                                primitive counts, bounds, memory\n"
    "  strahl bench --out results.csv --plot cost.svg        Embree vs naive vs raster\n\n"
    "The scene format is documented in docs/scene-format.md, the options in docs/cli.md.\n"
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

}  // namespace

std::optional<int> parseOptions(int argc, char** argv, Options& o) {
    CLI::App app{kDescription, "strahl"};
    // A bad command line is one line like every other error (exit status 2).
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("strahl: error: ") + e.what() + "\n";
    });
    app.set_version_flag("--version", "strahl " STRAHL_VERSION);
    app.require_subcommand(1);

    CLI::App* render = app.add_subcommand("render", "Render a scene to one or more image files");
    render->add_option("scene", o.scene, "Scene file (JSON, see docs/scene-format.md)")
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
    std::string cropText;
    render->add_option("--crop", cropText,
                       "Render only pixels X0<=x<X1, Y0<=y<Y1 (y=0 at the top): X0,Y0,X1,Y1");
    render->add_option("--aov", o.aovs, "AOV written to EXR outputs: normal, depth, albedo "
                                        "(repeat; overrides film.aovs)")
        ->check(CLI::IsMember(std::vector<std::string>(aovNames().begin(), aovNames().end())));
    render->add_flag("--exr-float", o.exrFloat, "Write 32-bit float EXR channels instead of half");
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
    render->add_option("--ocio-config", o.color.configFile,
                       "OpenColorIO config for display outputs (default: $OCIO, else built-in)");
    render->add_option("--display", o.color.display, "OCIO display (built-in: sRGB)");
    render->add_option("--view", o.color.view, "OCIO view (built-in: Standard, Filmic, Raw)");

    CLI::App* info = app.add_subcommand("info", "Print primitive counts, bounds and memory");
    info->add_option("scene", o.scene, "Scene file")->required();

    CLI::App* bench = addBenchCommand(app, o.bench);

    try {
        app.parse(argc, argv);
        if (!cropText.empty()) {
            const std::string problem = parseCrop(cropText, o.crop);
            if (!problem.empty()) throw CLI::ValidationError("--crop", problem);
        }
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);  // prints help, version or the error
        return code == 0 ? 0 : 2;
    }
    o.command = render->parsed() ? Command::Render
                : bench->parsed()  ? Command::Bench
                                   : Command::Info;
    if (packets == "16") o.packets = PacketMode::Packet16;
    else if (packets == "8") o.packets = PacketMode::Packet8;
    else if (packets == "single") o.packets = PacketMode::Single;
    return std::nullopt;
}

}  // namespace strahl::app
