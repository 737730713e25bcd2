// Curves: Embree's native curve geometry against the same strands as
// triangle tubes (issue 22: "Mrays/s and memory per primitive for curves
// (10^6 strands)").
//
//   fur      N strands of fur on a unit sphere (a furball, as
//            scripts/make_furball.py makes them), each one cubic B-spline
//            segment of 4 control points, radius 0.004 at the root to 0.001
//            at the tip. Three representations of the same strands:
//              round      RTC_GEOMETRY_TYPE_ROUND_BSPLINE_CURVE
//              flat       RTC_GEOMETRY_TYPE_FLAT_BSPLINE_CURVE (4 pieces)
//              triangles  each segment as a tube of 6 sides x 4 rings, 36
//                         triangles — coarse; a close-up needs more
//   Figures: build seconds, bytes per segment (control points and BVH, or
//   the mesh and its BVH) and Mrays/s of 512x512 camera rays at the ball
//   (single rays, parallel over rows), best of 3 interleaved rounds.
//   Ratios: round vs triangles in Mrays/s and in bytes per strand.
//
// Usage: bench_curves [strands for the comparison, default 200000]
//                     [strands for the curves-only run, default 1000000]


#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include "camera_rays.h"
#include "strahl/accel/accel.h"
#include "strahl/camera/camera.h"
#include "strahl/geometry/curve_set.h"
#include "strahl/geometry/triangle_mesh.h"

namespace strahl::bench {
namespace {

constexpr int kSize = 512;
constexpr int kRounds = 3;
constexpr int kTubeSides = 6, kTubeRings = 4;  // 6 sides x 3 ring gaps x 2 = 36 triangles a segment

double seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Fur on the unit sphere: Fibonacci-sphere roots, each strand 4 B-spline
// control points bending down a little.
CurveSetDesc furball(int strands, CurveType type) {
    CurveSetDesc desc;
    desc.name = "fur";
    desc.basis = CurveBasis::BSpline;
    desc.type = type;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> jitter(-0.3f, 0.3f);
    desc.points.reserve(size_t(strands) * 4);
    for (int i = 0; i < strands; ++i) {
        const float z = 1.0f - 2.0f * (float(i) + 0.5f) / float(strands);
        const float phi = float(i) * kPi * (3.0f - std::sqrt(5.0f));
        const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const Vec3 root(s * std::cos(phi), s * std::sin(phi), z);
        const Vec3 bend(jitter(rng), jitter(rng), -0.5f);
        for (int k = 0; k < 4; ++k) {
            const float t = float(k) / 3.0f;
            const Vec3 p = root * (0.97f + 0.35f * t) + bend * (0.35f * t * t);
            desc.points.emplace_back(p, 0.004f * (1.0f - 0.75f * t));
        }
        desc.segments.push_back(uint32_t(4 * i));
    }
    return desc;
}

// The same segments as triangle tubes: kTubeRings circles of kTubeSides
// points along each segment, joined by quads of two triangles.
TriangleMesh tubes(const CurveSet& curves) {
    TriangleMesh mesh;
    const uint32_t segments = curves.primitiveCount();
    mesh.positions.reserve(size_t(segments) * kTubeSides * kTubeRings);
    mesh.indices.reserve(size_t(segments) * kTubeSides * (kTubeRings - 1) * 6);
    for (uint32_t s = 0; s < segments; ++s) {
        glm::dvec4 b[4];
        curves.bezierOf(s, b);
        const auto at = [&](double u, glm::dvec4& p, glm::dvec3& d) {
            const double w = 1.0 - u;
            p = w * w * w * b[0] + 3.0 * w * w * u * b[1] + 3.0 * w * u * u * b[2] + u * u * u * b[3];
            const glm::dvec4 d4 = 3.0 * (w * w * (b[1] - b[0]) + 2.0 * w * u * (b[2] - b[1]) + u * u * (b[3] - b[2]));
            d = glm::dvec3(d4);
        };
        const uint32_t base = uint32_t(mesh.positions.size());
        for (int ring = 0; ring < kTubeRings; ++ring) {
            glm::dvec4 p;
            glm::dvec3 d;
            at(double(ring) / (kTubeRings - 1), p, d);
            const glm::dvec3 t = glm::normalize(d);
            const glm::dvec3 a = glm::normalize(glm::cross(t, std::abs(t.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
            const glm::dvec3 c = glm::cross(t, a);
            for (int k = 0; k < kTubeSides; ++k) {
                const double angle = 2.0 * 3.14159265358979 * k / kTubeSides;
                mesh.positions.push_back(Vec3(glm::dvec3(p) + p.w * (std::cos(angle) * a + std::sin(angle) * c)));
            }
        }
        for (int ring = 0; ring + 1 < kTubeRings; ++ring)
            for (int k = 0; k < kTubeSides; ++k) {
                const uint32_t i0 = base + uint32_t(ring * kTubeSides + k);
                const uint32_t i1 = base + uint32_t(ring * kTubeSides + (k + 1) % kTubeSides);
                const uint32_t j0 = i0 + kTubeSides, j1 = i1 + kTubeSides;
                mesh.indices.insert(mesh.indices.end(), {i0, i1, j1, i0, j1, j0});
            }
    }
    mesh.reservePadding();
    return mesh;
}

struct Result {
    const char* name;
    double buildSeconds = 0, bytes = 0, bestMrays = 0;
    size_t hits = 0;
};

double trace(const Accel& accel, const Camera& camera, size_t& hits) {
    return traceCameraRays(accel, camera, kSize, hits);
}

void compare(int strands) {
    const Camera camera(CameraFrame::lookAt(Vec3(0, -3.2f, 0.4f), Vec3(0, 0, 0), Vec3(0, 0, 1)),
                        Projection::Perspective, Camera::windowFromFov(0.7f, 1.0f, kSize, kSize), 1.0f, kSize,
                        kSize);
    const CurveSet round(furball(strands, CurveType::Round));
    const CurveSet flat(furball(strands, CurveType::Flat));
    const double m0 = seconds();
    const TriangleMesh mesh = tubes(round);
    const double meshSeconds = seconds() - m0;

    std::vector<Result> results{{"round curves"}, {"flat curves"}, {"triangle tubes"}};
    std::vector<std::unique_ptr<Accel>> accels;
    const std::vector<ShapeRef> shapes[3] = {{ShapeRef{nullptr, &round, nullptr}},
                                             {ShapeRef{nullptr, &flat, nullptr}},
                                             {ShapeRef{&mesh, nullptr, nullptr}}};
    const size_t shapeBytes[3] = {round.memoryBytes(), flat.memoryBytes(), mesh.memoryBytes()};
    for (int i = 0; i < 3; ++i) {
        const double t0 = seconds();
        accels.push_back(buildEmbreeAccel(std::span<const ShapeRef>(shapes[i]), {}));
        results[size_t(i)].buildSeconds = seconds() - t0;
        results[size_t(i)].bytes = double(accels.back()->memoryBytes() + shapeBytes[i]);
    }
    for (int round_ = 0; round_ < kRounds; ++round_)
        for (int i = 0; i < 3; ++i)
            results[size_t(i)].bestMrays =
                std::max(results[size_t(i)].bestMrays, trace(*accels[size_t(i)], camera, results[size_t(i)].hits));

    std::printf("\n%d strands (one B-spline segment each; tubes: %d triangles per segment, made in %.2f s)\n",
                strands, kTubeSides * (kTubeRings - 1) * 2, meshSeconds);
    std::printf("%-16s %10s %14s %10s %10s\n", "representation", "build s", "bytes/strand", "Mrays/s", "hits");
    for (const Result& r : results)
        std::printf("%-16s %10.2f %14.1f %10.2f %10zu\n", r.name, r.buildSeconds, r.bytes / strands, r.bestMrays,
                    r.hits);
    std::printf("ratio round curves / triangle tubes: %.2fx the Mrays/s, %.2fx the bytes\n",
                results[0].bestMrays / results[2].bestMrays, results[0].bytes / results[2].bytes);
}

void curvesOnly(int strands) {
    const Camera camera(CameraFrame::lookAt(Vec3(0, -3.2f, 0.4f), Vec3(0, 0, 0), Vec3(0, 0, 1)),
                        Projection::Perspective, Camera::windowFromFov(0.7f, 1.0f, kSize, kSize), 1.0f, kSize,
                        kSize);
    const CurveSet round(furball(strands, CurveType::Round));
    const std::vector<ShapeRef> shapes{ShapeRef{nullptr, &round, nullptr}};
    const double t0 = seconds();
    const auto accel = buildEmbreeAccel(std::span<const ShapeRef>(shapes), {});
    const double build = seconds() - t0;
    double best = 0;
    size_t hits = 0;
    for (int r = 0; r < kRounds; ++r) best = std::max(best, trace(*accel, camera, hits));
    std::printf("\n%d strands, round curves only: build %.2f s, %.1f bytes per strand (%.1f of them BVH), "
                "%.2f Mrays/s, %zu hits\n",
                strands, build, double(accel->memoryBytes() + round.memoryBytes()) / strands,
                double(accel->memoryBytes()) / strands, best, hits);
}

}  // namespace
}  // namespace strahl::bench

int main(int argc, char** argv) {
    const int compared = argc > 1 ? std::atoi(argv[1]) : 200000;
    const int alone = argc > 2 ? std::atoi(argv[2]) : 1000000;
    if (compared < 1 || alone < 1) {
        std::fprintf(stderr, "usage: bench_curves [strands compared, >= 1] [strands alone, >= 1]\n");
        return 1;
    }
    strahl::bench::compare(compared);
    strahl::bench::curvesOnly(alone);
    return 0;
}
