// Large scenes (docs/memory.md): the figures of the "large meshed scenes"
// targets, each measured in a fresh child process so that its peak resident
// memory (VmHWM) is its own:
//
//   1. scenes/scale/mesh10m.json (one mesh of 10,035,200 triangles): BVH build
//      time and Mtris/s for every quality and compact mode, Embree's bytes
//      and the resident bytes per triangle (mesh data included);
//   2. its time to first pixel: load + BVH + the first 32 x 32 tile at 1080p;
//   3. scenes/scale/forest.json (1,003,763,000 instanced triangles, needs
//      ../shared/data): a whole 1920 x 1080 path-traced frame at 1 spp and the
//      peak resident memory of the process.
//
// Each figure is printed with the target it is judged by and the ratio.
//
//   cmake --build build --target bench_scale && ./build/bin/bench_scale [--quick]
//
// --quick skips the high-quality build (the slowest) and the forest frame.

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "strahl/core/process_memory.h"
#include "strahl/film/film.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"

namespace fs = std::filesystem;
using namespace strahl;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Runs `scenario` in a child process and returns the line it printed (one
// line of results), or "failed: ..." — so each scenario's peak memory is its
// own and a scenario that runs out of memory cannot take the others down.
template <typename Scenario>
std::string isolated(Scenario&& scenario) {
    int fds[2];
    if (pipe(fds) != 0) return "failed: pipe";
    std::fflush(stdout);
    const pid_t child = fork();
    if (child < 0) return "failed: fork";
    if (child == 0) {
        close(fds[0]);
        std::string line;
        try {
            line = scenario();
        } catch (const std::exception& e) {
            line = std::string("failed: ") + e.what();
        }
        const ssize_t written = write(fds[1], line.data(), line.size());
        _exit(written == ssize_t(line.size()) ? 0 : 1);
    }
    close(fds[1]);
    std::string line;
    char buf[4096];
    for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;) line.append(buf, size_t(n));
    close(fds[0]);
    int status = 0;
    waitpid(child, &status, 0);
    if (line.empty()) return "failed: the child process died (status " + std::to_string(status) + ")";
    return line;
}

std::string format(const char* fmt, auto... args) {
    char buf[512];
    std::snprintf(buf, sizeof buf, fmt, args...);
    return buf;
}

double mib(size_t bytes) { return double(bytes) / double(1 << 20); }

// One BVH build of the 10^7-triangle mesh.
std::string buildFigures(const fs::path& scene, BvhQuality quality, bool compact) {
    const SceneDesc desc = parseSceneFile(scene);
    BuildOptions options;
    options.bvhQuality = quality;
    options.compact = compact;
    const size_t before = residentBytes();
    BuildTimings timings;
    const World world = buildWorld(desc, options, &timings);
    const size_t after = residentBytes();
    const double triangles = double(world.triangleCount());
    return format("%-7s %-7s %10.0f %7.2f %7.2f %8.2f %9.1f %9.1f %9.1f %9.0f", bvhQualityName(quality),
                  compact ? "yes" : "no", triangles, timings.loadSeconds, timings.bvhSeconds,
                  triangles / timings.bvhSeconds / 1e6,
                  double(world.accel->memoryBytes()) / triangles,
                  double(world.shapeMemoryBytes()) / triangles, double(after - before) / triangles,
                  mib(peakResidentBytes()));
}

// Parses and builds `scene` (default BVH settings) and renders the pixels of
// `crop` at `spp`: what the two render measurements share.
struct CropRender {
    BuildTimings timings;
    RenderStats stats;
    size_t triangles = 0, instancedTriangles = 0;
};

CropRender renderCrop(const SceneDesc& desc, const PixelRect& crop, int spp, int tileSize) {
    CropRender result;
    const BuiltScene scene = buildScene(desc, BuildOptions{}, &result.timings);
    const World& world = scene.world;
    result.triangles = world.triangleCount();
    result.instancedTriangles = world.instancedTriangleCount();
    const Camera camera = buildCamera(scene.camera, desc.film.width, desc.film.height);
    const auto integrator = makeIntegrator(desc.render.integrator, world,
                                           buildIntegratorOptions(desc, camera));
    Film film(desc.film.width, desc.film.height, crop, desc.film.aovs);
    RenderOptions options;
    options.tileSize = tileSize;
    options.spp = spp;
    options.seed = desc.render.seed;
    options.filter = buildPixelFilter(desc.film);
    result.stats = renderImage(world, camera, *integrator, film, options);
    return result;
}

// Load + BVH + the first tile of a full-size frame: what a user waits for
// before the first pixel appears. The tile is the one in the middle of the
// frame (the top-left one shows only sky).
std::string timeToFirstPixel(const fs::path& scene) {
    const auto start = Clock::now();
    const SceneDesc desc = parseSceneFile(scene);
    const int tile = 32, x0 = desc.film.width / 2, y0 = desc.film.height / 2;
    const CropRender r =
        renderCrop(desc, PixelRect{x0, y0, x0 + tile, y0 + tile}, desc.render.spp, tile);
    return format("%.2f %.2f %.2f %.2f %.0f", r.timings.loadSeconds, r.timings.bvhSeconds,
                  r.stats.firstTileSeconds, secondsSince(start), mib(peakResidentBytes()));
}

// A whole frame at the scene's resolution, 1 spp.
std::string wholeFrame(const fs::path& scene) {
    const auto start = Clock::now();
    const SceneDesc desc = parseSceneFile(scene);
    const CropRender r =
        renderCrop(desc, PixelRect{0, 0, desc.film.width, desc.film.height}, 1, 32);
    return format("%zu %zu %d %d %.2f %.2f %.2f %.2f %.2f %.0f", r.triangles,
                  r.instancedTriangles, desc.film.width, desc.film.height,
                  r.timings.loadSeconds, r.timings.bvhSeconds, r.stats.seconds,
                  double(r.stats.totalRays()) / r.stats.seconds / 1e6, secondsSince(start),
                  mib(peakResidentBytes()));
}

const char* verdict(bool met) { return met ? "met" : "MISSED"; }

}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    const fs::path source = STRAHL_SOURCE_DIR;
    const fs::path mesh = source / "scenes/scale/mesh10m.json";
    const fs::path forest = source / "scenes/scale/forest.json";
    std::printf("bench_scale: %s, %ld hardware threads\n", embreeVersion(),
                sysconf(_SC_NPROCESSORS_ONLN));

    std::printf("\n1. BVH build, %s (each row a fresh process)\n", mesh.filename().c_str());
    std::printf("%-7s %-7s %10s %7s %7s %8s %9s %9s %9s %9s\n", "quality", "compact", "triangles",
                "load s", "bvh s", "Mtris/s", "bvh B/tri", "mesh B/tri", "RSS B/tri", "peak MiB");
    struct Config {
        BvhQuality quality;
        bool compact;
    };
    std::vector<Config> configs = {{BvhQuality::Medium, false}, {BvhQuality::Medium, true},
                                   {BvhQuality::Low, false}, {BvhQuality::Low, true}};
    if (!quick) configs.push_back({BvhQuality::High, false});
    // Judged on the default settings: medium quality, compact (docs/memory.md).
    double defaultRate = 0.0, fullRate = 0.0, reservedBytes = 0.0, residentBytes = 0.0;
    for (const Config& c : configs) {
        const std::string line = isolated([&] { return buildFigures(mesh, c.quality, c.compact); });
        std::printf("%s\n", line.c_str());
        char q[16], compact[8];
        double tris, load, bvh, rate, bvhBytes, meshBytes, rssBytes, peak;
        if (std::sscanf(line.c_str(), "%15s %7s %lf %lf %lf %lf %lf %lf %lf %lf", q, compact, &tris,
                        &load, &bvh, &rate, &bvhBytes, &meshBytes, &rssBytes, &peak) != 10 ||
            c.quality != BvhQuality::Medium)
            continue;
        if (c.compact) {
            defaultRate = rate;
            reservedBytes = bvhBytes + meshBytes;
            residentBytes = rssBytes;
        } else {
            fullRate = rate;
        }
    }
    std::printf("build, medium quality, compact (the default): %.2f Mtris/s; target >= 5: "
                "ratio %.2f, %s (not compact: %.2f Mtris/s)\n",
                defaultRate, defaultRate / 5.0, verdict(defaultRate >= 5.0), fullRate);
    // Resident growth is what a machine runs out of; Embree's own count
    // includes blocks its allocator reserved but never touched.
    std::printf("bytes per unique triangle, BVH and mesh data, compact: %.1f B resident; target "
                "<= 64: ratio %.2f, %s (Embree's allocated bytes + mesh arrays: %.1f B)\n",
                residentBytes, residentBytes / 64.0,
                verdict(residentBytes > 0 && residentBytes <= 64.0), reservedBytes);

    std::printf("\n2. time to first pixel, %s at 1920x1080 (a fresh process)\n",
                mesh.filename().c_str());
    {
        const std::string line = isolated([&] { return timeToFirstPixel(mesh); });
        double load, bvh, tile, total, peak;
        if (std::sscanf(line.c_str(), "%lf %lf %lf %lf %lf", &load, &bvh, &tile, &total, &peak) == 5) {
            std::printf("load %.2f s + bvh %.2f s + first tile %.2f s = %.2f s (peak %.0f MiB); "
                        "target <= 10 s: ratio %.2f, %s\n",
                        load, bvh, tile, total, peak, total / 10.0, verdict(total <= 10.0));
        } else {
            std::printf("%s\n", line.c_str());
        }
    }

    std::printf("\n3. %s: a whole frame, 1 spp (a fresh process)\n", forest.filename().c_str());
    if (quick) {
        std::printf("skipped: --quick\n");
    } else if (!fs::exists(source / "../shared/data/stanford-armadillo/Armadillo.ply")) {
        std::printf("skipped: ../shared/data (the models) is not next to the repository\n");
    } else {
        const std::string line = isolated([&] { return wholeFrame(forest); });
        double stored, instanced, width, height, load, bvh, render, mrays, total, peak;
        if (std::sscanf(line.c_str(), "%lf %lf %lf %lf %lf %lf %lf %lf %lf %lf", &stored, &instanced,
                        &width, &height, &load, &bvh, &render, &mrays, &total, &peak) == 10) {
            std::printf("%.0f unique triangles, %.0f instanced; %.0fx%.0f: load %.2f s, bvh %.2f s, "
                        "render %.2f s (%.2f Mrays/s), %.2f s in all\n",
                        stored, instanced, width, height, load, bvh, render, mrays, total);
            std::printf("peak resident memory %.0f MiB; target < 8 GiB: ratio %.3f, %s\n", peak,
                        peak / 8192.0, verdict(instanced >= 1e9 && peak < 8192.0));
        } else {
            std::printf("%s\n", line.c_str());
        }
    }
    return 0;
}
