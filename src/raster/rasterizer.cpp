// The rasterizer's two passes (interface and sampling rule in rasterizer.h,
// the per-triangle math in triangle_setup.cpp):
//  1. binning: fixed-size chunks of triangles are bounded in pixels in
//     parallel (clipped against the near plane), each chunk listing the
//     (tile, triangle, bounds) entries it produces; a counting sort over the
//     tiles then concatenates the chunks' lists in chunk order, so each tile's
//     list is in (geomID, primID) order and does not depend on the threads;
//  2. tiles in parallel: each tile builds its triangles' edge functions, tests
//     the pixel centres inside their bounds, z-tests the covered ones, then
//     shades its pixels.
// Determinism: a pixel keeps the smallest (t, geomID, primID) of the fragments
// that cover it — a total order, so neither the thread count nor the tile size
// can change which hit wins, and the t, u, v of a fragment depend only on the
// triangle and the pixel.
// Known waste: a triangle spanning several tiles builds its edge functions
// once per tile (storing them between the passes would cost ~80 bytes per
// triangle), and the counting sort's scatter is serial (28 bytes per
// (triangle, tile) pair).

#include "strahl/raster/rasterizer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <optional>
#include <utility>

#include "strahl/camera/tile_rays.h"
#include "strahl/core/error.h"
#include "strahl/integrator/camera_sample.h"
#include "triangle_setup.h"

namespace strahl {

namespace {

using raster::DVec3;
using raster::RasterView;
using raster::TriangleCoverage;
using raster::TrianglePlane;

constexpr std::array<std::string_view, 4> kRasterIntegrators = {"eyelight", "normal", "depth",
                                                                "primid"};

// Triangles per binning chunk: enough work to amortise a task, few enough
// chunks' lists to merge; fixed, so that the bins never depend on the threads.
constexpr uint32_t kChunkTriangles = 16384;

// How many triangles ahead the tile pass prefetches indices and vertices (the
// vertices' prefetch reads indices prefetched 16 triangles before). Chosen on
// the 1.4M-triangle benchmark mesh (bench_raster): about 10 % faster than no
// prefetch; 16/8 and 64/24 measured the same within noise.
constexpr std::ptrdiff_t kPrefetchIndices = 32;
constexpr std::ptrdiff_t kPrefetchVertices = 16;

struct TriangleRef {
    uint32_t geomID, primID;

    bool operator<(const TriangleRef& o) const {
        return geomID != o.geomID ? geomID < o.geomID : primID < o.primID;
    }
};

// Square tiles over the crop, row by row from its top left (as the ray tracer
// cuts them); the last column and row may be narrower.
class TileGrid {
public:
    TileGrid(const PixelRect& crop, int size)
        : crop_(crop),
          size_(size),
          columns_((crop.width() + size - 1) / size),
          rows_((crop.height() + size - 1) / size) {}

    size_t count() const { return static_cast<size_t>(columns_) * static_cast<size_t>(rows_); }
    PixelRect tile(size_t index) const {
        const int x = crop_.x0 + static_cast<int>(index % size_t(columns_)) * size_;
        const int y = crop_.y0 + static_cast<int>(index / size_t(columns_)) * size_;
        return {x, y, std::min(x + size_, crop_.x1), std::min(y + size_, crop_.y1)};
    }
    // Calls f(tile index) for every tile that `pixels` (inside the crop) overlaps.
    template <typename F>
    void forEachOverlapping(const PixelRect& pixels, F&& f) const {
        const int cx0 = (pixels.x0 - crop_.x0) / size_, cx1 = (pixels.x1 - 1 - crop_.x0) / size_;
        const int cy0 = (pixels.y0 - crop_.y0) / size_, cy1 = (pixels.y1 - 1 - crop_.y0) / size_;
        for (int cy = cy0; cy <= cy1; ++cy)
            for (int cx = cx0; cx <= cx1; ++cx)
                f(static_cast<size_t>(cy) * size_t(columns_) + size_t(cx));
    }

private:
    PixelRect crop_;
    int size_, columns_, rows_;
};

// What every pass reads: the meshes and the camera. Camera-space vertices are
// recomputed wherever they are needed rather than stored: the transform costs
// less than fetching a stored double-precision copy (twice the size of the
// float positions) from memory, and it is a pure function of the vertex, so a
// vertex shared by several triangles is bit-identical in all of them.
struct RasterScene {
    const World& world;
    RasterView view;

    const uint32_t* indices(const TriangleRef& ref) const {
        return &world.shapes[ref.geomID].mesh.indices[3 * size_t(ref.primID)];
    }
    void inWorld(const TriangleRef& ref, Vec3 out[3]) const {
        const std::vector<Vec3>& positions = world.shapes[ref.geomID].mesh.positions;
        const uint32_t* index = indices(ref);
        for (int k = 0; k < 3; ++k) out[k] = positions[index[k]];
    }
    void inCamera(const Vec3 world3[3], DVec3 out[3]) const {
        for (int k = 0; k < 3; ++k) out[k] = view.toCamera(world3[k]);
    }
    // Starts loading what inWorld(ref) will read: the vertices, if the indices
    // are already cached, else the indices.
    void prefetchIndices(const TriangleRef& ref) const { __builtin_prefetch(indices(ref)); }
    void prefetchVertices(const TriangleRef& ref) const {
        const std::vector<Vec3>& positions = world.shapes[ref.geomID].mesh.positions;
        const uint32_t* index = indices(ref);
        for (int k = 0; k < 3; ++k) __builtin_prefetch(&positions[index[k]]);
    }
    // Embree's geometric normal, computed like the watertight test computes it.
    Vec3 geometricNormal(const TriangleRef& ref) const {
        Vec3 p[3];
        inWorld(ref, p);
        return glm::cross(p[1] - p[0], p[2] - p[0]);
    }
};

// A triangle in a tile's list, with the pixels (in the whole crop) it may cover.
struct BinnedTriangle {
    TriangleRef ref;
    PixelRect pixels;
};

// Each tile's triangles: triangles[begin[tile], begin[tile + 1]).
struct Bins {
    std::vector<size_t> begin;
    std::vector<BinnedTriangle> triangles;
};

Bins binTriangles(const RasterScene& scene, const TileGrid& grid, const PixelRect& crop,
                  RasterStats& stats) {
    struct Chunk {
        uint32_t geomID, first, last;
    };
    std::vector<Chunk> chunks;
    for (size_t g = 0; g < scene.world.shapes.size(); ++g) {
        const auto triangles = static_cast<uint32_t>(scene.world.shapes[g].mesh.triangleCount());
        stats.triangles += triangles;
        for (uint32_t first = 0; first < triangles; first += kChunkTriangles)
            chunks.push_back(
                {static_cast<uint32_t>(g), first, std::min(triangles, first + kChunkTriangles)});
    }

    struct Entry {
        uint32_t tile;  // tile counts fit: at most 2^28 pixels
        BinnedTriangle triangle;
    };
    std::vector<std::vector<Entry>> entries(chunks.size());
    std::atomic<uint64_t> inView{0};
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, chunks.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t c = r.begin(); c != r.end(); ++c) {
                entries[c].reserve(chunks[c].last - chunks[c].first);
                uint64_t visible = 0;
                for (uint32_t prim = chunks[c].first; prim < chunks[c].last; ++prim) {
                    const TriangleRef ref{chunks[c].geomID, prim};
                    Vec3 world3[3];
                    scene.inWorld(ref, world3);
                    DVec3 cam[3];
                    scene.inCamera(world3, cam);
                    PixelRect pixels;
                    if (!raster::trianglePixels(scene.view, cam, crop, pixels)) continue;
                    ++visible;
                    grid.forEachOverlapping(pixels, [&](size_t tile) {
                        entries[c].push_back({static_cast<uint32_t>(tile), {ref, pixels}});
                    });
                }
                inView += visible;
            }
        });
    stats.trianglesInView = inView;

    // Counting sort by tile, stable: chunks in order, entries in order.
    Bins bins;
    bins.begin.assign(grid.count() + 1, 0);
    for (const auto& list : entries)
        for (const Entry& e : list) ++bins.begin[e.tile + 1];
    for (size_t t = 0; t < grid.count(); ++t) bins.begin[t + 1] += bins.begin[t];
    bins.triangles.resize(bins.begin.back());
    std::vector<size_t> next(bins.begin.begin(), bins.begin.end() - 1);
    for (const auto& list : entries)
        for (const Entry& e : list) bins.triangles[next[e.tile]++] = e.triangle;
    return bins;
}

struct TileCounters {
    uint64_t fragments = 0;
    uint64_t coveredPixels = 0;
};

// Rasterizes one tile, then hands every pixel of it, row by row, to
// sink(x, y, ray, hit, rng): the pixel's camera ray, its first hit (invalid if
// none) and the sample generator the ray tracer would have given it.
template <typename Sink>
void rasterizeTile(const RasterScene& scene, const TileRayGenerator& rays, const PixelRect& tile,
                   const BinnedTriangle* first, const BinnedTriangle* last, TileCounters& counters,
                   Sink&& sink) {
    const int width = tile.width();
    const auto pixels = static_cast<size_t>(tile.area());
    std::vector<double> centreU(static_cast<size_t>(width)), centreV(size_t(tile.height()));
    for (int x = tile.x0; x < tile.x1; ++x) centreU[size_t(x - tile.x0)] = scene.view.centreU(x);
    for (int y = tile.y0; y < tile.y1; ++y) centreV[size_t(y - tile.y0)] = scene.view.centreV(y);
    std::vector<Ray> cameraRays(pixels);
    std::vector<Sampler> rngs(pixels);
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x) {
            const size_t k = size_t(y - tile.y0) * size_t(width) + size_t(x - tile.x0);
            cameraRays[k] = rays.sampleRay(x, y, 0, rngs[k]);
        }

    std::vector<Hit> hits(pixels);  // t = +inf, invalid
    for (const BinnedTriangle* triangle = first; triangle != last; ++triangle) {
        // A tile's triangles lie anywhere in the meshes: fetching their indices
        // and then vertices is a chain of two cache misses each, which
        // dominates the pass for small triangles unless started in advance.
        if (last - triangle > kPrefetchIndices)
            scene.prefetchIndices(triangle[kPrefetchIndices].ref);
        if (last - triangle > kPrefetchVertices)
            scene.prefetchVertices(triangle[kPrefetchVertices].ref);
        const TriangleRef& ref = triangle->ref;
        const PixelRect r{
            std::max(triangle->pixels.x0, tile.x0), std::max(triangle->pixels.y0, tile.y0),
            std::min(triangle->pixels.x1, tile.x1), std::min(triangle->pixels.y1, tile.y1)};
        Vec3 world3[3];
        scene.inWorld(ref, world3);
        DVec3 cam[3];
        scene.inCamera(world3, cam);
        const TriangleCoverage coverage = raster::triangleCoverage(scene.view, cam);
        std::optional<TrianglePlane> plane;  // built at the first covered pixel, if any
        for (int y = r.y0; y < r.y1; ++y) {
            const double v = centreV[size_t(y - tile.y0)];
            for (int x = r.x0; x < r.x1; ++x) {
                double weights[3];
                if (!coverage.covers(centreU[size_t(x - tile.x0)], v, weights)) continue;
                if (!plane) plane.emplace(world3);
                const size_t k = size_t(y - tile.y0) * size_t(width) + size_t(x - tile.x0);
                const Ray& ray = cameraRays[k];
                // The hit the ray tracer would accept: tnear < t < tfar, as float.
                const auto t = static_cast<float>(plane->rayParameter(ray));
                if (!(t > ray.tnear && t < ray.tfar)) continue;
                ++counters.fragments;
                Hit& best = hits[k];
                const bool nearer =
                    t < best.t || (t == best.t && ref < TriangleRef{best.geomID, best.primID});
                if (!nearer) continue;
                // > 0: the weights are all >= 0 and, for a triangle seen with
                // nonzero area, not all 0.
                const double sum = weights[0] + weights[1] + weights[2];
                best.t = t;
                best.u = static_cast<float>(weights[1] / sum);
                best.v = static_cast<float>(weights[2] / sum);
                best.geomID = ref.geomID;
                best.primID = ref.primID;
            }
        }
    }

    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x) {
            const size_t k = size_t(y - tile.y0) * size_t(width) + size_t(x - tile.x0);
            Hit& hit = hits[k];
            if (hit.valid()) {
                hit.Ng = scene.geometricNormal({hit.geomID, hit.primID});
                ++counters.coveredPixels;
            }
            sink(x, y, cameraRays[k], hit, rngs[k]);
        }
}

// Both passes over `crop`; makeSink() gives each tile task its sink.
template <typename MakeSink>
RasterStats rasterize(const World& world, const Camera& camera, const PixelRect& crop,
                      const RenderOptions& options, MakeSink&& makeSink) {
    if (options.tileSize < 1) fail("tile size must be at least 1, got ", options.tileSize);
    requireRasterizable(world);
    const auto start = std::chrono::steady_clock::now();
    RasterStats stats;
    const TileGrid grid(crop, options.tileSize);
    const TileRayGenerator rays(camera, options.seed, 1);
    if (options.progress) options.progress->begin("raster", grid.count());

    std::atomic<uint64_t> fragments{0}, coveredPixels{0};
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        const RasterView view(camera);
        const RasterScene scene{world, view};
        const Bins bins = binTriangles(scene, grid, crop, stats);
        // Grain 1: tiles are the unit of load balancing; they vary a lot in cost.
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, grid.count(), 1),
            [&](const tbb::blocked_range<size_t>& r) {
                for (size_t i = r.begin(); i != r.end(); ++i) {
                    TileCounters counters;
                    const BinnedTriangle* triangles = bins.triangles.data();
                    rasterizeTile(scene, rays, grid.tile(i), triangles + bins.begin[i],
                                  triangles + bins.begin[i + 1], counters, makeSink());
                    fragments += counters.fragments;
                    coveredPixels += counters.coveredPixels;
                    if (options.progress) options.progress->advance(1);
                }
            },
            tbb::simple_partitioner());
    });

    if (options.progress) options.progress->end();
    stats.fragments = fragments;
    stats.coveredPixels = coveredPixels;
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
}

std::string choices() {
    std::string list;
    for (std::string_view n : kRasterIntegrators)
        list += (list.empty() ? "" : ", ") + std::string(n);
    return list;
}

}  // namespace

std::span<const std::string_view> rasterIntegratorNames() {
    return kRasterIntegrators;
}

void requireRasterSettings(std::string_view integrator, int spp) {
    if (std::find(kRasterIntegrators.begin(), kRasterIntegrators.end(), integrator) ==
        kRasterIntegrators.end())
        fail("the rasterizer cannot shade integrator '", integrator,
             "': it sees first hits only and supports ", choices(),
             "; use --algorithm raytrace for the others");
    if (spp != 1)
        fail("the rasterizer takes one sample per pixel, at its centre: spp must be 1, got ", spp,
             "; use --algorithm raytrace for more");
}

void requireRasterizable(const World& world) {
    for (const SceneShape& shape : world.shapes)
        if (!shape.isMesh())
            fail("the rasterizer draws triangle meshes only, but shape '", shape.name, "' is ",
                 shape.user->describe(), "; use --algorithm raytrace for it");
        else if (shape.cutout)
            fail("the rasterizer draws solid triangles only, but shape '", shape.name,
                 "' has a material with an opacity (a cut-out); use --algorithm raytrace for it");
        else if (shape.mesh.deforms())
            fail("the rasterizer draws meshes at rest only, but shape '", shape.name,
                 "' deforms (motion blur); use --algorithm raytrace for it");
    if (!world.instances.empty())
        fail("the rasterizer draws top-level meshes only, but the scene has ",
             world.instances.size(), " instance(s); use --algorithm raytrace for it");
}

std::vector<Hit> rasterizeHits(const World& world, const Camera& camera, const PixelRect& crop,
                               const RenderOptions& options, RasterStats* stats) {
    std::vector<Hit> hits(static_cast<size_t>(crop.area()));
    const RasterStats result = rasterize(world, camera, crop, options, [&] {
        return [&](int x, int y, const Ray&, const Hit& hit, Sampler&) {
            hits[size_t(y - crop.y0) * size_t(crop.width()) + size_t(x - crop.x0)] = hit;
        };
    });
    if (stats) *stats = result;
    return hits;
}

RasterStats rasterizeImage(const World& world, const Camera& camera, const Integrator& integrator,
                           Film& film, const RenderOptions& options) {
    requireRasterSettings(integrator.name(), options.spp);
    const bool wantAovs = !film.aovs().empty();
    return rasterize(world, camera, film.crop(), options, [&] {
        // One per tile: the debug integrators trace nothing, so the counters
        // stay empty, but shade() wants them.
        return [&, stats = ShadingStats{}](int x, int y, const Ray& ray, const Hit& hit,
                                           Sampler& rng) mutable {
            const CameraSample sample =
                shadeCameraSample(world, integrator, ray, hit, rng, stats, wantAovs);
            film.addSample(x, y, sample.radiance, sample.aov);
        };
    });
}

}  // namespace strahl
