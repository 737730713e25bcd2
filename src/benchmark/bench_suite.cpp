// One scene of `strahl bench` (see bench_suite.h): load, build, then each ray
// pass on its own — rays generated first, traced in parallel, best of
// `repeats` — and the naive tracer on its sample.

#include "strahl/benchmark/bench_suite.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "bench_clock.h"
#include "strahl/camera/tile_rays.h"
#include "strahl/core/error.h"
#include "strahl/core/rng.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/raster/rasterizer.h"
#include "strahl/reference/naive_accel.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene_desc.h"

namespace strahl {

namespace {

using bench_detail::Clock;
using bench_detail::secondsSince;

// Runs pass() `repeats` times and returns the shortest time.
template <typename Pass>
double bestOf(int repeats, Pass&& pass) {
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r < std::max(1, repeats); ++r) {
        const auto start = Clock::now();
        pass();
        best = std::min(best, secondsSince(start));
    }
    return best;
}

double mrays(size_t rays, double seconds) { return seconds > 0 ? double(rays) / seconds / 1e6 : 0.0; }

// Camera packets of the whole image, made once and copied before each trace
// (tracing overwrites tfar and the hit).
template <int N>
std::vector<CameraPacket<N>> makePackets(const Camera& camera, int resolution) {
    const TileRayGenerator generator(camera, 0, 1);
    std::vector<CameraPacket<N>> packets;
    for (const PixelRect& tile : cutTiles(PixelRect{0, 0, resolution, resolution}, 32)) {
        std::vector<CameraPacket<N>> more = generator.tilePackets<N>(tile, 0);
        packets.insert(packets.end(), more.begin(), more.end());
    }
    return packets;
}

template <int N>
double packetSeconds(const Accel& accel, const Camera& camera, int resolution, int repeats) {
    const std::vector<CameraPacket<N>> packets = makePackets<N>(camera, resolution);
    return bestOf(repeats, [&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, packets.size(), 16),
                          [&](const tbb::blocked_range<size_t>& range) {
                              for (size_t i = range.begin(); i != range.end(); ++i) {
                                  CameraPacket<N> packet = packets[i];
                                  accel.intersectPacket(packet.valid, packet.rays,
                                                        RayCoherence::Coherent);
                              }
                          });
    });
}

// Closest hits of `rays`, in parallel; returns the time of the best pass.
double intersectSeconds(const Accel& accel, const std::vector<Ray>& rays, std::vector<Hit>& hits,
                        int repeats) {
    hits.assign(rays.size(), Hit{});
    return bestOf(repeats, [&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 256),
                          [&](const tbb::blocked_range<size_t>& range) {
                              for (size_t i = range.begin(); i != range.end(); ++i)
                                  hits[i] = accel.intersect(rays[i]);
                          });
    });
}

double occludedSeconds(const Accel& accel, const std::vector<Ray>& rays, int repeats) {
    std::atomic<size_t> blocked{0};
    return bestOf(repeats, [&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 256),
                          [&](const tbb::blocked_range<size_t>& range) {
                              size_t n = 0;
                              for (size_t i = range.begin(); i != range.end(); ++i)
                                  n += accel.occluded(rays[i]);
                              blocked += n;  // used, so the queries cannot be optimised away
                          });
    });
}

// A direction about unit n with density cos(theta) / pi (Malley's method).
Vec3 cosineDirection(const Vec3& n, float u1, float u2) {
    const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
    Vec3 b1, b2;
    orthonormalBasis(n, b1, b2);
    return r * std::cos(phi) * b1 + r * std::sin(phi) * b2 +
           std::sqrt(std::max(0.0f, 1.0f - u1)) * n;
}

struct SecondaryRays {
    std::vector<Ray> shadow, diffuse;
};

// From every camera hit: a shadow ray to the light and a cosine-distributed
// bounce on the side the camera sees, both offset by the hit's error bound.
SecondaryRays makeSecondaryRays(const TriangleMesh& mesh, const std::vector<Ray>& cameraRays,
                                const std::vector<Hit>& hits, const Vec3& light) {
    SecondaryRays out;
    for (size_t i = 0; i < hits.size(); ++i) {
        if (!hits[i].valid()) continue;
        const SurfaceInteraction si = triangleInteraction(mesh, hits[i].primID, hits[i].u, hits[i].v);
        Vec3 n = si.Ng;
        if (glm::dot(n, cameraRays[i].dir) > 0.0f) n = -n;
        out.shadow.push_back(spawnRayTo(si.p, si.pError, n, light));
        Pcg32 rng(i, 0x5EED);
        const float u1 = rng.nextFloat(), u2 = rng.nextFloat();
        out.diffuse.push_back(spawnRay(si.p, si.pError, n, cosineDirection(n, u1, u2)));
    }
    return out;
}

struct LoadedScene {
    World world;
    double loadSeconds = 0.0;
    double inputMegabytes = 0.0;
};

LoadedScene loadScene(const BenchSceneSpec& spec) {
    LoadedScene scene;
    const auto start = Clock::now();
    SceneShape shape;
    shape.name = spec.name;
    if (spec.generated()) {
        shape.mesh = generateBenchMesh(spec.triangles);
    } else {
        shape.mesh = loadMeshFile(spec.file).mesh;
        shape.mesh.reservePadding();
        scene.inputMegabytes = double(std::filesystem::file_size(spec.file)) / 1e6;
    }
    scene.loadSeconds = secondsSince(start);
    shape.mesh.validate(spec.name);
    if (shape.mesh.triangleCount() == 0) fail("bench: ", spec.name, ": the mesh has no triangles");
    shape.mesh.faceMaterials.clear();
    shape.materialOfSlot = {0};
    scene.world.shapes.push_back(std::move(shape));
    scene.world.materials.push_back(Material::diffuse("default", Color(0.8f)));
    return scene;
}

}  // namespace

BenchView benchView(const Bounds3& bounds, int resolution) {
    constexpr float kFovDegrees = 40.0f;
    const Vec3 centre = bounds.center();
    const float radius = std::max(0.5f * glm::length(bounds.diagonal()), 1e-6f);
    const float distance = radius / std::sin(glm::radians(0.5f * kFovDegrees));
    const Vec3 eye = centre + distance * glm::normalize(Vec3(0.55f, 0.45f, 1.0f));
    const float d = 0.01f * distance;
    const Camera camera(CameraFrame::lookAt(eye, centre, Vec3(0.0f, 1.0f, 0.0f)),
                        Projection::Perspective,
                        Camera::windowFromFov(glm::radians(kFovDegrees), d, resolution, resolution),
                        d, resolution, resolution);
    return BenchView{camera, centre + 2.0f * radius * glm::normalize(Vec3(-0.5f, 1.5f, 0.8f))};
}

BenchRow runBenchScene(const BenchSceneSpec& spec, const BenchOptions& options,
                       const std::function<void(const std::string&)>& status) {
    auto say = [&](const char* what) {
        if (status) status(spec.name + ": " + what);
    };
    if (options.resolution < 1 || options.resolution > kMaxFilmSide)
        fail("bench: resolution ", options.resolution, " is outside [1, ", kMaxFilmSide, "]");

    BenchRow row;
    row.scene = spec.name;
    row.generated = spec.generated();
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        say(spec.generated() ? "generating" : "loading");
        LoadedScene loaded = loadScene(spec);
        World& world = loaded.world;
        const TriangleMesh& mesh = world.shapes[0].mesh;
        row.triangles = mesh.triangleCount();
        row.vertices = mesh.vertexCount();
        row.loadSeconds = loaded.loadSeconds;
        row.inputMegabytes = loaded.inputMegabytes;
        row.meshMegabytes = double(mesh.memoryBytes()) / (1 << 20);

        say("building the BVH");
        const AccelScene accelScene = world.accelScene();
        AccelBuildOptions build;
        build.threads = options.threads;
        const auto buildStart = Clock::now();
        world.accel = buildEmbreeAccel(accelScene, build);
        row.buildSeconds = secondsSince(buildStart);
        world.prepareLights();
        row.bvhMegabytes = double(world.accel->memoryBytes()) / (1 << 20);
        const Accel& accel = *world.accel;

        const int res = options.resolution;
        const BenchView framing = benchView(world.bounds(), res);
        std::vector<Ray> cameraRays;
        cameraRays.reserve(size_t(res) * size_t(res));
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x)
                cameraRays.push_back(framing.camera.generateRay(float(x) + 0.5f, float(y) + 0.5f));
        row.primaryRays = cameraRays.size();

        say("tracing primary rays");
        std::vector<Hit> hits;
        row.singleMrays = mrays(cameraRays.size(), intersectSeconds(accel, cameraRays, hits, options.repeats));
        row.primaryHits = size_t(std::count_if(hits.begin(), hits.end(), [](const Hit& h) { return h.valid(); }));
        row.packetWidth = resolvePacketWidth(PacketMode::Auto, accel);
        const double packetTime = row.packetWidth == 16
                                      ? packetSeconds<16>(accel, framing.camera, res, options.repeats)
                                      : packetSeconds<8>(accel, framing.camera, res, options.repeats);
        row.packetMrays = mrays(cameraRays.size(), packetTime);

        say("tracing shadow and diffuse rays");
        const SecondaryRays secondary = makeSecondaryRays(mesh, cameraRays, hits, framing.light);
        row.shadowMrays = mrays(secondary.shadow.size(), occludedSeconds(accel, secondary.shadow, options.repeats));
        std::vector<Hit> bounceHits;
        row.diffuseMrays = mrays(secondary.diffuse.size(),
                                 intersectSeconds(accel, secondary.diffuse, bounceHits, options.repeats));

        // The naive sample: evenly spaced over the image, so it sees the same
        // mix of hits and misses as the whole.
        const double affordable = options.naiveBudget / double(row.triangles);
        const size_t sampleSize =
            std::clamp(size_t(affordable), std::min(kMinNaiveRays, cameraRays.size()), cameraRays.size());
        std::vector<Ray> sample;
        std::vector<size_t> pixel;
        for (size_t k = 0; k < sampleSize; ++k) {
            pixel.push_back(k * cameraRays.size() / sampleSize);
            sample.push_back(cameraRays[pixel.back()]);
        }
        say(("naive tracer on " + std::to_string(sampleSize) + " rays").c_str());
        const auto naive = buildNaiveAccel(accelScene);
        std::vector<Hit> naiveHits;
        row.naiveRays = sample.size();
        row.naiveMrays = mrays(sample.size(), intersectSeconds(*naive, sample, naiveHits, 1));
        size_t agree = 0;
        for (size_t k = 0; k < sample.size(); ++k) {
            const Hit& a = hits[pixel[k]];
            const Hit& b = naiveHits[k];
            agree += a.valid() == b.valid() && (!a.valid() || (a.geomID == b.geomID && a.primID == b.primID));
        }
        row.naiveAgreement = sample.empty() ? 1.0 : double(agree) / double(sample.size());
        row.speedupSingle = row.singleMrays / row.naiveMrays;
        row.speedupPacket = row.packetMrays / row.naiveMrays;

        if (options.raster) {
            say("rasterizing");
            const auto integrator = makeIntegrator("eyelight", world);
            RenderOptions raster;
            raster.threads = options.threads;
            row.rasterSeconds = bestOf(options.repeats, [&] {
                Film film(res, res, PixelRect{0, 0, res, res}, {});
                rasterizeImage(world, framing.camera, *integrator, film, raster);
            });
        }
    });
    return row;
}

namespace {

// Ordinary least squares y = intercept + slope * x, with the coefficient of
// determination r^2.
struct Line {
    double slope = 0.0, intercept = 0.0, r2 = 0.0;
    size_t points = 0;
};

Line fitLine(const std::vector<double>& x, const std::vector<double>& y) {
    Line line;
    line.points = x.size();
    if (x.size() < 2) return line;
    const double n = double(x.size());
    double mx = 0, my = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        mx += x[i];
        my += y[i];
    }
    mx /= n;
    my /= n;
    double sxx = 0, sxy = 0, syy = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        sxx += (x[i] - mx) * (x[i] - mx);
        sxy += (x[i] - mx) * (y[i] - my);
        syy += (y[i] - my) * (y[i] - my);
    }
    if (sxx <= 0) return line;
    line.slope = sxy / sxx;
    line.intercept = my - line.slope * mx;
    line.r2 = syy > 0 ? (sxy * sxy) / (sxx * syy) : 1.0;
    return line;
}

}  // namespace

PowerFit fitPowerLaw(const std::vector<double>& triangles, const std::vector<double>& cost) {
    std::vector<double> x, y;
    for (size_t i = 0; i < triangles.size() && i < cost.size(); ++i) {
        if (triangles[i] > 0 && cost[i] > 0) {
            x.push_back(std::log10(triangles[i]));
            y.push_back(std::log10(cost[i]));
        }
    }
    const Line line = fitLine(x, y);
    return PowerFit{line.slope, line.intercept, line.r2, line.points};
}

LogFit fitLogarithmic(const std::vector<double>& triangles, const std::vector<double>& cost) {
    std::vector<double> x, y;
    for (size_t i = 0; i < triangles.size() && i < cost.size(); ++i) {
        if (triangles[i] > 0) {
            x.push_back(std::log10(triangles[i]));
            y.push_back(cost[i]);
        }
    }
    const Line line = fitLine(x, y);
    return LogFit{line.intercept, line.slope, line.r2, line.points};
}

}  // namespace strahl
