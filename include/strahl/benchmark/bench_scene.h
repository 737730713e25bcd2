#pragma once
// The scenes `strahl bench` measures: a ladder of generated meshes of 10^2 to
// 10^7 triangles, and real models from the shared data folder. Each scene is
// one triangle mesh, framed by the same automatic camera, lit by one point
// light, so the figures differ only by the geometry.

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "strahl/core/bounds.h"
#include "strahl/geometry/triangle_mesh.h"

namespace strahl {

// A generated ladder rung: a bumpy sphere (bumps make it non-convex, so
// diffuse bounces hit the mesh again) on a ground square, of about `triangles`
// triangles. Generated, not stored, so no file is involved.
TriangleMesh generateBenchMesh(size_t triangles);

// The ladder's limits: below, the timings are all overhead; above, the mesh
// and its BVH need several GiB.
inline constexpr size_t kMinBenchTriangles = 100;
inline constexpr size_t kMaxBenchTriangles = 100'000'000;

// A real model: a short name for the command line and its file relative to the
// shared data folder.
struct BenchModel {
    const char* name;
    const char* file;
};
std::span<const BenchModel> benchModels();

struct BenchSceneSpec {
    std::string name;                // "ladder-1e4", "armadillo"
    size_t triangles = 0;            // generated: the requested count
    std::filesystem::path file;      // model: its file; empty for generated
    bool generated() const { return file.empty(); }
};

// The scene list of a bench run: the ladder sizes, then the named models
// ("all": every model) found in dataDir. Throws strahl::Error for a size
// outside [kMinBenchTriangles, kMaxBenchTriangles], an unknown model name (the
// message lists the known ones), a data folder that does not exist when models
// are asked for, or a model file missing from it.
std::vector<BenchSceneSpec> benchScenes(std::span<const size_t> ladder,
                                        std::span<const std::string> models,
                                        const std::filesystem::path& dataDir);

// Parses a ladder size: an integer or a power of ten written "1e5".
size_t parseBenchSize(const std::string& text);

}  // namespace strahl
