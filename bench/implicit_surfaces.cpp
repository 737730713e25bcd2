// Implicit-surface throughput (issue: "Mrays/s for the same sphere as (a)
// implicit user geometry, (b) Embree's built-in sphere, (c) a tessellated
// mesh; torus via closed form vs via a formula string").
//
//   sphere  The unit sphere filling a 512x512 image, camera rays traced as
//           (a) ImplicitShape(makeImplicitSphere(1)) as Embree user geometry,
//           (b) buildEmbreeSphereAccel (RTC_GEOMETRY_TYPE_SPHERE_POINT),
//           (c) an icosphere of 81,920 triangles in buildEmbreeAccel.
//           Target: (a) >= 0.5 x (b) in Mrays/s.
//   torus   R = 1, r = 0.3, tilted 50 degrees so rays pass through the hole:
//           makeImplicitTorus (hand-written C++) vs makeFormulaSurface with the
//           same factored quartic, both as ImplicitShape user geometry.
//   eval    The raw evaluators of the same two tori: value (double), range
//           (interval box) and alongRay (RayDual over a ray segment), ns each.
//   Target for both: the formula within 3x of the hand-written C++, i.e.
//   builtin/formula <= 3 in Mrays/s and formula/builtin <= 3 in ns per eval.
//
// Rays: pre-generated camera rays (one per pixel centre) in 32x32 tiles, traced
// in parallel over the tiles, as packets of the native width (rtcIntersect16/8)
// and as single rays (rtcIntersect1); only traversal and intersection are
// timed. Every case runs in kRounds interleaved rounds in one process, and each
// ratio uses both cases' fastest round — the one least disturbed by the other
// load of a shared machine — so a pair is always measured back to back. The
// run ends with the table "figure | value | target | met?".
//
// Usage: bench_implicit [google-benchmark flags]

#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_mesh.h"
#include "strahl/accel/embree_spheres.h"
#include "strahl/camera/tile_rays.h"
#include "strahl/core/sampler.h"
#include "strahl/geometry/formula.h"
#include "strahl/geometry/implicit_builtins.h"
#include "strahl/geometry/implicit_formula.h"
#include "strahl/geometry/implicit_shape.h"
#include "strahl/render/renderer.h"

namespace strahl::bench {
namespace {

constexpr int kSize = 512;
constexpr int kTile = 32;
constexpr int kRounds = 5;
constexpr double kMinSeconds = 0.2;  // per case and round
constexpr int kIcosphereLevels = 6;  // 20 * 4^6 = 81,920 triangles
constexpr double kMajorRadius = 1.0, kMinorRadius = 0.3;
constexpr float kTorusTiltDegrees = 50.0f;
// The torus of src/geometry/implicit_torus.cpp, factored exactly as Torus::eval writes it:
// ρ = √(x² + y²) and z² − r² computed once (the compiler's CSE finds both).
constexpr const char* kTorusFormula =
    "((sqrt(x^2 + y^2) - R)^2 + (z^2 - r^2)) * ((sqrt(x^2 + y^2) + R)^2 + (z^2 - r^2))";
constexpr int kEvaluations = 1024;  // inputs per micro-benchmark iteration

// ---- camera rays -------------------------------------------------------------

// The camera rays of one view, pre-generated per tile as packets of the native
// width and as single rays.
struct CameraRays {
    int packetWidth = 16;
    std::vector<std::vector<CameraPacket<16>>> packets16;
    std::vector<std::vector<CameraPacket<8>>> packets8;
    std::vector<std::vector<Ray>> single;
};

template <int N>
std::vector<std::vector<CameraPacket<N>>> makePackets(const TileRayGenerator& gen,
                                                      const std::vector<PixelRect>& tiles) {
    std::vector<std::vector<CameraPacket<N>>> packets(tiles.size());
    for (size_t i = 0; i < tiles.size(); ++i) {
        const PixelRect& t = tiles[i];
        for (int by = t.y0; by < t.y1; by += CameraPacket<N>::kBlockHeight)
            for (int bx = t.x0; bx < t.x1; bx += CameraPacket<N>::kBlockWidth) {
                packets[i].emplace_back();
                gen.fillPacket(t, bx, by, 0, packets[i].back());
            }
    }
    return packets;
}

CameraRays makeCameraRays(const Camera& camera, int packetWidth) {
    CameraRays rays;
    rays.packetWidth = packetWidth;
    const TileRayGenerator gen(camera, 0, 1);
    const std::vector<PixelRect> tiles = cutTiles(PixelRect{0, 0, kSize, kSize}, kTile);
    if (packetWidth == 16)
        rays.packets16 = makePackets<16>(gen, tiles);
    else
        rays.packets8 = makePackets<8>(gen, tiles);
    rays.single.resize(tiles.size());
    for (size_t i = 0; i < tiles.size(); ++i) {
        const PixelRect& t = tiles[i];
        for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) {
                Sampler rng;
                rays.single[i].push_back(gen.sampleRay(x, y, 0, rng));
            }
    }
    return rays;
}

// Traces every camera ray once; returns the number of hits.
template <int N>
size_t tracePackets(const Accel& accel, const std::vector<std::vector<CameraPacket<N>>>& tiles) {
    std::atomic<size_t> hits{0};
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, tiles.size(), 1),
        [&](const tbb::blocked_range<size_t>& r) {
            size_t tileHits = 0;
            for (size_t i = r.begin(); i != r.end(); ++i) {
                for (const CameraPacket<N>& source : tiles[i]) {
                    RayHitPacket<N> p;
                    std::memcpy(&p, &source.rays, sizeof p);  // fresh tfar/geomID
                    accel.intersectPacket(source.valid, p, RayCoherence::Coherent);
                    for (int lane = 0; lane < N; ++lane)
                        tileHits += source.valid[lane] && p.geomID[lane] != kInvalidId;
                }
            }
            hits += tileHits;
        },
        tbb::simple_partitioner());
    return hits.load();
}

size_t traceSingle(const Accel& accel, const std::vector<std::vector<Ray>>& tiles) {
    std::atomic<size_t> hits{0};
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, tiles.size(), 1),
        [&](const tbb::blocked_range<size_t>& r) {
            size_t tileHits = 0;
            for (size_t i = r.begin(); i != r.end(); ++i)
                for (const Ray& ray : tiles[i]) tileHits += accel.intersect(ray).valid();
            hits += tileHits;
        },
        tbb::simple_partitioner());
    return hits.load();
}

size_t traceAll(const Accel& accel, const CameraRays& rays, bool packets) {
    if (!packets) return traceSingle(accel, rays.single);
    return rays.packetWidth == 16 ? tracePackets<16>(accel, rays.packets16)
                                  : tracePackets<8>(accel, rays.packets8);
}

// ---- the scenes ----------------------------------------------------------------

// Unit icosphere: the icosahedron split at edge midpoints `levels` times, every
// vertex pushed back onto the sphere after each split.
TriangleMesh icosphere(int levels) {
    const float p = 0.5f * (1.0f + std::sqrt(5.0f));  // golden ratio
    TriangleMesh mesh;
    mesh.positions = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                      {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
    mesh.indices = {0, 11, 5, 0, 5, 1,  0, 1, 7,  0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,
                    11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8,
                    3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    for (Vec3& v : mesh.positions) v = glm::normalize(v);
    for (int level = 0; level < levels; ++level) {
        mesh = subdivideMidpoints(mesh);
        for (Vec3& v : mesh.positions) v = glm::normalize(v);
    }
    mesh.reservePadding();
    return mesh;
}

Camera frontCamera(float distance, float fovDegrees) {
    return Camera(CameraFrame::lookAt(Vec3(0, 0, distance), Vec3(0), Vec3(0, 1, 0)),
                  Projection::Perspective,
                  Camera::windowFromFov(glm::radians(fovDegrees), 1.0f, kSize, kSize), 1.0f,
                  kSize, kSize);
}

// Every scene of the benchmark, built once. Built in place and never moved:
// the accelerators point into the shapes and share the mesh's vertices.
struct Scenes {
    // The unit sphere three radii in front of the camera, 40° field of view: its
    // disc spans 97% of the image height.
    Camera sphereCamera = frontCamera(3.0f, 40.0f);
    ImplicitShape implicitSphere{makeImplicitSphere(1.0), Mat4(1.0f), ImplicitShapeOptions{}};
    TriangleMesh icosphereMesh = icosphere(kIcosphereLevels);
    std::unique_ptr<Accel> sphereImplicitAccel, sphereEmbreeAccel, sphereMeshAccel;
    CameraRays sphereRays;

    Camera torusCamera = frontCamera(4.0f, 40.0f);
    ImplicitSurfacePtr torusBuiltin = makeImplicitTorus(kMajorRadius, kMinorRadius);
    ImplicitSurfacePtr torusFormula =
        makeFormulaSurface(kTorusFormula, {{"R", kMajorRadius}, {"r", kMinorRadius}});
    std::unique_ptr<ImplicitShape> torusBuiltinShape, torusFormulaShape;
    std::unique_ptr<Accel> torusBuiltinAccel, torusFormulaAccel;
    CameraRays torusRays;

    Scenes() {
        const ShapeRef implicitRef[] = {ShapeRef{nullptr, &implicitSphere}};
        sphereImplicitAccel = buildEmbreeAccel(implicitRef, {});
        const Vec4 unitSphere[] = {Vec4(0.0f, 0.0f, 0.0f, 1.0f)};
        sphereEmbreeAccel = buildEmbreeSphereAccel(unitSphere, {});
        const TriangleMesh* meshes[] = {&icosphereMesh};
        sphereMeshAccel = buildEmbreeAccel(meshes, {});
        const int width = resolvePacketWidth(PacketMode::Auto, *sphereEmbreeAccel);
        sphereRays = makeCameraRays(sphereCamera, width);

        // The same box, so the same cells, for both: a formula has no bounds of its own.
        ImplicitShapeOptions options;
        const float outer = float(kMajorRadius + kMinorRadius), tube = float(kMinorRadius);
        options.box = Bounds3{Vec3(-outer, -outer, -tube), Vec3(outer, outer, tube)};
        const Mat4 tilt =
            glm::rotate(Mat4(1.0f), glm::radians(kTorusTiltDegrees), Vec3(1.0f, 0.0f, 0.0f));
        torusBuiltinShape = std::make_unique<ImplicitShape>(torusBuiltin, tilt, options);
        torusFormulaShape = std::make_unique<ImplicitShape>(torusFormula, tilt, options);
        const ShapeRef builtinRef[] = {ShapeRef{nullptr, torusBuiltinShape.get()}};
        const ShapeRef formulaRef[] = {ShapeRef{nullptr, torusFormulaShape.get()}};
        torusBuiltinAccel = buildEmbreeAccel(builtinRef, {});
        torusFormulaAccel = buildEmbreeAccel(formulaRef, {});
        torusRays = makeCameraRays(torusCamera, width);
    }
};

Scenes& scenes() {
    static Scenes s;
    return s;
}

// ---- benchmarks ------------------------------------------------------------------

void traceLoop(benchmark::State& state, const Accel& accel, const CameraRays& rays,
               bool packets) {
    for (auto _ : state) benchmark::DoNotOptimize(traceAll(accel, rays, packets));
    state.counters["Mrays/s"] = benchmark::Counter(double(kSize) * kSize / 1e6,
                                                   benchmark::Counter::kIsIterationInvariantRate);
}

// Inputs of the evaluator micro-benchmarks, all around the torus: points of
// its box, boxes the size of one of its 32^3 cells, and ray segments of that
// length crossing the box.
struct EvalInputs {
    std::vector<DVec3> points;
    std::vector<IntervalBox> boxes;
    std::vector<DVec3> rayOrigins, rayDirs;
    std::vector<num::Interval> segments;
};

const EvalInputs& evalInputs() {
    static const EvalInputs inputs = [] {
        EvalInputs in;
        Pcg32 rng(7, 1);
        const DVec3 extent(kMajorRadius + kMinorRadius, kMajorRadius + kMinorRadius,
                           kMinorRadius);
        const double cell = 2.0 * extent.x / 32.0;  // ImplicitShape's default 32 cells per axis
        auto inBox = [&] {
            return DVec3(rng.nextFloat() * 2.0 - 1.0, rng.nextFloat() * 2.0 - 1.0,
                         rng.nextFloat() * 2.0 - 1.0) * extent;
        };
        for (int i = 0; i < kEvaluations; ++i) {
            in.points.push_back(inBox());
            const DVec3 lo = inBox();
            in.boxes.push_back(IntervalBox{num::Interval(lo.x, lo.x + cell),
                                           num::Interval(lo.y, lo.y + cell),
                                           num::Interval(lo.z, lo.z + cell)});
            const DVec3 o = inBox() + DVec3(0.0, 0.0, 2.0);
            const DVec3 d = glm::normalize(inBox() - o);
            const double t = glm::length(o) - 0.5;
            in.rayOrigins.push_back(o);
            in.rayDirs.push_back(d);
            in.segments.push_back(num::Interval(t, t + cell));
        }
        return in;
    }();
    return inputs;
}

enum class Arithmetic { Value, Range, AlongRay };

void evalLoop(benchmark::State& state, const ImplicitSurface& surface, Arithmetic arithmetic) {
    const EvalInputs& in = evalInputs();
    for (auto _ : state) {
        double sum = 0.0;
        switch (arithmetic) {
        case Arithmetic::Value:
            for (const DVec3& p : in.points) sum += surface.value(p);
            break;
        case Arithmetic::Range:
            for (const IntervalBox& box : in.boxes) sum += surface.range(box).lo;
            break;
        case Arithmetic::AlongRay:
            for (int i = 0; i < kEvaluations; ++i) {
                const num::RayDual f = surface.alongRay(in.rayOrigins[i], in.rayDirs[i],
                                                        in.segments[i]);
                sum += f.v.lo + f.d[0].hi;
            }
            break;
        }
        benchmark::DoNotOptimize(sum);
    }
    state.counters["s/eval"] = benchmark::Counter(
        kEvaluations, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// Console output as usual, plus each case's fastest round in seconds per iteration.
class FastestRoundReporter : public benchmark::ConsoleReporter {
public:
    // Colours only on a terminal, so a redirected run is plain text.
    FastestRoundReporter()
        : ConsoleReporter(isatty(fileno(stdout)) ? OO_ColorTabular : OO_Tabular) {}

    void ReportRuns(const std::vector<Run>& runs) override {
        ConsoleReporter::ReportRuns(runs);
        for (const Run& run : runs) {
            if (run.run_type != Run::RT_Iteration || run.iterations == 0) continue;
            const double seconds = run.real_accumulated_time / double(run.iterations);
            auto [it, inserted] = best_.try_emplace(run.run_name.function_name, seconds);
            if (!inserted) it->second = std::min(it->second, seconds);
        }
    }
    bool has(const std::string& name) const { return best_.count(name) != 0; }
    double seconds(const std::string& name) const { return best_.at(name); }

private:
    std::map<std::string, double> best_;
};

struct Case {
    std::string name;
    std::function<void(benchmark::State&)> run;
};

std::vector<Case> allCases() {
    Scenes& s = scenes();
    std::vector<Case> cases;
    for (bool packets : {true, false}) {
        const std::string mode = packets ? "packets" : "single";
        cases.push_back({"sphere/implicit/" + mode, [&s, packets](benchmark::State& st) {
                             traceLoop(st, *s.sphereImplicitAccel, s.sphereRays, packets);
                         }});
        cases.push_back({"sphere/embree/" + mode, [&s, packets](benchmark::State& st) {
                             traceLoop(st, *s.sphereEmbreeAccel, s.sphereRays, packets);
                         }});
        cases.push_back({"sphere/mesh/" + mode, [&s, packets](benchmark::State& st) {
                             traceLoop(st, *s.sphereMeshAccel, s.sphereRays, packets);
                         }});
        cases.push_back({"torus/builtin/" + mode, [&s, packets](benchmark::State& st) {
                             traceLoop(st, *s.torusBuiltinAccel, s.torusRays, packets);
                         }});
        cases.push_back({"torus/formula/" + mode, [&s, packets](benchmark::State& st) {
                             traceLoop(st, *s.torusFormulaAccel, s.torusRays, packets);
                         }});
    }
    const std::pair<const char*, Arithmetic> arithmetics[] = {
        {"value", Arithmetic::Value}, {"range", Arithmetic::Range},
        {"alongRay", Arithmetic::AlongRay}};
    for (const auto& [label, arithmetic] : arithmetics) {
        const Arithmetic a = arithmetic;
        cases.push_back({std::string("eval/") + label + "/builtin",
                         [&s, a](benchmark::State& st) { evalLoop(st, *s.torusBuiltin, a); }});
        cases.push_back({std::string("eval/") + label + "/formula",
                         [&s, a](benchmark::State& st) { evalLoop(st, *s.torusFormula, a); }});
    }
    return cases;
}

// One row of the closing table: a ratio of two cases' fastest rounds.
struct Figure {
    std::string name;
    double value;
    std::string target;
    bool met;
};

void printTable(const std::vector<Figure>& figures) {
    std::printf("\n%-52s | %8s | %8s | %s\n", "figure", "value", "target", "met?");
    std::printf("%s\n", std::string(84, '-').c_str());
    for (const Figure& f : figures)
        std::printf("%-52s | %8.2f | %8s | %s\n", f.name.c_str(), f.value, f.target.c_str(),
                    f.target.empty() ? "" : (f.met ? "yes" : "NO"));
}

}  // namespace
}  // namespace strahl::bench

int main(int argc, char** argv) {
    using namespace strahl;
    using namespace strahl::bench;
    benchmark::Initialize(&argc, argv);
    Scenes& s = scenes();
    const CameraRays& sphereRays = s.sphereRays;
    std::printf("embree %s; image %dx%d, tiles %dx%d, packets of %d; %d rounds\n",
                embreeVersion(), kSize, kSize, kTile, kTile, sphereRays.packetWidth, kRounds);
    std::printf("sphere hits (pixels): implicit %zu, embree %zu, mesh %zu (icosphere, %zu "
                "triangles)\n",
                traceAll(*s.sphereImplicitAccel, sphereRays, true),
                traceAll(*s.sphereEmbreeAccel, sphereRays, true),
                traceAll(*s.sphereMeshAccel, sphereRays, true),
                s.icosphereMesh.triangleCount());
    std::printf("torus hits (pixels): builtin %zu, formula %zu; cells %u and %u\n",
                traceAll(*s.torusBuiltinAccel, s.torusRays, true),
                traceAll(*s.torusFormulaAccel, s.torusRays, true),
                s.torusBuiltinShape->primitiveCount(), s.torusFormulaShape->primitiveCount());
    const std::string variables[] = {"x", "y", "z"};
    const Formula tape = Formula::compile(kTorusFormula, variables,
                                          {{"R", kMajorRadius}, {"r", kMinorRadius}});
    std::printf("torus formula \"%s\": %zu instructions, %zu registers\n", kTorusFormula,
                tape.instructionCount(), tape.registerCount());

    const std::vector<Case> cases = allCases();
    for (int round = 0; round < kRounds; ++round)
        for (const Case& c : cases)
            benchmark::RegisterBenchmark(c.name.c_str(), c.run)
                ->Unit(c.name.starts_with("eval/") ? benchmark::kMicrosecond
                                                   : benchmark::kMillisecond)
                ->UseRealTime()
                ->MinTime(kMinSeconds);
    FastestRoundReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);

    const double rays = double(kSize) * kSize;
    std::vector<Figure> figures;
    std::printf("\nfastest round of %d:\n", kRounds);
    for (const Case& c : cases) {
        if (!reporter.has(c.name)) continue;
        if (c.name.starts_with("eval/"))
            std::printf("  %-26s %8.1f ns/eval\n", c.name.c_str(),
                        reporter.seconds(c.name) / kEvaluations * 1e9);
        else
            std::printf("  %-26s %8.2f Mrays/s\n", c.name.c_str(),
                        rays / reporter.seconds(c.name) / 1e6);
    }
    auto both = [&](const std::string& a, const std::string& b) {
        return reporter.has(a) && reporter.has(b);
    };
    for (const char* mode : {"packets", "single"}) {
        const std::string implicit = std::string("sphere/implicit/") + mode;
        const std::string embree = std::string("sphere/embree/") + mode;
        const std::string mesh = std::string("sphere/mesh/") + mode;
        if (both(implicit, embree)) {
            const double r = reporter.seconds(embree) / reporter.seconds(implicit);
            figures.push_back({std::string("sphere ") + mode + ": implicit / embree (Mrays/s)",
                               r, ">= 0.50", r >= 0.5});
        }
        if (both(implicit, mesh))
            figures.push_back({std::string("sphere ") + mode + ": implicit / mesh (Mrays/s)",
                               reporter.seconds(mesh) / reporter.seconds(implicit), "", true});
    }
    for (const char* mode : {"packets", "single"}) {
        const std::string builtin = std::string("torus/builtin/") + mode;
        const std::string formula = std::string("torus/formula/") + mode;
        if (both(builtin, formula)) {
            const double r = reporter.seconds(formula) / reporter.seconds(builtin);
            figures.push_back({std::string("torus ") + mode + ": builtin / formula (Mrays/s)", r,
                               "<= 3.00", r <= 3.0});
        }
    }
    for (const char* arithmetic : {"value", "range", "alongRay"}) {
        const std::string builtin = std::string("eval/") + arithmetic + "/builtin";
        const std::string formula = std::string("eval/") + arithmetic + "/formula";
        if (both(builtin, formula)) {
            const double r = reporter.seconds(formula) / reporter.seconds(builtin);
            figures.push_back({std::string("torus eval ") + arithmetic +
                                   ": formula / builtin (ns per eval)",
                               r, "<= 3.00", r <= 3.0});
        }
    }
    printTable(figures);
    benchmark::Shutdown();
    return 0;
}
