// Quads: meshes traced as Embree quads against the same meshes as Embree
// triangles (issue 22: "Mrays/s and memory per primitive for ... quads vs
// triangles").
//
//   grid        a procedural height field of 1024 x 1024 cells, each split
//               into two triangles (2.1 M triangles, all pairs) — what the
//               parametric tessellator and most scanned quad meshes give.
//   conference  ../shared/data's conference room OBJ (331 k faces, nearly
//               all quads; skipped when ../shared/data is absent).
//   sponza      ../shared/data's Sponza OBJ (26 k of its 40 k faces quads).
//   For each, both layouts (full and compact) built both ways, and which of
//   the two the default (QuadPolicy::Auto) picks. Figures: build
//   seconds, BVH bytes per stored triangle (Embree's allocations, with the
//   quads' corner and pairing tables) and Mrays/s of 512 x 512 single camera
//   rays parallel over rows, best of 3 interleaved rounds. Ratios: quads /
//   triangles in BVH bytes and Mrays/s. The hit counts must match: the two
//   are one surface.
//
// Usage: bench_quads [cells per side of the grid, default 1024]


#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "camera_rays.h"
#include "strahl/accel/accel.h"
#include "strahl/accel/quad_faces.h"
#include "strahl/camera/camera.h"
#include "strahl/core/error.h"
#include "strahl/meshio/mesh_file.h"

namespace strahl::bench {
namespace {

constexpr int kSize = 512;
constexpr int kRounds = 3;

double seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

TriangleMesh heightField(int cells) {
    TriangleMesh m;
    m.positions.reserve(size_t(cells + 1) * (cells + 1) + 1);
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
            const float x = float(i) / float(cells), y = float(j) / float(cells);
            m.positions.emplace_back(x, y, 0.05f * std::sin(40.0f * x) * std::cos(33.0f * y));
        }
    const auto row = uint32_t(cells + 1);
    m.indices.reserve(size_t(cells) * cells * 6);
    for (uint32_t j = 0; j < uint32_t(cells); ++j)
        for (uint32_t i = 0; i < uint32_t(cells); ++i) {
            const uint32_t a = j * row + i, b = a + 1, c = a + row + 1, d = a + row;
            m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
        }
    m.reservePadding();
    return m;
}

struct Case {
    std::string name;
    TriangleMesh mesh;
    Camera camera;
};

double trace(const Accel& accel, const Camera& camera, size_t& hits) {
    return traceCameraRays(accel, camera, kSize, hits);
}

Camera looking(const Vec3& eye, const Vec3& at, const Vec3& up, float fovDegrees) {
    return Camera(CameraFrame::lookAt(eye, at, up), Projection::Perspective,
                  Camera::windowFromFov(glm::radians(fovDegrees), 1.0f, kSize, kSize), 1.0f, kSize, kSize);
}

void run(const Case& c) {
    const QuadFaces pairs = pairTriangles(c.mesh);
    const double triangles = double(c.mesh.triangleCount());
    const bool automatic =
        tracesAsQuads(QuadPolicy::Auto, c.mesh.triangleCount(), [&]() -> const QuadFaces& { return pairs; });
    std::printf("\n%s: %zu triangles, %.1f %% of them paired (%zu quad faces); the default traces it as %s\n",
                c.name.c_str(), c.mesh.triangleCount(), 100.0 * double(pairs.pairedTriangles) / triangles,
                pairs.faceCount, automatic ? "quads" : "triangles");
    std::printf("%-8s %-10s %8s %16s %9s %9s\n", "layout", "primitive", "build s", "BVH bytes/tri", "Mrays/s",
                "hits");
    const TriangleMesh* meshes[] = {&c.mesh};
    for (bool compact : {false, true}) {
        struct Run {
            bool quads;
            std::unique_ptr<Accel> accel;
            double build = 0, best = 0;
            size_t hits = 0;
        } runs[2] = {{false, nullptr}, {true, nullptr}};
        for (Run& r : runs) {
            AccelBuildOptions options;
            options.compact = compact;
            options.quads = r.quads ? QuadPolicy::Always : QuadPolicy::Never;
            const double t0 = seconds();
            r.accel = buildEmbreeAccel(meshes, options);
            r.build = seconds() - t0;
        }
        for (int round = 0; round < kRounds; ++round)
            for (Run& r : runs) r.best = std::max(r.best, trace(*r.accel, c.camera, r.hits));
        for (const Run& r : runs)
            std::printf("%-8s %-10s %8.2f %16.1f %9.2f %9zu\n", compact ? "compact" : "full",
                        r.quads ? "quads" : "triangles", r.build, double(r.accel->memoryBytes()) / triangles, r.best,
                        r.hits);
        std::printf("ratio quads / triangles (%s): %.2fx the BVH bytes, %.2fx the Mrays/s%s\n",
                    compact ? "compact" : "full",
                    double(runs[1].accel->memoryBytes()) / double(runs[0].accel->memoryBytes()),
                    runs[1].best / runs[0].best, runs[0].hits == runs[1].hits ? "" : "  HIT COUNTS DIFFER");
    }
}

std::filesystem::path sharedData() {
    return std::filesystem::path(STRAHL_SOURCE_DIR).parent_path() / "shared" / "data";
}

}  // namespace
}  // namespace strahl::bench

int main(int argc, char** argv) {
    using namespace strahl;
    using namespace strahl::bench;
    const int cells = argc > 1 ? std::atoi(argv[1]) : 1024;
    if (cells < 1 || cells > 8192) {
        std::fprintf(stderr, "usage: bench_quads [cells per side of the grid, 1 to 8192]\n");
        return 1;
    }
    try {
        run({"grid", heightField(cells), looking(Vec3(0.5f, -0.6f, 0.6f), Vec3(0.5f, 0.5f, 0.0f), Vec3(0, 0, 1), 50)});
        const auto data = sharedData();
        if (!std::filesystem::exists(data)) {
            std::printf("\nconference, sponza: skipped (%s is absent)\n", data.string().c_str());
            return 0;
        }
        TriangleMesh conference = loadObj(data / "conference/conference.obj").mesh;
        conference.reservePadding();
        const Bounds3 cb = conference.bounds();
        // Inside the room, looking along its length at the table.
        const Vec3 centre = cb.center();
        run({"conference", std::move(conference),
             looking(centre + Vec3(0.45f * cb.diagonal().x, 0.1f * cb.diagonal().y, 0.0f), centre,
                     Vec3(0, 1, 0), 70)});
        TriangleMesh sponza = loadObj(data / "sponza-dabrovic/sponza.obj").mesh;
        sponza.reservePadding();
        const Bounds3 sb = sponza.bounds();
        run({"sponza", std::move(sponza),
             looking(sb.center() + Vec3(0.4f * sb.diagonal().x, -0.2f * sb.diagonal().y, 0.0f),
                     sb.center() - Vec3(0.2f * sb.diagonal().x, 0.1f * sb.diagonal().y, 0.0f), Vec3(0, 1, 0), 70)});
    } catch (const Error& e) {
        std::fprintf(stderr, "bench_quads: %s\n", e.what());
        return 1;
    }
    return 0;
}
