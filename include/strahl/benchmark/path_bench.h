#pragma once
// `strahl bench --path`: what the path tracer costs on real scenes. Each scene
// file of the repository is rendered as the user would render it (same camera,
// lights, materials and seed) but at resolution x resolution pixels, `spp`
// samples per pixel, `maxDepth` bounces and integrator "path", and reported as
// samples per second and Mrays per second, with the time to the first finished
// tile. One cold render per scene: the first pixel is only meaningful once.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "strahl/benchmark/bench_report.h"

namespace strahl {

// A scene of the path bench: a short name for the command line and its file
// relative to the repository's scenes/ folder.
struct PathBenchScene {
    const char* name;
    const char* file;
};
// cornell: scenes/default.json (CornellBox-Sphere, its emissive ceiling lamp
// and a point light; ships with the repository); sponza:
// scenes/showcase/sponza.json (needs ../shared/data next to the repository).
std::span<const PathBenchScene> pathBenchScenes();

struct PathBenchOptions {
    std::filesystem::path scenesDir = "scenes";  // the repository's scenes/ folder
    std::vector<std::string> scenes = {"cornell", "sponza"};
    int resolution = 512;  // film width and height
    int spp = 16;
    int maxDepth = 8;
    int threads = 0;       // 0: all hardware threads
};

struct PathBenchRow {
    std::string scene;
    std::filesystem::path file;  // the scene file
    // Skipped: a file the scene needs is absent; nothing below is measured.
    bool skipped = false;
    std::string skipReason;
    int width = 0, height = 0, spp = 0, maxDepth = 0;
    size_t triangles = 0;
    double loadSeconds = 0.0;       // reading and preparing the meshes (BuildTimings)
    double bvhSeconds = 0.0;        // Embree BVH
    // Parsing the scene file, lights, camera and integrator: the wall time of
    // the setup minus load and BVH. Not part of firstPixelSeconds, which is
    // defined as in `strahl render`'s summary.
    double setupSeconds = 0.0;
    double firstTileSeconds = 0.0;  // from the start of the render to the first finished tile
    double renderSeconds = 0.0;
    uint64_t cameraRays = 0, shadowRays = 0, bounceRays = 0;
    int packetWidth = 0;

    uint64_t totalRays() const { return cameraRays + shadowRays + bounceRays; }
    double samples() const { return double(width) * double(height) * double(spp); }
    double firstPixelSeconds() const { return loadSeconds + bvhSeconds + firstTileSeconds; }
    double samplesPerSecond() const { return renderSeconds > 0 ? samples() / renderSeconds : 0.0; }
    double mraysPerSecond() const {
        return renderSeconds > 0 ? double(totalRays()) / renderSeconds / 1e6 : 0.0;
    }
    double raysPerSample() const { return samples() > 0 ? double(totalRays()) / samples() : 0.0; }
};

// The scene files of options.scenes, in order. Throws strahl::Error, before
// anything is measured, for an unknown name (the message lists the known
// ones), a scenes folder that does not exist, or a scene file missing from it.
std::vector<std::filesystem::path> pathBenchFiles(const PathBenchOptions& options);

// Renders every scene of options.scenes once, in order. A scene whose mesh or
// image files (its "file" keys) are absent is a skipped row, not an error.
// `status` (optional) is told what is being measured.
std::vector<PathBenchRow> runPathBench(const PathBenchOptions& options,
                                       const std::function<void(const std::string&)>& status = {});

// How much more a sample and a ray of `scene` cost than of `base`, both from
// the same run; empty unless both were measured.
struct PathCostRatio {
    double perSample = 0.0;  // base samples/s / scene samples/s
    double perRay = 0.0;     // base Mrays/s / scene Mrays/s
};
std::optional<PathCostRatio> pathCostRatio(std::span<const PathBenchRow> rows,
                                           const std::string& scene, const std::string& base);

// The path rows as a table, skipped scenes as "skipped: ..." lines, and the
// sponza/cornell cost ratio when both were measured.
void printPathBenchTable(std::FILE* out, std::span<const PathBenchRow> rows);

// writeBenchResults (bench_report.h) with the path rows: JSON gets a "path"
// array (and "path_options"); CSV keeps its one table of ladder and model rows
// and leaves the path rows out (they have other columns: use .json). Defined in
// bench_report.cpp next to the other writers.
void writeBenchResults(const std::filesystem::path& file, std::span<const BenchRow> rows,
                       const BenchFits& fits, const BenchOptions& options,
                       std::span<const PathBenchRow> pathRows, const PathBenchOptions& pathOptions);

}  // namespace strahl
