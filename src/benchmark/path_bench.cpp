#include "strahl/benchmark/path_bench.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench_clock.h"
#include "strahl/core/error.h"
#include "strahl/film/film.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"

namespace strahl {

namespace {

namespace fs = std::filesystem;
using bench_detail::Clock;
using bench_detail::secondsSince;

// Collects every string under a "file" key, at any depth: the mesh, patch and
// image files a scene names (scene-format.md), relative to its folder.
void collectFiles(const nlohmann::json& node, std::vector<std::string>& files) {
    if (node.is_object()) {
        for (const auto& [key, value] : node.items()) {
            if (key == "file" && value.is_string())
                files.push_back(value.get<std::string>());
            else
                collectFiles(value, files);
        }
    } else if (node.is_array()) {
        for (const nlohmann::json& value : node) collectFiles(value, files);
    }
}

// The first file the scene names that does not exist, or empty. A scene that
// is not valid JSON has no missing files here: parseSceneFile reports it.
fs::path firstMissingFile(const fs::path& sceneFile) {
    std::ifstream in(sceneFile, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    const nlohmann::json document =
        nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false,
                              /*ignore_comments=*/true);
    if (document.is_discarded()) return {};
    std::vector<std::string> files;
    collectFiles(document, files);
    std::error_code ec;
    for (const std::string& name : files) {
        const fs::path file = (sceneFile.parent_path() / name).lexically_normal();
        if (!fs::exists(file, ec)) return file;
    }
    return {};
}

std::string knownNames() {
    std::string known;
    for (const PathBenchScene& s : pathBenchScenes()) {
        if (!known.empty()) known += ", ";
        known += s.name;
    }
    return known;
}

}  // namespace

std::span<const PathBenchScene> pathBenchScenes() {
    static constexpr std::array<PathBenchScene, 2> kScenes = {{
        {"cornell", "default.json"},
        {"sponza", "showcase/sponza.json"},
    }};
    return kScenes;
}

std::vector<fs::path> pathBenchFiles(const PathBenchOptions& options) {
    std::vector<fs::path> files;
    if (options.scenes.empty()) return files;
    std::error_code ec;
    if (!fs::is_directory(options.scenesDir, ec))
        fail("bench: the scenes folder ", options.scenesDir.string(),
             " does not exist (give --scenes DIR, or --path none)");
    for (const std::string& name : options.scenes) {
        const auto found = std::find_if(pathBenchScenes().begin(), pathBenchScenes().end(),
                                        [&](const PathBenchScene& s) { return name == s.name; });
        if (found == pathBenchScenes().end())
            fail("bench: unknown path scene '", name, "' (known: ", knownNames(), ", none)");
        const fs::path file = options.scenesDir / found->file;
        if (!fs::is_regular_file(file, ec))
            fail("bench: path scene '", name, "': no file ", file.string(),
                 " (give --scenes DIR: the repository's scenes folder)");
        files.push_back(file);
    }
    return files;
}

std::vector<PathBenchRow> runPathBench(const PathBenchOptions& options,
                                       const std::function<void(const std::string&)>& status) {
    if (options.resolution < 1 || options.resolution > kMaxFilmSide)
        fail("bench: path resolution ", options.resolution, " is outside [1, ", kMaxFilmSide, "]");
    if (options.spp < 1)
        fail("bench: path samples per pixel must be at least 1, got ", options.spp);
    if (options.maxDepth < 0) fail("bench: path max depth must be >= 0, got ", options.maxDepth);
    auto say = [&](const std::string& what) {
        if (status) status(what);
    };
    const std::vector<fs::path> files = pathBenchFiles(options);
    std::vector<PathBenchRow> rows;
    for (size_t i = 0; i < files.size(); ++i) {
        PathBenchRow row;
        row.scene = options.scenes[i];
        row.file = files[i];
        if (const fs::path missing = firstMissingFile(files[i]); !missing.empty()) {
            row.skipped = true;
            row.skipReason = concat(missing.string(), " not found");
            rows.push_back(std::move(row));
            continue;
        }

        say(concat("path ", row.scene, ": load and build"));
        const auto setupStart = Clock::now();
        SceneDesc desc = parseSceneFile(files[i]);
        desc.film.width = desc.film.height = options.resolution;
        desc.render.spp = options.spp;
        desc.render.maxDepth = options.maxDepth;
        desc.render.integrator = "path";
        BuildOptions build;
        build.threads = options.threads;
        BuildTimings timings;
        const BuiltScene scene = buildScene(desc, build, &timings);
        const World& world = scene.world;
        const Camera camera = buildCamera(scene.camera, desc.film.width, desc.film.height);
        const auto integrator = makeIntegrator(desc.render.integrator, world,
                                               buildIntegratorOptions(desc, camera));
        const double setup = secondsSince(setupStart);

        say(concat("path ", row.scene, ": render ", options.resolution, "x", options.resolution,
                   ", ", options.spp, " spp"));
        // Beauty only: the AOVs are film bookkeeping, not path tracing.
        Film film(desc.film.width, desc.film.height,
                  PixelRect{0, 0, desc.film.width, desc.film.height}, {});
        RenderOptions render;
        render.threads = options.threads;
        render.spp = desc.render.spp;
        render.seed = desc.render.seed;
        const RenderStats stats = renderImage(world, camera, *integrator, film, render);

        row.width = desc.film.width;
        row.height = desc.film.height;
        row.spp = desc.render.spp;
        row.maxDepth = desc.render.maxDepth;
        row.triangles = world.instancedTriangleCount();
        row.loadSeconds = timings.loadSeconds;
        row.bvhSeconds = timings.bvhSeconds;
        row.setupSeconds = std::max(0.0, setup - timings.loadSeconds - timings.bvhSeconds);
        row.firstTileSeconds = stats.firstTileSeconds;
        row.renderSeconds = stats.seconds;
        row.cameraRays = stats.cameraRays;
        row.shadowRays = stats.shadowRays;
        row.bounceRays = stats.bounceRays;
        row.packetWidth = stats.packetWidth;
        rows.push_back(std::move(row));
    }
    return rows;
}

std::optional<PathCostRatio> pathCostRatio(std::span<const PathBenchRow> rows,
                                           const std::string& scene, const std::string& base) {
    auto measured = [&](const std::string& name) -> const PathBenchRow* {
        for (const PathBenchRow& r : rows)
            if (r.scene == name && !r.skipped && r.renderSeconds > 0 && r.totalRays() > 0)
                return &r;
        return nullptr;
    };
    const PathBenchRow* s = measured(scene);
    const PathBenchRow* b = measured(base);
    if (!s || !b) return std::nullopt;
    return PathCostRatio{b->samplesPerSecond() / s->samplesPerSecond(),
                         b->mraysPerSecond() / s->mraysPerSecond()};
}

void printPathBenchTable(std::FILE* out, std::span<const PathBenchRow> rows) {
    if (rows.empty()) return;
    std::fprintf(out, "%-9s %10s %9s %8s %8s %8s %8s %10s %8s %9s\n", "path", "triangles",
                 "image", "load s", "bvh s", "first px", "render s", "samples/s", "Mrays/s",
                 "rays/spl");
    for (const PathBenchRow& r : rows) {
        if (r.skipped) {
            std::fprintf(out, "%-9s skipped: %s\n", r.scene.c_str(), r.skipReason.c_str());
            continue;
        }
        const std::string image = concat(r.width, "x", r.height);
        std::fprintf(out, "%-9s %10zu %9s %8.3f %8.3f %8.3f %8.3f %10.0f %8.2f %9.2f\n",
                     r.scene.c_str(), r.triangles, image.c_str(), r.loadSeconds, r.bvhSeconds,
                     r.firstPixelSeconds(), r.renderSeconds, r.samplesPerSecond(),
                     r.mraysPerSecond(), r.raysPerSample());
    }
    std::fprintf(out,
                 "first px: load + bvh + first tile; Mrays/s: camera + shadow + bounce rays per "
                 "render second; rays/spl: rays per sample\n");
    if (const auto ratio = pathCostRatio(rows, "sponza", "cornell"))
        std::fprintf(out,
                     "sponza/cornell cost ratio (this run): %.2fx per sample, %.2fx per ray\n",
                     ratio->perSample, ratio->perRay);
}

}  // namespace strahl
