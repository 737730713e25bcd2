// Subdivision surfaces: Embree's native subdivision geometry against the
// same limit surface as a triangle mesh (issue 22: "Mrays/s and memory per
// primitive for … subdivision (adaptive)").
//
//   A torus cage of 96 x 48 quads (R = 1, r = 0.4), refined at 2 … 5
//   levels (2^levels segments per cage edge; 4^levels quads per face):
//     subdivision   RTC_GEOMETRY_TYPE_SUBDIVISION at that tessellation rate
//     displaced     the same with a displacement function (strahl's offsets)
//     triangles     strahl's refinement of the limit surface (the naive
//                   tracer's reference, catmull_clark.h) as a triangle mesh,
//                   two triangles per refined quad
//   Figures: build seconds, bytes per refined quad — Embree's (its grids and
//   BVH; for triangles the mesh and its BVH) and with strahl's shading
//   tables of the SubdivisionSurface — and Mrays/s of 512x512 camera rays
//   (single rays, parallel over rows), best of 3 interleaved rounds.
//   Ratios: subdivision vs triangles in Mrays/s and in Embree bytes.
//
// Usage: bench_subdivision [max levels, 2 … 6, default 5]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "camera_rays.h"
#include "strahl/accel/accel.h"
#include "strahl/camera/camera.h"
#include "strahl/geometry/catmull_clark.h"
#include "strahl/geometry/subdivision_surface.h"
#include "strahl/geometry/triangle_mesh.h"

namespace strahl::bench {
namespace {

constexpr int kSize = 512;
constexpr int kRounds = 3;
constexpr int kAround = 96, kTube = 48;

double seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

SubdivisionCage torusCage() {
    SubdivisionCage c;
    for (int i = 0; i < kAround; ++i)
        for (int j = 0; j < kTube; ++j) {
            const double a = 2.0 * kPi * i / kAround, b = 2.0 * kPi * j / kTube;
            c.positions.emplace_back((1.0 + 0.4 * std::cos(b)) * std::cos(a), (1.0 + 0.4 * std::cos(b)) * std::sin(a),
                                     0.4 * std::sin(b));
        }
    for (int i = 0; i < kAround; ++i)
        for (int j = 0; j < kTube; ++j) {
            const auto at = [](int ii, int jj) { return uint32_t((ii % kAround) * kTube + jj % kTube); };
            c.faceSizes.push_back(4);
            c.indices.insert(c.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return c;
}

// The refined limit surface as triangles, split along the diagonal Embree
// uses (catmull_clark.h's corner order is rotated per quad; the mesh takes
// corners 0-1-2 and 0-2-3, which is the same surface up to that diagonal).
TriangleMesh limitTriangles(const SubdivisionCage& cage, int levels) {
    const RefinedSurface r = refineCatmullClark(cage, levels, "torus");
    TriangleMesh mesh;
    mesh.positions.reserve(r.positions.size());
    for (const DVec3& p : r.positions) mesh.positions.emplace_back(p);
    mesh.indices.reserve(r.quads.size() * 6);
    for (const auto& q : r.quads) mesh.indices.insert(mesh.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
    mesh.reservePadding();
    return mesh;
}

struct Result {
    const char* name;
    double buildSeconds = 0, embreeBytes = 0, totalBytes = 0, bestMrays = 0;
    size_t hits = 0;
};

void run(int levels, const Camera& camera) {
    const SubdivisionCage cage = torusCage();
    SubdivisionDesc plain{"torus", cage, levels, nullptr, "", ""};
    SubdivisionDesc bumpy{"torus", cage, levels,
                          [](const DVec3& p, const DVec3&, const DVec2&) {
                              return 0.01 * std::sin(40.0 * p.x) * std::sin(40.0 * p.y) * std::sin(40.0 * p.z);
                          },
                          "bumps", ""};
    const double s0 = seconds();
    const SubdivisionSurface surface(std::move(plain));
    const double refineSeconds = seconds() - s0;
    const SubdivisionSurface displaced(std::move(bumpy));
    const TriangleMesh mesh = limitTriangles(cage, levels);
    const double quads = double(surface.refinedQuadCount());

    std::vector<Result> results{{"subdivision"}, {"displaced"}, {"triangles"}};
    const std::vector<ShapeRef> shapes[3] = {{ShapeRef{nullptr, &surface, nullptr}},
                                             {ShapeRef{nullptr, &displaced, nullptr}},
                                             {ShapeRef{&mesh, nullptr, nullptr}}};
    const size_t shapeBytes[3] = {surface.memoryBytes(), displaced.memoryBytes(), mesh.memoryBytes()};
    std::vector<std::unique_ptr<Accel>> accels;
    for (int i = 0; i < 3; ++i) {
        const double t0 = seconds();
        accels.push_back(buildEmbreeAccel(std::span<const ShapeRef>(shapes[i]), {}));
        Result& r = results[size_t(i)];
        r.buildSeconds = seconds() - t0;
        r.embreeBytes = double(accels.back()->memoryBytes()) + (i == 2 ? double(shapeBytes[i]) : 0.0);
        r.totalBytes = double(accels.back()->memoryBytes() + shapeBytes[i]);
    }
    for (int round = 0; round < kRounds; ++round)
        for (int i = 0; i < 3; ++i) {
            Result& r = results[size_t(i)];
            r.bestMrays = std::max(r.bestMrays, traceCameraRays(*accels[size_t(i)], camera, kSize, r.hits));
        }
    std::printf("\nlevels %d: %d cage faces, %.0f refined quads (strahl's refinement %.2f s)\n", levels,
                kAround * kTube, quads, refineSeconds);
    std::printf("%-12s %9s %16s %16s %9s %8s\n", "geometry", "build s", "Embree B/quad", "with tables B/q", "Mrays/s",
                "hits");
    for (const Result& r : results)
        std::printf("%-12s %9.3f %16.1f %16.1f %9.2f %8zu\n", r.name, r.buildSeconds, r.embreeBytes / quads,
                    r.totalBytes / quads, r.bestMrays, r.hits);
    std::printf("ratio subdivision / triangles: %.2fx the Mrays/s, %.2fx the Embree bytes\n",
                results[0].bestMrays / results[2].bestMrays, results[0].embreeBytes / results[2].embreeBytes);
}

}  // namespace
}  // namespace strahl::bench

int main(int argc, char** argv) {
    const int maxLevels = argc > 1 ? std::atoi(argv[1]) : 5;
    if (maxLevels < 2 || maxLevels > 6) {
        std::fprintf(stderr, "usage: bench_subdivision [max levels, 2 ... 6]\n");
        return 1;
    }
    using namespace strahl;
    const Camera camera(CameraFrame::lookAt(Vec3(0, -2.6f, 1.6f), Vec3(0, 0, 0), Vec3(0, 0, 1)),
                        Projection::Perspective, Camera::windowFromFov(0.8f, 1.0f, 512, 512), 1.0f, 512, 512);
    for (int levels = 2; levels <= maxLevels; ++levels) bench::run(levels, camera);
    return 0;
}
