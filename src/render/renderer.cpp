#include "strahl/render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

#include "strahl/camera/tile_rays.h"
#include "strahl/core/error.h"
#include "strahl/integrator/camera_sample.h"

namespace strahl {

std::vector<PixelRect> cutTiles(const PixelRect& crop, int size) {
    std::vector<PixelRect> tiles;
    for (int y = crop.y0; y < crop.y1; y += size)
        for (int x = crop.x0; x < crop.x1; x += size)
            tiles.push_back({x, y, std::min(x + size, crop.x1), std::min(y + size, crop.y1)});
    return tiles;
}

namespace {

// Everything one worker needs while rendering one tile.
struct TileContext {
    const World& world;
    const Integrator& integrator;
    Film& film;
    bool wantAovs;
    bool adaptive;  // render only the pixels that still run (adaptive sampling)
    ShadingStats stats;
    uint64_t cameraRays = 0;

    // Whether pixel (x, y) takes its sample `pass` (the film's count of it)
    // now: with adaptive sampling, not once stopped, nor if it already has it
    // (a resumed pass that an interrupt cut short).
    bool wants(int x, int y, int pass) const {
        return !adaptive ||
               (!film.converged(x, y) && film.sampleCount(x, y) == static_cast<uint32_t>(pass));
    }

    void shadeSample(int px, int py, const Ray& ray, const Hit& hit, Sampler& sampler) {
        const CameraSample sample =
            shadeCameraSample(world, integrator, ray, hit, sampler, stats, wantAovs);
        film.addSample(px, py, sample.radiance, sample.aov);
    }
};

// Sample pass `pass` (the sampler's sample index `sample`) of every pixel of
// `tile` that wants it.
template <int N>
void renderTilePackets(TileContext& ctx, const TileRayGenerator& gen, const PixelRect& tile,
                       int pass, int sample) {
    using Packet = CameraPacket<N>;
    Packet packet;
    const auto wanted = [&](int x, int y) { return ctx.wants(x, y, pass); };
    for (int by = tile.y0; by < tile.y1; by += Packet::kBlockHeight) {
        for (int bx = tile.x0; bx < tile.x1; bx += Packet::kBlockWidth) {
            const int active = gen.fillPacket(tile, bx, by, sample, packet, wanted);
            if (active == 0) continue;
            ctx.cameraRays += static_cast<uint64_t>(active);
            for (int lane = 0; lane < N; ++lane)
                if (packet.valid[lane]) ctx.film.prefetch(packet.px[lane], packet.py[lane]);
            ctx.world.accel->intersectPacket(packet.valid, packet.rays, RayCoherence::Coherent);
            // The lanes the integrator shades at once (the AOVs need each
            // lane's surface interaction: then none).
            alignas(16) Color radiance[N];
            const uint32_t shaded =
                ctx.wantAovs ? 0u
                             : ctx.integrator.shadeCameraLanes(
                                   ctx.world, CameraLanes::of(packet.rays, packet.valid), radiance);
            for (int lane = 0; lane < N; ++lane) {
                if (!packet.valid[lane]) continue;
                if (shaded & (1u << lane)) {
                    AovSample aov;
                    aov.hit = packet.rays.geomID[lane] != kInvalidId;
                    ctx.film.addSample(packet.px[lane], packet.py[lane], radiance[lane], aov);
                    continue;
                }
                Ray ray = packet.rays.ray(lane);
                ray.tfar = kInfinity;  // the packet's tfar now holds the hit distance
                ctx.shadeSample(packet.px[lane], packet.py[lane], ray, packet.rays.hit(lane),
                                packet.sampler[lane]);
            }
        }
    }
}

void renderTileSingle(TileContext& ctx, const TileRayGenerator& gen, const PixelRect& tile,
                      int pass, int sample) {
    Sampler sampler;
    for (int y = tile.y0; y < tile.y1; ++y) {
        for (int x = tile.x0; x < tile.x1; ++x) {
            if (!ctx.wants(x, y, pass)) continue;
            const Ray ray = gen.sampleRay(x, y, sample, sampler);
            ++ctx.cameraRays;
            ctx.shadeSample(x, y, ray, ctx.world.accel->intersect(ray), sampler);
        }
    }
}

}  // namespace

int resolvePacketWidth(PacketMode mode, const Accel& accel) {
    switch (mode) {
        case PacketMode::Packet8:
            return 8;
        case PacketMode::Packet16:
            return 16;
        case PacketMode::Single:
            return 1;
        case PacketMode::Auto:
            break;
    }
    // Embree emulates wider packets on narrower ISAs, so anything but 16 means 8.
    return accel.nativePacketWidth() == 16 ? 16 : 8;
}

// The samples every pixel of `tile` already has in the film (0 for a new film,
// more when resuming from a checkpoint). Tiles are rendered whole, so all
// pixels of a tile agree unless the film was made with another tile size.
int tileStartSample(const Film& film, const PixelRect& tile, int spp) {
    if (film.tracksConvergence()) {
        // Adaptive sampling: the first pass a running pixel of the tile lacks;
        // spp if adaptive sampling stopped them all.
        uint32_t first = static_cast<uint32_t>(spp);
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x)
                if (!film.converged(x, y)) first = std::min(first, film.sampleCount(x, y));
        return static_cast<int>(first);
    }
    const uint32_t count = film.sampleCount(tile.x0, tile.y0);
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x)
            if (film.sampleCount(x, y) != count)
                fail("the film's pixels in tile (", tile.x0, ", ", tile.y0,
                     ") have different sample counts: it was rendered with another tile size");
    return static_cast<int>(count);
}

RenderStats renderImage(const World& world, const Camera& camera, const Integrator& integrator,
                        Film& film, const RenderOptions& options) {
    if (options.spp < 1) fail("samples per pixel must be at least 1, got ", options.spp);
    if (options.tileSize < 1) fail("tile size must be at least 1, got ", options.tileSize);
    // A world whose light set was never built would render without its lights.
    if (!world.lightsPrepared()) fail("renderImage: World::prepareLights() has not been called");
    const auto start = std::chrono::steady_clock::now();
    // Adaptive sampling's later passes have work in a few places only: tiles
    // of at most 8 x 8 pixels let both threads share it. (Any tile size gives
    // the same image.)
    constexpr int kAdaptiveTileSize = 8;
    const std::vector<PixelRect> tiles = cutTiles(
        film.crop(), options.adaptive.enabled() ? std::min(options.tileSize, kAdaptiveTileSize)
                                                : options.tileSize);
    if (options.sampleOffset < 0 || options.sampleOffset > INT32_MAX - options.spp)
        fail("sample offset ", options.sampleOffset, " with ", options.spp,
             " samples per pixel is out of range");
    const AdaptiveSampling& adaptive = options.adaptive;
    if (adaptive.enabled() != film.tracksConvergence())
        fail(adaptive.enabled() ? "adaptive sampling needs a film that tracks convergence"
                                : "the film tracks convergence but adaptive sampling is off");
    if (adaptive.enabled() && (options.sampleOffset != 0 || options.samplePart))
        fail("adaptive sampling does not split into sample ranges (--sample-offset)");
    if (adaptive.enabled() && adaptive.minSamples < 2)
        fail("adaptive sampling needs at least 2 samples per pixel before it stops one, got ",
             adaptive.minSamples);
    // The generator only asks whether there is more than one sample per pixel
    // (one alone goes through the pixel centre); a part of a split render is
    // part of a render of many.
    const TileRayGenerator generator(camera, options.seed,
                                     options.samplePart ? std::max(options.spp, 2) : options.spp,
                                     options.filter, world.hasMotion());

    RenderStats result;
    result.packetWidth = resolvePacketWidth(options.packets, *world.accel);
    std::vector<int> tileStart(tiles.size());
    int firstPass = options.spp;
    size_t work = 0;  // tile passes still to render
    for (size_t i = 0; i < tiles.size(); ++i) {
        tileStart[i] = tileStartSample(film, tiles[i], options.spp);
        if (tileStart[i] > options.spp)
            fail("the film already has ", tileStart[i], " samples per pixel, more than the ",
                 options.spp, " asked for");
        firstPass = std::min(firstPass, tileStart[i]);
        work += static_cast<size_t>(options.spp - tileStart[i]);
    }
    result.completedPasses = firstPass;
    if (adaptive.enabled() && firstPass == options.spp) {
        // Resumed from a film adaptive sampling has finished: its passes are
        // the most samples a pixel took.
        uint32_t most = 0;
        for (int y = film.crop().y0; y < film.crop().y1; ++y)
            for (int x = film.crop().x0; x < film.crop().x1; ++x)
                most = std::max(most, film.sampleCount(x, y));
        result.completedPasses = static_cast<int>(most);
        result.converged = result.completedPasses < options.spp;
    }

    std::atomic<uint64_t> cameraRays{0}, shadowRays{0}, bounceRays{0};
    std::atomic<bool> firstTile{true};
    const auto cancelled = [&] {
        return options.cancel && options.cancel->load(std::memory_order_relaxed);
    };
    if (options.progress) options.progress->begin("render", work);

    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    // Pass s renders sample s of every tile that does not have it yet, so after
    // each pass the image is a complete (s + 1)-sample image. Every pixel still
    // accumulates its samples in index order, whatever the passes, threads or
    // tile order: the sums, hence the image, are bit-identical.
    std::vector<size_t> passTiles;  // the tiles that take this pass
    passTiles.reserve(tiles.size());
    for (int pass = firstPass; pass < options.spp; ++pass) {
        if (cancelled()) break;
        // Only those: late in an adaptive render most tiles have stopped, and
        // a task per tile per pass would cost more than the work.
        passTiles.clear();
        for (size_t i = 0; i < tiles.size(); ++i)
            if (tileStart[i] <= pass) passTiles.push_back(i);
        arena.execute([&] {
            // Grain 1: tiles are the unit of load balancing; they vary a lot in cost.
            tbb::parallel_for(
                tbb::blocked_range<size_t>(0, passTiles.size(), 1),
                [&](const tbb::blocked_range<size_t>& range) {
                    for (size_t k = range.begin(); k != range.end(); ++k) {
                        const size_t i = passTiles[k];
                        // Tiles in flight finish; the rest of the pass is skipped.
                        if (cancelled()) continue;
                        TileContext ctx{
                            world, integrator, film, !film.aovs().empty(), adaptive.enabled(),
                            {},    0};
                        const int sample = options.sampleOffset + pass;  // the sampler's index
                        // Once adaptive sampling stops pixels, the running
                        // ones are scattered: a packet would carry a lane or
                        // two at the cost of a full one. Camera rays then go
                        // one by one (a rule of the pass alone, so the image
                        // is the same for any tiles and threads).
                        const bool sparse = adaptive.enabled() && pass >= adaptive.minSamples;
                        switch (sparse ? 1 : result.packetWidth) {
                            case 16:
                                renderTilePackets<16>(ctx, generator, tiles[i], pass, sample);
                                break;
                            case 8:
                                renderTilePackets<8>(ctx, generator, tiles[i], pass, sample);
                                break;
                            default:
                                renderTileSingle(ctx, generator, tiles[i], pass, sample);
                                break;
                        }
                        world.rethrowCutoutError();
                        cameraRays += ctx.cameraRays;
                        shadowRays += ctx.stats.shadowRays;
                        bounceRays += ctx.stats.bounceRays;
                        if (firstTile.exchange(false))
                            result.firstTileSeconds = std::chrono::duration<double>(
                                                          std::chrono::steady_clock::now() - start)
                                                          .count();
                        if (options.progress) options.progress->advance(1);
                    }
                },
                tbb::simple_partitioner());
        });
        if (cancelled()) break;
        result.completedPasses = pass + 1;
        // The decisions of this pass boundary, from the film alone, before a
        // checkpoint (passDone) records them. Tiles whose pixels all stopped
        // are not visited again.
        if (adaptive.enabled() && isDecisionPass(pass + 1, adaptive.minSamples) &&
            pass + 1 < options.spp) {
            const size_t running =
                arena.execute([&] { return stopConvergedPixels(film, adaptive); });
            for (size_t i = 0; i < tiles.size(); ++i)
                if (tileStart[i] <= pass)
                    tileStart[i] = tileStartSample(film, tiles[i], options.spp);
            if (running == 0) {
                result.converged = true;
                break;
            }
        }
        if (options.passDone && pass + 1 < options.spp && !options.passDone(pass + 1)) {
            result.stoppedEarly = true;
            break;
        }
    }
    result.cancelled = cancelled() && result.completedPasses < options.spp && !result.converged;

    if (options.progress) options.progress->end();
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.cameraRays = cameraRays;
    result.shadowRays = shadowRays;
    result.bounceRays = bounceRays;
    return result;
}

}  // namespace strahl
