// Object order vs image order at 1024x1024 on a mesh of at least 1M triangles,
// the same framing as bench_primary_rays (the mesh fills the image):
//   raytrace: renderImage with the eyelight integrator (Embree BVH, camera
//             packets); the BVH is built once before, its build time printed;
//   raster:   rasterizeImage with the same integrator, camera and film: no
//             preprocessing at all, so its time is the whole cost.
// Both shade the same first hits; the run prints on how many pixels they agree
// and the rasterizer's counters. Each case runs 5 repetitions; "min" is the
// fastest, the one least disturbed by other load on a shared machine.
//
// Usage: bench_raster [--mesh FILE] [google-benchmark flags]

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_mesh.h"
#include "strahl/camera/tile_rays.h"
#include "strahl/integrator/integrator.h"
#include "strahl/raster/rasterizer.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene_builder.h"

namespace strahl::bench {
namespace {

constexpr int kSize = 1024;
constexpr int kTile = 32;
constexpr size_t kMinTriangles = 1'000'000;
constexpr int kRepetitions = 5;

struct Fixture {
    World world;
    Camera camera{CameraFrame{}, Projection::Perspective, ImageWindow{}, 1.0f, kSize, kSize};
    std::string meshDescription;
    double bvhSeconds = 0.0;
};

Fixture& fixture(const std::string& meshPath = {}) {
    static Fixture f = [&] {
        Fixture fx;
        SceneDesc desc = parseSceneText(R"({ "shapes": [ { "type": "mesh", "positions":
            [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [0, 1, 2] } ] })",
                                        "bench_raster.json");
        desc.shapes[0].inlineMesh = benchmarkMesh(meshPath, kMinTriangles, fx.meshDescription);
        BuildTimings timings;
        fx.world = buildWorld(desc, BuildOptions{}, &timings);
        fx.bvhSeconds = timings.bvhSeconds;
        fx.camera = frontCamera(fx.world.bounds(), kSize);
        return fx;
    }();
    return f;
}

void BM_RaytraceEyelight(benchmark::State& state) {
    Fixture& f = fixture();
    const auto integrator = makeIntegrator("eyelight", f.world);
    RenderOptions options;
    options.tileSize = kTile;
    for (auto _ : state) {
        Film film(kSize, kSize, PixelRect{0, 0, kSize, kSize}, {});
        renderImage(f.world, f.camera, *integrator, film, options);
    }
}

void BM_RasterEyelight(benchmark::State& state) {
    Fixture& f = fixture();
    const auto integrator = makeIntegrator("eyelight", f.world);
    RenderOptions options;
    options.tileSize = kTile;
    for (auto _ : state) {
        Film film(kSize, kSize, PixelRect{0, 0, kSize, kSize}, {});
        rasterizeImage(f.world, f.camera, *integrator, film, options);
    }
}

// The first hits of both algorithms, compared once: pixels that see the same
// triangle (or both nothing).
void printAgreement(const Fixture& f) {
    RasterStats stats;
    const PixelRect image{0, 0, kSize, kSize};
    const std::vector<Hit> raster =
        rasterizeHits(f.world, f.camera, image, RenderOptions{}, &stats);
    const TileRayGenerator rays(f.camera, 0, 1);
    size_t same = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            Sampler rng;
            const Hit traced = f.world.accel->intersect(rays.sampleRay(x, y, 0, rng));
            const Hit& r = raster[size_t(y) * kSize + size_t(x)];
            same += traced.geomID == r.geomID && traced.primID == r.primID;
        }
    std::printf("raster: %llu triangles, %llu in view, %llu fragments, %llu pixels covered\n",
                static_cast<unsigned long long>(stats.triangles),
                static_cast<unsigned long long>(stats.trianglesInView),
                static_cast<unsigned long long>(stats.fragments),
                static_cast<unsigned long long>(stats.coveredPixels));
    std::printf("agreement: %zu of %d pixels see the same triangle in both (%.4f %%)\n", same,
                kSize * kSize, 100.0 * double(same) / (double(kSize) * kSize));
}

double fastest(const std::vector<double>& v) {
    return *std::min_element(v.begin(), v.end());
}

}  // namespace
}  // namespace strahl::bench

int main(int argc, char** argv) {
    using namespace strahl::bench;
    const std::string meshPath = takeOption(argc, argv, "--mesh");
    benchmark::Initialize(&argc, argv);
    const Fixture& f = fixture(meshPath);
    std::printf(
        "mesh: %s, %zu triangles; image %dx%d; tiles %dx%d; BVH build %.3f s (raytrace only)\n",
        f.meshDescription.c_str(), f.world.triangleCount(), kSize, kSize, kTile, kTile,
        f.bvhSeconds);
    printAgreement(f);
    for (auto [name, fn] : {std::pair{"BM_RaytraceEyelight", &BM_RaytraceEyelight},
                            std::pair{"BM_RasterEyelight", &BM_RasterEyelight}}) {
        benchmark::RegisterBenchmark(name, fn)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(0.5)
            ->Repetitions(kRepetitions)
            ->ComputeStatistics("min", fastest);
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
