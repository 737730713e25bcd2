#pragma once
// `strahl bench`: for each scene, what it costs to load, build and trace —
// Embree against the naive tracer, ray tracing against rasterization.
//
// Every scene is traced at resolution x resolution by the same automatic
// camera. Ray passes are timed alone: the rays are generated first, then
// traced in parallel by all threads of the run; each Embree pass is repeated
// and its best time kept (the machine is shared and noisy; the best is the
// least disturbed). The naive tracer runs once, on an evenly spaced sample of
// the camera rays when the whole image would take too long (the sample size is
// reported); its answers are checked against Embree's on the same rays.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "strahl/benchmark/bench_scene.h"
#include "strahl/camera/camera.h"

namespace strahl {

struct BenchOptions {
    int resolution = 512;  // image side in pixels
    int threads = 0;       // 0: all hardware threads
    int repeats = 3;       // Embree passes per figure; the best is kept
    // Triangle tests the naive tracer may spend per scene: the sample is
    // budget / triangles rays (at least kMinNaiveRays, at most the image).
    double naiveBudget = 2e9;
    bool raster = true;  // also time the z-buffer rasterizer
};

// The naive sample never shrinks below this many rays, however big the scene.
inline constexpr size_t kMinNaiveRays = 64;

struct BenchRow {
    std::string scene;
    bool generated = false;
    size_t triangles = 0;
    size_t vertices = 0;
    double loadSeconds = 0.0;    // reading the file, or generating the mesh
    double inputMegabytes = 0.0; // file size; 0 for generated meshes
    double buildSeconds = 0.0;   // Embree BVH
    double meshMegabytes = 0.0, bvhMegabytes = 0.0;
    size_t primaryRays = 0;      // resolution^2
    size_t primaryHits = 0;
    double packetMrays = 0.0;    // primary rays, packets of packetWidth
    int packetWidth = 0;
    double singleMrays = 0.0;    // primary rays one at a time
    double shadowMrays = 0.0;    // occlusion rays from every hit to the light
    double diffuseMrays = 0.0;   // incoherent cosine-distributed bounce rays
    size_t naiveRays = 0;        // the sample the naive tracer traced
    double naiveMrays = 0.0;
    double naiveAgreement = 0.0; // fraction of the sample with the same hit as Embree
    double rasterSeconds = -1.0; // < 0: not measured
    // Per-ray cost ratio naive / Embree single rays, and naive / Embree packets.
    double speedupSingle = 0.0, speedupPacket = 0.0;

    double naiveNanosecondsPerRay() const { return naiveMrays > 0 ? 1e3 / naiveMrays : 0.0; }
    double singleNanosecondsPerRay() const { return singleMrays > 0 ? 1e3 / singleMrays : 0.0; }
    double packetNanosecondsPerRay() const { return packetMrays > 0 ? 1e3 / packetMrays : 0.0; }
};

// The view every bench scene is traced from: the camera looks at the bounding
// box's centre from a fixed direction (above, right, in front), far enough
// that the box's bounding sphere fits a 40° field of view, with the image
// plane at 1% of that distance so nothing of the model is cut off; the light
// is above and to the left, two radii out.
struct BenchView {
    Camera camera;
    Vec3 light;
};
BenchView benchView(const Bounds3& bounds, int resolution);

// Runs one scene. `status` (optional) is told what is being measured.
BenchRow runBenchScene(const BenchSceneSpec& spec, const BenchOptions& options,
                       const std::function<void(const std::string&)>& status = {});

// Least-squares fit of log10(cost) = intercept + slope * log10(triangles): the
// slope is the exponent of the growth (1 for linear cost).
struct PowerFit {
    double slope = 0.0, intercept = 0.0, r2 = 0.0;
    size_t points = 0;
};
PowerFit fitPowerLaw(const std::vector<double>& triangles, const std::vector<double>& cost);

// Least-squares fit of cost = a + b * log10(triangles): logarithmic growth.
struct LogFit {
    double a = 0.0, b = 0.0, r2 = 0.0;
    size_t points = 0;
};
LogFit fitLogarithmic(const std::vector<double>& triangles, const std::vector<double>& cost);

}  // namespace strahl
