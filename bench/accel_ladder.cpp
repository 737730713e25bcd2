// Google Benchmark view of the `strahl bench` ladder: cost per camera ray of
// Embree (single rays) and of the naive tracer on generated meshes of 10^2 to
// 10^5 triangles (naive beyond that takes minutes per figure; `strahl bench`
// samples it instead). Same meshes and camera as `strahl bench`
// (generateBenchMesh); the figure of interest is ns per ray and how it grows
// with the triangle count, reported as items (rays) per second.

#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/benchmark/bench_scene.h"
#include "strahl/benchmark/bench_suite.h"
#include "strahl/camera/camera.h"
#include "strahl/reference/naive_accel.h"

namespace strahl::bench {
namespace {

constexpr int kSide = 64;  // 4096 camera rays per iteration

struct Ladder {
    TriangleMesh mesh;
    std::unique_ptr<Accel> embree, naive;
    std::vector<Ray> rays;
};

// One fixture per size, built on first use, seen as strahl bench sees it.
const Ladder& ladder(size_t triangles) {
    static std::map<size_t, std::unique_ptr<Ladder>> cache;
    auto& slot = cache[triangles];
    if (!slot) {
        slot = std::make_unique<Ladder>();
        slot->mesh = generateBenchMesh(triangles);
        const TriangleMesh* meshes[] = {&slot->mesh};
        slot->embree = buildEmbreeAccel(meshes, {});
        slot->naive = buildNaiveAccel(meshes);
        const Camera camera = benchView(slot->mesh.bounds(), kSide).camera;
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x)
                slot->rays.push_back(camera.generateRay(float(x) + 0.5f, float(y) + 0.5f));
    }
    return *slot;
}

void trace(benchmark::State& state, bool naive) {
    const Ladder& l = ladder(size_t(state.range(0)));
    const Accel& accel = naive ? *l.naive : *l.embree;
    for (auto _ : state) {
        for (const Ray& ray : l.rays) benchmark::DoNotOptimize(accel.intersect(ray));
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(l.rays.size()));
    state.counters["triangles"] = double(l.mesh.triangleCount());
}

void BM_EmbreeSingleRay(benchmark::State& state) { trace(state, false); }
void BM_NaiveRay(benchmark::State& state) { trace(state, true); }

BENCHMARK(BM_EmbreeSingleRay)->RangeMultiplier(10)->Range(100, 10'000'000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NaiveRay)->RangeMultiplier(10)->Range(100, 100'000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace strahl::bench

BENCHMARK_MAIN();
