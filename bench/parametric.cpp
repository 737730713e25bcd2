// Parametric surfaces, direct vs tessellated (issue 4: "Mrays/s and memory of
// direct vs tessellated at equal maximum silhouette error, for the sphere,
// torus and teapot; tessellation speed (triangles/s)").
//
// Surfaces: the sphere r = 1, the torus R = 1, r = 0.35, and the Utah teapot
// (scenes/data/teapot.bpt, 32 bicubic Bézier patches), each in object space.
//
// Modes, each as the only shape of its own Embree accelerator:
//   direct      ParametricShape with default options: Embree user geometry over
//               sub-patches, Newton on f itself. Its geometric error is its
//               Newton tolerance, relativeTolerance x extent = 1e-9 x extent.
//   tess-px     tessellateParametric over an adaptive grid whose maximum chordal
//               error (ParametricGridOptions::maxChordError) is half a pixel's
//               footprint at the nearest point of the object for this camera:
//               the silhouette is within half a pixel of the true one.
//   tess-1e-5   the same at 1e-5 x extent, a "near-exact" tessellation (no
//               tessellation reaches the direct mode's 1e-9 in memory). If it
//               would exceed kMemoryBudget the error is doubled until it fits,
//               and the run says so.
// "extent" is parametricExtent(): the diagonal of the surface's box.
//
// Camera: 512 x 512, 40° field of view, looking at the centre of the object's
// bounding sphere (radius ρ) from azimuth -60°, elevation 30° (z up), at the
// distance D = 1.1 ρ / sin 20° where the whole sphere fits the frame. Half a
// pixel's footprint at the nearest point, D - ρ, is the tess-px error.
//
// Before anything is timed, every configuration's camera rays are traced once
// as single rays and once as packets, and the hit masks are compared: packets
// against single rays of the same mode, and each tessellation against the
// direct mode. The benchmark aborts if any pair disagrees on more than 0.5 %
// of the pixels that either hits. It also prints where the time goes: the
// camera rays split by the direct mode's answer (misses by their distance in
// pixels from the nearest hit, frontal and grazing hits), each class traced on
// one thread in every mode.
//
// Timed cases (all in kRounds interleaved rounds, so each ratio pairs cases
// measured back to back in one process):
//   <surface>/<mode>/packets   camera rays as 16-wide packets (4x4 pixels) over
//   <surface>/<mode>/single    32x32 tiles, or one ray at a time; tiles traced
//                              in parallel on all threads; only traversal and
//                              intersection are timed.
//   <surface>/tessellate       buildParametricGrid + tessellateParametric at an
//                              error fine enough for >= 1M triangles, one thread.
// Counters: Mrays/s; MB = shape memoryBytes() (mesh + (u, v) table for a
// tessellation, sub-patch table for direct) + Embree's bytes in use for the
// BVH; prims (triangles or sub-patches); build_ms (shape + BVH, fastest of 3);
// rel_err (error / extent); dir/tess = direct / this configuration's Mrays/s
// (from the direct case of the same round) and memory.
// The run ends with a summary table from each case's fastest round.
//
// Usage: bench_parametric [google-benchmark flags]

#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "strahl/accel/accel.h"
#include "strahl/camera/camera.h"
#include "strahl/camera/tile_rays.h"
#include "strahl/geometry/bezier_patches.h"
#include "strahl/geometry/parametric_builtins.h"
#include "strahl/geometry/parametric_grid.h"
#include "strahl/geometry/parametric_shape.h"
#include "strahl/geometry/parametric_tessellation.h"
#include "strahl/meshio/bezier_file.h"
#include "strahl/render/renderer.h"

namespace strahl::bench {
namespace {

constexpr int kSize = 512;
constexpr int kTile = 32;
constexpr int kRounds = 3;
constexpr float kFovDegrees = 40.0f;
constexpr double kFrameMargin = 1.1;  // bounding sphere radius / radius that exactly fits
constexpr float kAzimuthDegrees = -60.0f, kElevationDegrees = 30.0f;
constexpr double kNearExactRelativeError = 1e-5;
constexpr double kMemoryBudget = 2.0 * 1024 * 1024 * 1024;
// Estimated bytes per grid cell of a tessellation: two triangles (indices and
// Embree BVH, ~90 B each) and one vertex (position and (u, v)).
constexpr double kEstimatedBytesPerCell = 2 * (12 + 90) + 12 + 8;
constexpr double kSpeedTriangles = 1e6;  // tessellation-speed cases tessellate at least this many
constexpr double kMinAgreement = 0.995;  // of the pixels either configuration hits
constexpr int kBuildRepeats = 3;
constexpr int kCostPasses = 2;            // single-thread cost classes: best of
constexpr double kGrazingCosine = 0.25;   // ParametricShape's own grazing threshold

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

constexpr double kPixels = double(kSize) * kSize;

// ---- camera rays --------------------------------------------------------------

struct PixelRay {
    Ray ray;
    int pixel;  // y * kSize + x
};

struct CameraRays {
    std::vector<std::vector<CameraPacket<16>>> packets;  // per tile
    std::vector<std::vector<PixelRay>> single;           // per tile
};

CameraRays makeCameraRays(const Camera& camera) {
    CameraRays rays;
    const TileRayGenerator gen(camera, 0, 1);
    for (const PixelRect& tile : cutTiles(PixelRect{0, 0, kSize, kSize}, kTile)) {
        rays.packets.push_back(gen.tilePackets<16>(tile, 0));
        std::vector<PixelRay>& single = rays.single.emplace_back();
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                Sampler rng;
                single.push_back({gen.sampleRay(x, y, 0, rng), y * kSize + x});
            }
    }
    return rays;
}

// Traces every camera ray once on all threads; returns the number of hits.
size_t tracePackets(const Accel& accel, const CameraRays& rays) {
    std::atomic<size_t> hits{0};
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, rays.packets.size(), 1),
        [&](const tbb::blocked_range<size_t>& r) {
            size_t tileHits = 0;
            for (size_t i = r.begin(); i != r.end(); ++i)
                for (const CameraPacket<16>& source : rays.packets[i]) {
                    RayHitPacket16 p;
                    std::memcpy(&p, &source.rays, sizeof p);  // fresh tfar/geomID
                    accel.intersect16(source.valid, p, RayCoherence::Coherent);
                    for (int lane = 0; lane < 16; ++lane)
                        tileHits += source.valid[lane] && p.geomID[lane] != kInvalidId;
                }
            hits += tileHits;
        },
        tbb::simple_partitioner());
    return hits.load();
}

size_t traceSingle(const Accel& accel, const CameraRays& rays) {
    std::atomic<size_t> hits{0};
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, rays.single.size(), 1),
        [&](const tbb::blocked_range<size_t>& r) {
            size_t tileHits = 0;
            for (size_t i = r.begin(); i != r.end(); ++i)
                for (const PixelRay& pr : rays.single[i]) tileHits += accel.intersect(pr.ray).valid();
            hits += tileHits;
        },
        tbb::simple_partitioner());
    return hits.load();
}

// The hit of every pixel's camera ray, single rays, and the hit distance of
// every pixel traced as packets (infinity for a miss).
std::vector<Hit> recordSingle(const Accel& accel, const CameraRays& rays) {
    std::vector<Hit> hits(size_t(kSize) * kSize);
    tbb::parallel_for(size_t(0), rays.single.size(), [&](size_t i) {
        for (const PixelRay& pr : rays.single[i]) hits[size_t(pr.pixel)] = accel.intersect(pr.ray);
    });
    return hits;
}

std::vector<float> recordPackets(const Accel& accel, const CameraRays& rays) {
    std::vector<float> t(size_t(kSize) * kSize, kInfinity);
    tbb::parallel_for(size_t(0), rays.packets.size(), [&](size_t i) {
        for (const CameraPacket<16>& source : rays.packets[i]) {
            RayHitPacket16 p;
            std::memcpy(&p, &source.rays, sizeof p);
            accel.intersect16(source.valid, p, RayCoherence::Coherent);
            for (int lane = 0; lane < 16; ++lane)
                if (source.valid[lane] && p.geomID[lane] != kInvalidId)
                    t[size_t(source.py[lane] * kSize + source.px[lane])] = p.tfar[lane];
        }
    });
    return t;
}

// ---- surfaces and configurations -------------------------------------------------

enum class Mode { Direct, TessPixel, TessNearExact };
const char* modeName(Mode m) {
    switch (m) {
    case Mode::Direct: return "direct";
    case Mode::TessPixel: return "tess-px";
    case Mode::TessNearExact: return "tess-1e-5";
    }
    return "?";
}

// One way of tracing one surface: its shape, its accelerator, what it cost.
// Held by pointer and never moved (the accelerator points into the shape).
struct Config {
    Mode mode = Mode::Direct;
    double error = 0.0;          // object space: Newton tolerance or max chordal error
    bool gridCapped = false;     // some grid direction stopped at maxSegments
    bool budgetCapped = false;   // the error was raised to fit kMemoryBudget
    size_t primitives = 0;       // sub-patches or triangles
    double buildSeconds = 0.0;   // fastest of kBuildRepeats: shape (grid, tessellation) + BVH
    size_t shapeBytes = 0, bvhBytes = 0;
    // Declared before the accelerator, so destroyed after it.
    std::unique_ptr<ParametricShape> direct;
    TriangleMesh mesh;
    std::unique_ptr<TessellatedSurface> tessellated;
    std::unique_ptr<Accel> accel;

    double megabytes() const { return double(shapeBytes + bvhBytes) / (1 << 20); }
};

struct Subject {
    std::string name;
    ParametricSurfacePtr surface;
    double extent = 0.0;
    DVec3 centre{0.0};
    double radius = 0.0;  // bounding sphere about centre
    std::optional<Camera> camera;
    double eyeDistance = 0.0;
    double halfPixelError = 0.0;
    CameraRays rays;
    std::vector<std::unique_ptr<Config>> configs;  // Direct, TessPixel, TessNearExact
    double speedError = 0.0;                       // the tessellation-speed cases' chordal error
    size_t speedTriangles = 0;
};

// Bounding sphere of a 65 x 65 grid of points per patch, about their box's centre.
void boundingSphere(const ParametricSurface& s, DVec3& centre, double& radius) {
    constexpr int n = 64;
    const ParamDomain& d = s.domain();
    std::vector<DVec3> points;
    DVec3 lo(1e300), hi(-1e300);
    for (uint32_t p = 0; p < s.patchCount(); ++p)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                points.push_back(s.point(p, d.u0 + d.width() * i / n, d.v0 + d.height() * j / n));
                lo = glm::min(lo, points.back());
                hi = glm::max(hi, points.back());
            }
    centre = 0.5 * (lo + hi);
    radius = 0.0;
    for (const DVec3& x : points) radius = std::max(radius, glm::length(x - centre));
}

std::unique_ptr<Config> buildDirect(const Subject& s) {
    auto c = std::make_unique<Config>();
    c->mode = Mode::Direct;
    const auto start = Clock::now();
    c->direct = std::make_unique<ParametricShape>(s.surface, Mat4(1.0f), ParametricShapeOptions{});
    const ShapeRef refs[] = {ShapeRef{nullptr, c->direct.get()}};
    c->accel = buildEmbreeAccel(refs, {});
    c->buildSeconds = secondsSince(start);
    c->error = c->direct->tolerance();
    c->primitives = c->direct->primitiveCount();
    c->shapeBytes = c->direct->memoryBytes();
    c->bvhBytes = c->accel->memoryBytes();
    return c;
}

std::unique_ptr<Config> buildTessellated(const Subject& s, Mode mode, double error) {
    auto c = std::make_unique<Config>();
    c->mode = mode;
    ParametricGridOptions options;
    options.maxChordError = error;
    const auto start = Clock::now();
    ParametricGrid grid = buildParametricGrid(*s.surface, options);
    while (double(grid.cellCount()) * kEstimatedBytesPerCell > kMemoryBudget) {
        options.maxChordError *= 2.0;
        c->budgetCapped = true;
        grid = buildParametricGrid(*s.surface, options);
    }
    Tessellation t = tessellateParametric(*s.surface, grid, ParametricNormals::Exact);
    c->mesh = std::move(t.mesh);
    c->mesh.reservePadding();  // so Embree shares the vertices instead of copying them
    c->tessellated = std::make_unique<TessellatedSurface>(s.surface, std::move(t), Mat4(1.0f),
                                                          ParametricNormals::Exact);
    const TriangleMesh* meshes[] = {&c->mesh};
    c->accel = buildEmbreeAccel(meshes, {});
    c->buildSeconds = secondsSince(start);
    c->error = options.maxChordError;
    c->gridCapped = grid.capped;
    c->primitives = c->mesh.triangleCount();
    c->shapeBytes = c->mesh.memoryBytes() + c->tessellated->memoryBytes();
    c->bvhBytes = c->accel->memoryBytes();
    return c;
}

// Builds kBuildRepeats times, keeps the last and the fastest build time.
std::unique_ptr<Config> buildBest(const std::function<std::unique_ptr<Config>()>& build) {
    std::unique_ptr<Config> best;
    double fastest = 1e300;
    for (int i = 0; i < kBuildRepeats; ++i) {
        best.reset();  // one at a time: memory figures are per configuration
        best = build();
        fastest = std::min(fastest, best->buildSeconds);
    }
    best->buildSeconds = fastest;
    return best;
}

Subject makeSubject(std::string name, ParametricSurfacePtr surface) {
    Subject s;
    s.name = std::move(name);
    s.surface = std::move(surface);
    s.extent = parametricExtent(*s.surface);
    boundingSphere(*s.surface, s.centre, s.radius);

    const double halfFov = glm::radians(0.5 * double(kFovDegrees));
    s.eyeDistance = kFrameMargin * s.radius / std::sin(halfFov);
    const float az = glm::radians(kAzimuthDegrees), el = glm::radians(kElevationDegrees);
    const Vec3 back(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    const Vec3 centre(s.centre);
    const Vec3 eye = centre + float(s.eyeDistance) * back;
    s.camera.emplace(CameraFrame::lookAt(eye, centre, Vec3(0.0f, 0.0f, 1.0f)),
                     Projection::Perspective,
                     Camera::windowFromFov(glm::radians(kFovDegrees), 1.0f, kSize, kSize), 1.0f,
                     kSize, kSize);
    // A pixel subtends (t - b) / ny / d per unit distance; its footprint is
    // smallest at the nearest point of the object.
    const ImageWindow& w = s.camera->window();
    const double pixelPerDistance = double(w.t - w.b) / kSize / double(s.camera->focalDistance());
    s.halfPixelError = 0.5 * pixelPerDistance * (s.eyeDistance - s.radius);
    s.rays = makeCameraRays(*s.camera);

    s.configs.push_back(buildBest([&] { return buildDirect(s); }));
    s.configs.push_back(
        buildBest([&] { return buildTessellated(s, Mode::TessPixel, s.halfPixelError); }));
    s.configs.push_back(buildBest([&] {
        return buildTessellated(s, Mode::TessNearExact, kNearExactRelativeError * s.extent);
    }));

    // The speed cases' error: halve the near-exact one until the grid gives
    // >= 1M triangles (two per cell; a pole drops a few, so aim 5 % higher).
    ParametricGridOptions options;
    options.maxChordError = kNearExactRelativeError * s.extent;
    while (2.0 * double(buildParametricGrid(*s.surface, options).cellCount()) <
           1.05 * kSpeedTriangles)
        options.maxChordError *= 0.5;
    s.speedError = options.maxChordError;
    return s;
}

// ---- correctness checks -------------------------------------------------------------

struct Agreement {
    size_t either = 0, differ = 0;  // pixels hit by either; hit by exactly one
    double share() const { return either ? 1.0 - double(differ) / double(either) : 1.0; }
};

Agreement compareMasks(const std::vector<float>& a, const std::vector<float>& b) {
    Agreement g;
    for (size_t i = 0; i < a.size(); ++i) {
        const bool ha = a[i] < kInfinity, hb = b[i] < kInfinity;
        g.either += ha || hb;
        g.differ += ha != hb;
    }
    return g;
}

std::vector<float> depths(const std::vector<Hit>& hits) {
    std::vector<float> t(hits.size());
    for (size_t i = 0; i < hits.size(); ++i) t[i] = hits[i].valid() ? hits[i].t : kInfinity;
    return t;
}

// Quantile q of |t_a - t_b| over the pixels both hit.
double depthQuantile(const std::vector<float>& a, const std::vector<float>& b, double q) {
    std::vector<double> d;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i] < kInfinity && b[i] < kInfinity) d.push_back(std::abs(double(a[i]) - double(b[i])));
    if (d.empty()) return 0.0;
    const size_t k = std::min(d.size() - 1, size_t(q * double(d.size())));
    std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(k), d.end());
    return d[k];
}

// Checks every configuration of `s`; prints what it found; false on a failure.
bool checkSubject(const Subject& s) {
    bool ok = true;
    const std::vector<Hit> directHits = recordSingle(*s.configs[0]->accel, s.rays);
    const std::vector<float> directT = depths(directHits);
    for (const auto& c : s.configs) {
        const std::vector<float> single =
            c->mode == Mode::Direct ? directT : depths(recordSingle(*c->accel, s.rays));
        const std::vector<float> packets = recordPackets(*c->accel, s.rays);
        const Agreement self = compareMasks(single, packets);
        std::printf("  %-9s hits %zu pixels; packets vs single: %zu differ (%.4f %% agree)", modeName(c->mode),
                    size_t(std::count_if(single.begin(), single.end(),
                                         [](float t) { return t < kInfinity; })),
                    self.differ, 100.0 * self.share());
        if (self.share() < kMinAgreement) {
            std::printf("  FAIL");
            ok = false;
        }
        if (c->mode != Mode::Direct) {
            const Agreement g = compareMasks(directT, single);
            std::printf("; vs direct: %zu of %zu differ (%.4f %% agree), |dt| median %.2g, "
                        "99%% %.2g, max %.2g (x extent)",
                        g.differ, g.either, 100.0 * g.share(),
                        depthQuantile(directT, single, 0.5) / s.extent,
                        depthQuantile(directT, single, 0.99) / s.extent,
                        depthQuantile(directT, single, 1.0) / s.extent);
            if (g.share() < kMinAgreement) {
                std::printf("  FAIL");
                ok = false;
            }
        }
        std::printf("\n");
    }
    return ok;
}

// Chessboard distance of every pixel to the nearest pixel with a hit (two-pass
// distance transform), capped at kSize.
std::vector<int> distanceToHit(const std::vector<Hit>& hits) {
    std::vector<int> d(hits.size());
    for (size_t i = 0; i < hits.size(); ++i) d[i] = hits[i].valid() ? 0 : kSize;
    auto at = [&](int x, int y) -> int& { return d[size_t(y * kSize + x)]; };
    auto relax = [&](int x, int y, int nx, int ny) {
        if (nx >= 0 && nx < kSize && ny >= 0 && ny < kSize) at(x, y) = std::min(at(x, y), at(nx, ny) + 1);
    };
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            for (int i = -1; i <= 1; ++i) relax(x, y, x + i, y - 1);
            relax(x, y, x - 1, y);
        }
    for (int y = kSize - 1; y >= 0; --y)
        for (int x = kSize - 1; x >= 0; --x) {
            for (int i = -1; i <= 1; ++i) relax(x, y, x + i, y + 1);
            relax(x, y, x + 1, y);
        }
    return d;
}

// Whether the ray passes through the box (slab test, t >= 0).
bool crossesBox(const Ray& r, const Bounds3& b) {
    float t0 = 0.0f, t1 = kInfinity;
    for (int a = 0; a < 3; ++a) {
        const float inv = 1.0f / r.dir[a];
        float ta = (b.min[a] - r.origin[a]) * inv, tb = (b.max[a] - r.origin[a]) * inv;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 <= t1;
}

// Where the direct mode's time goes: the camera rays split by what the direct
// mode answers for them — misses by their distance in pixels from the nearest
// hit pixel, hits frontal or grazing (|cos(Ng, d)| < kGrazingCosine) — each
// class traced on one thread in every configuration (ns per ray, best of
// kCostPasses), with the direct mode's share of the frame time and the mean
// number of sub-patch boxes on the rays' paths.
void printCostClasses(const Subject& s) {
    const ParametricShape& shape = *s.configs[0]->direct;
    const std::vector<Hit> directHits = recordSingle(*s.configs[0]->accel, s.rays);
    const std::vector<int> distance = distanceToHit(directHits);
    constexpr int kClasses = 5;
    const char* names[kClasses] = {"miss >16px", "miss 3-16px", "miss <=2px", "hit frontal",
                                   "hit grazing"};
    std::vector<Ray> classes[kClasses];
    for (const auto& tile : s.rays.single)
        for (const PixelRay& pr : tile) {
            const Hit& h = directHits[size_t(pr.pixel)];
            const int d = distance[size_t(pr.pixel)];
            int k = d > 16 ? 0 : d > 2 ? 1 : 2;
            if (h.valid()) {
                const float cosine =
                    std::abs(glm::dot(glm::normalize(h.Ng), glm::normalize(pr.ray.dir)));
                k = cosine < float(kGrazingCosine) ? 4 : 3;
            }
            classes[k].push_back(pr.ray);
        }
    std::printf("  single-thread ns/ray by the direct mode's answer (|cos| < %.2f: grazing):\n",
                kGrazingCosine);
    std::printf("    %-22s", "");
    for (const char* n : names) std::printf(" %12s", n);
    std::printf("\n    %-22s", "rays");
    for (const auto& c : classes) std::printf(" %12zu", c.size());
    std::printf("\n    %-22s", "sub-patch boxes/ray");
    for (const auto& rays : classes) {
        std::atomic<size_t> crossed{0};
        tbb::parallel_for(size_t(0), rays.size(), [&](size_t i) {
            size_t n = 0;
            for (uint32_t prim = 0; prim < shape.primitiveCount(); ++prim)
                n += crossesBox(rays[i], shape.primitiveBounds(prim));
            crossed += n;
        });
        std::printf(" %12.2f", rays.empty() ? 0.0 : double(crossed.load()) / double(rays.size()));
    }
    std::printf("\n");
    for (const auto& c : s.configs) {
        double seconds[kClasses], total = 0.0;
        for (int k = 0; k < kClasses; ++k) {
            double best = 1e300;
            for (int pass = 0; pass < kCostPasses; ++pass) {
                const auto start = Clock::now();
                size_t hits = 0;
                for (const Ray& r : classes[k]) hits += c->accel->intersect(r).valid();
                benchmark::DoNotOptimize(hits);
                best = std::min(best, secondsSince(start));
            }
            seconds[k] = best;
            total += best;
        }
        std::printf("    %-22s", (std::string(modeName(c->mode)) + " ns/ray").c_str());
        for (int k = 0; k < kClasses; ++k)
            std::printf(" %12.1f", classes[k].empty() ? 0.0 : seconds[k] / double(classes[k].size()) * 1e9);
        std::printf("\n    %-22s", (std::string(modeName(c->mode)) + " share of time").c_str());
        for (int k = 0; k < kClasses; ++k) std::printf(" %11.1f%%", 100.0 * seconds[k] / total);
        std::printf("   (%.3f s per frame)\n", total);
    }
}

// ---- benchmarks ------------------------------------------------------------------------

std::vector<Subject>& subjects() {
    static std::vector<Subject> all;
    return all;
}

// The latest Mrays/s of every direct case, for the ratio counters of the
// tessellated cases that follow it in the same round.
std::map<std::string, double>& latestDirect() {
    static std::map<std::string, double> m;
    return m;
}

void traceCase(benchmark::State& state, const Subject& s, const Config& c, bool packets) {
    size_t iterations = 0;
    const auto start = Clock::now();
    for (auto _ : state) {
        benchmark::DoNotOptimize(packets ? tracePackets(*c.accel, s.rays) : traceSingle(*c.accel, s.rays));
        ++iterations;
    }
    const double mrays = double(iterations) * kPixels / secondsSince(start) / 1e6;
    const std::string key = s.name + (packets ? "/packets" : "/single");
    if (c.mode == Mode::Direct) latestDirect()[key] = mrays;
    const double direct = latestDirect().count(key) ? latestDirect()[key] : 0.0;
    const Config& d = *s.configs[0];
    state.counters["Mrays/s"] = mrays;
    state.counters["MB"] = c.megabytes();
    state.counters["prims"] = double(c.primitives);
    state.counters["build_ms"] = c.buildSeconds * 1e3;
    state.counters["rel_err"] = c.error / s.extent;
    state.counters["dir/tess_Mrays"] = direct / mrays;
    state.counters["dir/tess_MB"] = d.megabytes() / c.megabytes();
}

void tessellateCase(benchmark::State& state, const Subject& s) {
    ParametricGridOptions options;
    options.maxChordError = s.speedError;
    size_t triangles = 0;
    double gridSeconds = 0.0, total = 0.0;
    for (auto _ : state) {
        const auto start = Clock::now();
        const ParametricGrid grid = buildParametricGrid(*s.surface, options);
        gridSeconds += secondsSince(start);
        const Tessellation t = tessellateParametric(*s.surface, grid, ParametricNormals::Exact);
        total += secondsSince(start);
        triangles = t.mesh.triangleCount();
        benchmark::DoNotOptimize(t.mesh.indices.data());
    }
    const double iterations = double(state.iterations());
    state.counters["tris"] = double(triangles);
    state.counters["Mtris/s"] = double(triangles) * iterations / total / 1e6;
    state.counters["grid_share"] = gridSeconds / total;
    state.counters["rel_err"] = s.speedError / s.extent;
}

// Console output as usual; remembers each case's best counters over the rounds.
class BestRoundReporter : public benchmark::ConsoleReporter {
public:
    BestRoundReporter() : ConsoleReporter(isatty(fileno(stdout)) ? OO_ColorTabular : OO_Tabular) {}

    void ReportRuns(const std::vector<Run>& runs) override {
        ConsoleReporter::ReportRuns(runs);
        for (const Run& run : runs) {
            if (run.run_type != Run::RT_Iteration || run.iterations == 0) continue;
            for (const char* counter : {"Mrays/s", "Mtris/s"}) {
                const auto it = run.counters.find(counter);
                if (it == run.counters.end()) continue;
                double& best = best_[run.run_name.function_name];
                best = std::max(best, it->second.value);
            }
        }
    }
    bool has(const std::string& name) const { return best_.count(name) != 0; }
    double best(const std::string& name) const { return best_.at(name); }

private:
    std::map<std::string, double> best_;
};

void printSummary(const BestRoundReporter& r) {
    std::printf("\nfastest round of %d (ratios: direct / this, both from the same run):\n", kRounds);
    std::printf("%-7s %-9s %9s %9s %8s %9s %8s %8s %8s %9s %9s %8s %8s %8s\n", "surface",
                "mode", "error", "err/ext", "prims", "build ms", "shape MB", "BVH MB", "MB",
                "pkt Mr/s", "sgl Mr/s", "d/t pkt", "d/t sgl", "d/t MB");
    for (const Subject& s : subjects()) {
        const Config& d = *s.configs[0];
        for (const auto& c : s.configs) {
            const std::string base = s.name + "/" + modeName(c->mode) + "/";
            const std::string dbase = s.name + "/direct/";
            auto value = [&](const std::string& k) { return r.has(base + k) ? r.best(base + k) : 0.0; };
            auto ratio = [&](const std::string& k) {
                return r.has(base + k) && r.has(dbase + k) ? r.best(dbase + k) / r.best(base + k) : 0.0;
            };
            std::printf("%-7s %-9s %9.3g %9.3g %8zu %9.1f %8.3f %8.3f %8.3f %9.3g %9.3g %8.3g "
                        "%8.3g %8.3g%s%s\n",
                        s.name.c_str(), modeName(c->mode), c->error, c->error / s.extent,
                        c->primitives, c->buildSeconds * 1e3, double(c->shapeBytes) / (1 << 20),
                        double(c->bvhBytes) / (1 << 20), c->megabytes(), value("packets"),
                        value("single"), ratio("packets"), ratio("single"),
                        d.megabytes() / c->megabytes(), c->gridCapped ? "  (grid capped)" : "",
                        c->budgetCapped ? "  (raised to fit 2 GiB)" : "");
        }
    }
    std::printf("\ntessellation speed (buildParametricGrid + tessellateParametric, one thread, "
                "fastest round):\n");
    for (const Subject& s : subjects()) {
        const std::string name = s.name + "/tessellate";
        if (r.has(name))
            std::printf("  %-7s error %.3g (%.3g x extent): %.2f Mtriangles/s\n", s.name.c_str(),
                        s.speedError, s.speedError / s.extent, r.best(name));
    }
}

}  // namespace
}  // namespace strahl::bench

int main(int argc, char** argv) {
    using namespace strahl;
    using namespace strahl::bench;
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

    const auto setupStart = Clock::now();
    const std::filesystem::path teapotFile =
        std::filesystem::path(STRAHL_SOURCE_DIR) / "scenes/data/teapot.bpt";
    std::vector<Subject>& all = subjects();
    all.push_back(makeSubject("sphere", makeParametricSphere(1.0)));
    all.push_back(makeSubject("torus", makeParametricTorus(1.0, 0.35)));
    all.push_back(makeSubject("teapot", makeBezierPatchSet(loadBezierFile(teapotFile), "teapot.bpt")));

    std::printf("embree %s; image %dx%d, fov %.0f deg, tiles %dx%d, packets of 16 (native %d); "
                "%d rounds\n",
                embreeVersion(), kSize, kSize, double(kFovDegrees), kTile, kTile,
                all[0].configs[0]->accel->nativePacketWidth(), kRounds);
    bool ok = true;
    for (const Subject& s : all) {
        std::printf("%s: %s, extent %.4g, bounding radius %.4g, eye at %.4g; half a pixel at "
                    "the nearest point = %.4g (%.3g x extent)\n",
                    s.name.c_str(), s.surface->describe().c_str(), s.extent, s.radius,
                    s.eyeDistance, s.halfPixelError, s.halfPixelError / s.extent);
        ok = checkSubject(s) && ok;
        printCostClasses(s);
    }
    std::printf("setup and checks: %.1f s\n", secondsSince(setupStart));
    if (!ok) {
        std::fprintf(stderr, "bench_parametric: the modes disagree on more than %.1f %% of the "
                             "pixels (FAIL above); not timing a broken mode\n",
                     100.0 * (1.0 - kMinAgreement));
        return 1;
    }

    for (int round = 0; round < kRounds; ++round) {
        for (const Subject& s : all) {
            for (bool packets : {true, false})
                for (const auto& c : s.configs) {
                    const std::string name =
                        s.name + "/" + modeName(c->mode) + (packets ? "/packets" : "/single");
                    const Subject* sp = &s;
                    const Config* cp = c.get();
                    benchmark::RegisterBenchmark(name.c_str(),
                                                 [sp, cp, packets](benchmark::State& st) {
                                                     traceCase(st, *sp, *cp, packets);
                                                 })
                        ->Unit(benchmark::kMillisecond)
                        ->UseRealTime();
                }
            const Subject* sp = &s;
            benchmark::RegisterBenchmark((s.name + "/tessellate").c_str(),
                                         [sp](benchmark::State& st) { tessellateCase(st, *sp); })
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
        }
    }
    BestRoundReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    printSummary(reporter);
    benchmark::Shutdown();
    return 0;
}
