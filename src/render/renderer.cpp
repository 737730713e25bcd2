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
    ShadingStats stats;
    uint64_t cameraRays = 0;

    void shadeSample(int px, int py, const Ray& ray, const Hit& hit, Sampler& sampler) {
        const CameraSample sample =
            shadeCameraSample(world, integrator, ray, hit, sampler, stats, wantAovs);
        film.addSample(px, py, sample.radiance, sample.aov);
    }
};

// Samples [s0, s1) of every pixel of `tile`.
template <int N>
void renderTilePackets(TileContext& ctx, const TileRayGenerator& gen, const PixelRect& tile,
                       int s0, int s1) {
    using Packet = CameraPacket<N>;
    Packet packet;
    for (int s = s0; s < s1; ++s) {
        for (int by = tile.y0; by < tile.y1; by += Packet::kBlockHeight) {
            for (int bx = tile.x0; bx < tile.x1; bx += Packet::kBlockWidth) {
                ctx.cameraRays += static_cast<uint64_t>(gen.fillPacket(tile, bx, by, s, packet));
                ctx.world.accel->intersectPacket(packet.valid, packet.rays, RayCoherence::Coherent);
                for (int lane = 0; lane < N; ++lane) {
                    if (!packet.valid[lane]) continue;
                    Ray ray = packet.rays.ray(lane);
                    ray.tfar = kInfinity;  // the packet's tfar now holds the hit distance
                    ctx.shadeSample(packet.px[lane], packet.py[lane], ray, packet.rays.hit(lane),
                                    packet.sampler[lane]);
                }
            }
        }
    }
}

void renderTileSingle(TileContext& ctx, const TileRayGenerator& gen, const PixelRect& tile,
                      int s0, int s1) {
    Sampler sampler;
    for (int s = s0; s < s1; ++s) {
        for (int y = tile.y0; y < tile.y1; ++y) {
            for (int x = tile.x0; x < tile.x1; ++x) {
                const Ray ray = gen.sampleRay(x, y, s, sampler);
                ++ctx.cameraRays;
                ctx.shadeSample(x, y, ray, ctx.world.accel->intersect(ray), sampler);
            }
        }
    }
}

}  // namespace

int resolvePacketWidth(PacketMode mode, const Accel& accel) {
    switch (mode) {
        case PacketMode::Packet8: return 8;
        case PacketMode::Packet16: return 16;
        case PacketMode::Single: return 1;
        case PacketMode::Auto: break;
    }
    // Embree emulates wider packets on narrower ISAs, so anything but 16 means 8.
    return accel.nativePacketWidth() == 16 ? 16 : 8;
}

// The samples every pixel of `tile` already has in the film (0 for a new film,
// more when resuming from a checkpoint). Tiles are rendered whole, so all
// pixels of a tile agree unless the film was made with another tile size.
int tileStartSample(const Film& film, const PixelRect& tile) {
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
    const std::vector<PixelRect> tiles = cutTiles(film.crop(), options.tileSize);
    if (options.sampleOffset < 0 || options.sampleOffset > INT32_MAX - options.spp)
        fail("sample offset ", options.sampleOffset, " with ", options.spp,
             " samples per pixel is out of range");
    // The generator only asks whether there is more than one sample per pixel
    // (one alone goes through the pixel centre); a part of a split render is
    // part of a render of many.
    const TileRayGenerator generator(camera, options.seed,
                                     options.samplePart ? std::max(options.spp, 2) : options.spp,
                                     options.filter);

    RenderStats result;
    result.packetWidth = resolvePacketWidth(options.packets, *world.accel);
    std::vector<int> tileStart(tiles.size());
    int firstPass = options.spp;
    size_t work = 0;  // tile passes still to render
    for (size_t i = 0; i < tiles.size(); ++i) {
        tileStart[i] = tileStartSample(film, tiles[i]);
        if (tileStart[i] > options.spp)
            fail("the film already has ", tileStart[i], " samples per pixel, more than the ",
                 options.spp, " asked for");
        firstPass = std::min(firstPass, tileStart[i]);
        work += static_cast<size_t>(options.spp - tileStart[i]);
    }
    result.completedPasses = firstPass;

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
    for (int pass = firstPass; pass < options.spp; ++pass) {
        if (cancelled()) break;
        arena.execute([&] {
            // Grain 1: tiles are the unit of load balancing; they vary a lot in cost.
            tbb::parallel_for(
                tbb::blocked_range<size_t>(0, tiles.size(), 1),
                [&](const tbb::blocked_range<size_t>& range) {
                    for (size_t i = range.begin(); i != range.end(); ++i) {
                        // Tiles in flight finish; the rest of the pass is skipped.
                        if (tileStart[i] > pass || cancelled()) continue;
                        TileContext ctx{world, integrator, film, !film.aovs().empty(), {}, 0};
                        const int sample = options.sampleOffset + pass;  // the sampler's index
                        switch (result.packetWidth) {
                            case 16:
                                renderTilePackets<16>(ctx, generator, tiles[i], sample, sample + 1);
                                break;
                            case 8:
                                renderTilePackets<8>(ctx, generator, tiles[i], sample, sample + 1);
                                break;
                            default:
                                renderTileSingle(ctx, generator, tiles[i], sample, sample + 1);
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
        if (options.passDone && pass + 1 < options.spp && !options.passDone(pass + 1)) {
            result.stoppedEarly = true;
            break;
        }
    }
    result.cancelled = cancelled() && result.completedPasses < options.spp;

    if (options.progress) options.progress->end();
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.cameraRays = cameraRays;
    result.shadowRays = shadowRays;
    result.bounceRays = bounceRays;
    return result;
}

}  // namespace strahl
