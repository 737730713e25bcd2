// The ceiling of issue 20's path target: of the time strahl's path tracer
// takes per sample, how much is Embree's traversal of the rays it traces.
//
// One render of the scene (as `strahl render` makes it: its camera, film size,
// spp, seed and integrator settings) goes through a recording accelerator
// that keeps every query: the camera packets, the closest-hit (bounce) rays
// and the any-hit (shadow) rays. Then, in --rounds interleaved rounds, the
// scene is rendered again (the render phase alone, as timings.render) and
// the recorded queries are replayed through the same Embree BVH with no ray
// generation, shading or film: tiles of queries over all threads, as the
// render spreads its tiles. The replay is the least time any renderer could
// take to trace those same rays through this Embree, one query at a time and
// camera rays in packets, as strahl traces them.
//
// Prints, per sample pass (fastest round of each):
//   render   strahl's render phase
//   embree   the replay: Embree alone on the same queries
// and the replay's share of the render. The peer script
// (peer_embree_tutorials.sh) divides `embree` by the `pathtracer`'s seconds
// per sample: the path target (<= 0.8) cannot be met while that quotient is
// above 0.8, whatever the shading costs.
//
// Usage: bench_path_rays --scene FILE.json [--rounds N] [--threads N] [--quads auto|always|never]
//   --quads  which meshes Embree traces as quads (strahl render --quads /
//            --no-quads; auto, the default, as strahl render)

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <exception>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_mesh.h"
#include "strahl/film/film.h"
#include "strahl/integrator/integrator.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene_builder.h"

namespace strahl::bench {
namespace {

using Clock = std::chrono::steady_clock;

// What one thread of the recording render asked the accelerator, in order.
struct QueryLog {
    std::vector<Ray> closest;  // intersect()
    std::vector<Ray> any;      // occluded()
    std::vector<RayHitPacket8> packets8;
    std::vector<RayHitPacket16> packets16;
    // Per packet, its lanes' mask (the first 8 or 16 used). A render traces
    // camera packets of one width, so valid[i] belongs to packet i.
    std::vector<std::array<int, 16>> valid;
};

// Forwards every query to the real accelerator and logs it first.
class RecordingAccel final : public Accel {
public:
    explicit RecordingAccel(const Accel& inner) : inner_(inner) {}

    Hit intersect(const Ray& ray) const override {
        logs_.local().closest.push_back(ray);
        return inner_.intersect(ray);
    }
    bool occluded(const Ray& ray) const override {
        logs_.local().any.push_back(ray);
        return inner_.occluded(ray);
    }
    void intersect8(const int* valid, RayHitPacket8& packet, RayCoherence c) const override {
        record(valid, packet, logs_.local().packets8);
        inner_.intersect8(valid, packet, c);
    }
    void intersect16(const int* valid, RayHitPacket16& packet, RayCoherence c) const override {
        record(valid, packet, logs_.local().packets16);
        inner_.intersect16(valid, packet, c);
    }
    int nativePacketWidth() const override { return inner_.nativePacketWidth(); }
    Bounds3 bounds() const override { return inner_.bounds(); }
    size_t memoryBytes() const override { return inner_.memoryBytes(); }

    tbb::enumerable_thread_specific<QueryLog>& logs() const { return logs_; }

private:
    // Logs a camera packet before it is traced, and its lanes' mask.
    template <class Packet>
    void record(const int* valid, const Packet& packet, std::vector<Packet>& packets) const {
        packets.push_back(packet);
        std::array<int, 16> mask{};
        std::copy(valid, valid + Packet::kWidth, mask.begin());
        logs_.local().valid.push_back(mask);
    }

    const Accel& inner_;
    mutable tbb::enumerable_thread_specific<QueryLog> logs_;
};

// The recorded queries, cut into work items of about kChunk rays.
struct Replay {
    static constexpr size_t kChunk = 4096;  // rays per task: many tasks, each long enough to amortise scheduling
    struct Item {
        const QueryLog* log;
        enum Kind { Closest, Any, Packets8, Packets16 } kind;
        size_t begin, end;
    };
    std::vector<Item> items;
    size_t closest = 0, any = 0, cameraRays = 0;

    explicit Replay(const tbb::enumerable_thread_specific<QueryLog>& logs) {
        for (const QueryLog& log : logs) {
            if (!log.packets8.empty() && !log.packets16.empty())
                throw std::runtime_error("a render traced camera packets of two widths");
            cut(log, Item::Closest, log.closest.size(), kChunk);
            cut(log, Item::Any, log.any.size(), kChunk);
            cut(log, Item::Packets8, log.packets8.size(), kChunk / 8);
            cut(log, Item::Packets16, log.packets16.size(), kChunk / 16);
            closest += log.closest.size();
            any += log.any.size();
            for (const auto& mask : log.valid)
                cameraRays += static_cast<size_t>(std::count(mask.begin(), mask.end(), -1));
        }
    }
    void cut(const QueryLog& log, Item::Kind kind, size_t count, size_t chunk) {
        for (size_t b = 0; b < count; b += chunk) items.push_back({&log, kind, b, std::min(count, b + chunk)});
    }

    // Seconds to trace every recorded query once through `accel`.
    double run(const Accel& accel) const {
        const auto start = Clock::now();
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, items.size(), 1),
            [&](const tbb::blocked_range<size_t>& range) {
                size_t sink = 0;  // keeps the results alive
                for (size_t k = range.begin(); k != range.end(); ++k) {
                    const Item& item = items[k];
                    const QueryLog& log = *item.log;
                    for (size_t i = item.begin; i < item.end; ++i) {
                        switch (item.kind) {
                            case Item::Closest:
                                sink += accel.intersect(log.closest[i]).geomID;
                                break;
                            case Item::Any:
                                sink += accel.occluded(log.any[i]);
                                break;
                            case Item::Packets8: {
                                RayHitPacket8 p = log.packets8[i];  // fresh tfar and geomID
                                accel.intersect8(log.valid[i].data(), p, RayCoherence::Coherent);
                                sink += p.geomID[0];
                                break;
                            }
                            case Item::Packets16: {
                                RayHitPacket16 p = log.packets16[i];
                                accel.intersect16(log.valid[i].data(), p, RayCoherence::Coherent);
                                sink += p.geomID[0];
                                break;
                            }
                        }
                    }
                }
                volatile size_t keep = sink;
                (void)keep;
            },
            tbb::simple_partitioner());
        return std::chrono::duration<double>(Clock::now() - start).count();
    }
};

int run(int argc, char** argv) {
    const std::string scenePath = takeOption(argc, argv, "--scene");
    const std::string roundsText = takeOption(argc, argv, "--rounds");
    const std::string threadsText = takeOption(argc, argv, "--threads");
    const std::string quads = takeOption(argc, argv, "--quads");
    if (scenePath.empty() || argc != 1 ||
        (!quads.empty() && quads != "auto" && quads != "always" && quads != "never")) {
        std::fprintf(stderr,
                     "usage: bench_path_rays --scene FILE.json [--rounds N] [--threads N] "
                     "[--quads auto|always|never]\n");
        return 2;
    }
    const int rounds = roundsText.empty() ? 3 : std::stoi(roundsText);
    const int threads = threadsText.empty() ? 0 : std::stoi(threadsText);
    if (rounds < 1 || threads < 0) {
        std::fprintf(stderr, "bench_path_rays: --rounds must be >= 1 and --threads >= 0\n");
        return 2;
    }
    // The replay's threads, as many as the render's.
    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<size_t>(threads));

    const SceneDesc desc = parseSceneFile(scenePath);
    BuildOptions build;
    build.threads = threads;
    if (quads == "always") build.quads = QuadPolicy::Always;
    if (quads == "never") build.quads = QuadPolicy::Never;
    BuiltScene scene = buildScene(desc, build);
    World& world = scene.world;
    const Camera camera = buildCamera(scene.camera, desc.film.width, desc.film.height);
    const auto integrator =
        makeIntegrator(desc.render.integrator, world, buildIntegratorOptions(desc, camera));
    RenderOptions render;
    render.threads = threads;
    render.spp = desc.render.spp;
    render.seed = desc.render.seed;
    const auto renderOnce = [&] {
        Film film(desc.film.width, desc.film.height,
                  PixelRect{0, 0, desc.film.width, desc.film.height}, {});
        return renderImage(world, camera, *integrator, film, render).seconds;
    };

    // The recording render: the same queries the timed renders make (the
    // images are deterministic, so are the rays).
    std::unique_ptr<Accel> embree = std::move(world.accel);
    auto recorder = std::make_unique<RecordingAccel>(*embree);
    const RecordingAccel& recording = *recorder;
    world.accel = std::move(recorder);
    renderOnce();
    const Replay replay(recording.logs());
    // The replay points into the recorder's logs: it stays alive, set aside.
    const std::unique_ptr<Accel> recorderKept = std::move(world.accel);
    world.accel = std::move(embree);

    double bestRender = std::numeric_limits<double>::infinity();
    double bestReplay = bestRender;
    for (int k = 0; k < rounds; ++k) {
        const double r = renderOnce();
        const double e = replay.run(*world.accel);
        std::printf("bench_path_rays: round %d: render %.3f s, embree alone %.3f s\n", k + 1, r, e);
        bestRender = std::min(bestRender, r);
        bestReplay = std::min(bestReplay, e);
    }
    const double spp = desc.render.spp;
    std::printf("bench_path_rays: %s, %dx%d, %d spp, %.2f M rays (camera %.2f M in packets, "
                "closest-hit %.2f M, shadow %.2f M)\n",
                scenePath.c_str(), desc.film.width, desc.film.height, desc.render.spp,
                double(replay.cameraRays + replay.closest + replay.any) / 1e6,
                double(replay.cameraRays) / 1e6, double(replay.closest) / 1e6,
                double(replay.any) / 1e6);
    std::printf("per sample, fastest of %d rounds: render %.4f s  embree %.4f s  (embree alone is "
                "%.0f %% of the render)\n",
                rounds, bestRender / spp, bestReplay / spp, 100.0 * bestReplay / bestRender);
    return 0;
}

}  // namespace
}  // namespace strahl::bench

int main(int argc, char** argv) {
    try {
        return strahl::bench::run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_path_rays: %s\n", e.what());
        return 1;
    }
}
