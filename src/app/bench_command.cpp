#include "bench_command.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <vector>

#include "strahl/benchmark/bench_report.h"
#include "strahl/benchmark/bench_scene.h"
#include "strahl/benchmark/bench_suite.h"
#include "strahl/benchmark/path_bench.h"
#include "strahl/core/error.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::app {

namespace {

namespace fs = std::filesystem;

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> items;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        if (!item.empty()) items.push_back(item);
    }
    return items;
}

// Runs `check` on an output file given with `option`, naming the option in
// its message.
void checkOutput(const char* option, const std::string& file,
                 void (*check)(const std::filesystem::path&)) {
    if (file.empty()) return;
    try {
        check(file);
    } catch (const Error& e) {
        fail(option, " ", e.what());
    }
}

// The repository's scenes folder: --scenes, else ./scenes when it holds the
// Cornell box (run from the repository root), else the scenes folder of the
// source tree the executable was built in (<source>/<build>/bin/strahl).
fs::path scenesFolder(const std::string& given) {
    if (!given.empty()) return given;
    const fs::path here = "scenes";
    std::error_code ec;
    if (fs::is_regular_file(here / "default.json", ec)) return here;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path source = exe.parent_path().parent_path().parent_path() / "scenes";
        if (fs::is_regular_file(source / "default.json", ec)) return source;
    }
    return here;  // pathBenchFiles names it in its error
}

}  // namespace

CLI::App* addBenchCommand(CLI::App& app, BenchCommandOptions& o) {
    CLI::App* bench = app.add_subcommand(
        "bench",
        "Benchmark Embree against the naive tracer and the rasterizer on a ladder of generated "
        "meshes and on real models (see docs/benchmarks.md)");
    bench->add_option("--ladder", o.ladder,
                      "Generated mesh sizes in triangles, comma-separated (1000 or 1e3), or none. "
                      "Default 1e2,1e3,1e4,1e5,1e6,1e7");
    bench->add_option("--models", o.models,
                      "Real models from the data folder, comma-separated, 'all' or 'none'. "
                      "Default: all, if the data folder exists");
    bench->add_option("--data", o.data,
                      "The shared data folder (default $STRAHL_DATA, else ../shared/data)");
    bench->add_option("--resolution", o.resolution, "Image side in pixels (default 512)")
        ->check(CLI::Range(1, kMaxFilmSide));
    bench->add_option("--threads", o.threads, "Worker threads; 0 = all cores (default)")
        ->check(CLI::Range(0, 4096));
    bench->add_option("--repeats", o.repeats,
                      "Passes per Embree figure, the best kept (default 3)")
        ->check(CLI::Range(1, 100));
    bench->add_option("--naive-budget", o.naiveBudget,
                      "Triangle tests the naive tracer may spend per scene; its ray sample is "
                      "budget / triangles rays (default 2e9)")
        ->check(CLI::Range(1.0, 1e15));
    bench->add_flag("--no-raster", o.noRaster, "Do not time the rasterizer");
    bench->add_option("--out", o.out, "Write the results as .csv or .json");
    bench->add_option("--plot", o.plot, "Write the log-log plot of cost per ray as .svg");
    bench->add_option("--path", o.path,
                      "Path-trace the repository's scenes, comma-separated (cornell, sponza), "
                      "or none. Default cornell,sponza");
    // 65536: the scene format's own limit on render.spp.
    bench->add_option("--path-spp", o.pathSpp, "Samples per pixel of the path scenes (default 16)")
        ->check(CLI::Range(1, 65536));
    bench->add_option("--scenes", o.scenes,
                      "The repository's scenes folder (default ./scenes, else the source tree "
                      "of the executable)");
    bench->add_flag("-q,--quiet", o.quiet, "No progress lines");
    return bench;
}

int runBench(const BenchCommandOptions& o) {
    std::vector<size_t> ladder;
    if (o.ladder != "none") {
        for (const std::string& size : splitList(o.ladder)) ladder.push_back(parseBenchSize(size));
    }
    fs::path data = o.data;
    if (data.empty()) {
        const char* env = std::getenv("STRAHL_DATA");
        data = env && *env ? fs::path(env) : fs::path("../shared/data");
    }
    std::vector<std::string> models;
    std::error_code ec;
    if (o.models.empty()) {
        if (fs::is_directory(data, ec))
            models = {"all"};
        else if (!o.quiet)
            std::fprintf(stderr, "strahl: note: no data folder at %s: real models skipped "
                                 "(give --data DIR)\n", data.string().c_str());
    } else if (o.models != "none") {
        models = splitList(o.models);
    }
    const std::vector<BenchSceneSpec> scenes = benchScenes(ladder, models, data);
    PathBenchOptions pathOptions;
    pathOptions.scenes = o.path == "none" ? std::vector<std::string>{} : splitList(o.path);
    pathOptions.scenesDir = scenesFolder(o.scenes);
    pathOptions.resolution = o.resolution;
    pathOptions.spp = o.pathSpp;
    pathOptions.threads = o.threads;
    pathBenchFiles(pathOptions);  // unknown names and missing scene files fail here
    if (scenes.empty() && pathOptions.scenes.empty())
        fail("bench: nothing to measure (--ladder none, --models none and --path none)");
    if (scenes.empty() && !o.plot.empty())
        fail("--plot: the plot shows the ladder and the models: there are none to plot");
    // The output files are checked before hours of measuring, not after.
    checkOutput("--out", o.out, &checkBenchResultsFile);
    checkOutput("--plot", o.plot, &checkBenchPlotFile);

    BenchOptions options;
    options.resolution = o.resolution;
    options.threads = o.threads;
    options.repeats = o.repeats;
    options.naiveBudget = o.naiveBudget;
    options.raster = !o.noRaster;

    const auto status = [&](const std::string& what) {
        if (!o.quiet) std::fprintf(stderr, "bench: %s\n", what.c_str());
    };
    if (o.quiet) setMeshWarningHandler([](const std::string&) {});  // as `strahl render -q`
    std::vector<BenchRow> rows;
    for (const BenchSceneSpec& spec : scenes) rows.push_back(runBenchScene(spec, options, status));
    const std::vector<PathBenchRow> pathRows = runPathBench(pathOptions, status);

    const BenchFits fits = fitBench(rows);
    if (!rows.empty()) {
        std::printf("strahl bench: %dx%d camera rays per scene, %d threads (0 = all), best of %d\n",
                    o.resolution, o.resolution, o.threads, o.repeats);
        printBenchTable(stdout, rows, fits);
    }
    if (!pathRows.empty()) {
        if (!rows.empty()) std::printf("\n");
        std::printf("strahl bench --path: %dx%d, %d spp, max depth %d, %d threads (0 = all), "
                    "one render per scene\n",
                    pathOptions.resolution, pathOptions.resolution, pathOptions.spp,
                    pathOptions.maxDepth, o.threads);
        printPathBenchTable(stdout, pathRows);
    }
    if (!o.out.empty()) {
        writeBenchResults(o.out, rows, fits, options, pathRows, pathOptions);
        std::printf("wrote %s\n", o.out.c_str());
        std::string ext = fs::path(o.out).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(),
                       [](unsigned char c) { return char(std::tolower(c)); });
        if (!pathRows.empty() && ext != ".json")
            std::printf("note: the path rows are not in the CSV (other columns): use --out "
                        "FILE.json\n");
    }
    if (!o.plot.empty()) {
        writeBenchPlot(o.plot, rows, fits);
        std::printf("wrote %s\n", o.plot.c_str());
    }
    return 0;
}

}  // namespace strahl::app
