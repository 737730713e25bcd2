// Watertightness of closed parametric surfaces in both modes: rays aimed from
// outside at points of the seams and poles — where a tessellation has welded
// vertices and the direct mode hands roots from one sub-patch to the next —
// must all hit: 10⁶ rays per mode (sphere and torus), through the naive
// tracer's watertight triangle test for tessellations and through Embree for
// the direct mode (the naive tracer, calling the same shape code, on a sample).

#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <atomic>
#include <random>

#include "strahl/core/point3.h"

#include "sanitizers/sanitized.h"
#include "strahl/accel/accel.h"
#include "strahl/geometry/parametric_builtins.h"
#include "strahl/geometry/parametric_shape.h"
#include "strahl/geometry/parametric_tessellation.h"
#include "strahl/reference/naive_accel.h"

namespace strahl {
namespace {

// Surface points on the seams and poles of a closed surface, and the points
// of its tessellation on the corresponding welded edges.
struct Target {
    DVec3 onSurface;
    DVec3 onMesh;
    DVec3 normal;  // of the surface there
};

// Rays per surface and mode: 500 000 (10⁶ per mode); a quarter of that under
// the sanitizers, where they take minutes (tests/sanitizers/sanitized.h).
const int kTargets = test::fullOrSanitized(500000, 125000);

// A point on the seam/pole lines of the domain: one parameter at a border or
// (for the sphere) a pole, the other random; on the mesh, the same point of
// the grid line between its two neighbouring grid points.
std::vector<Target> seamTargets(const ParametricSurface& s, const PatchGrid& grid, int count,
                                uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Target> targets;
    targets.reserve(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
        const bool alongV = (i % 2) == 0;  // fix u at a border, vary v; else the reverse
        const std::vector<double>& fixedList = alongV ? grid.u : grid.v;
        const std::vector<double>& freeList = alongV ? grid.v : grid.u;
        const double fixed = (i % 4) < 2 ? fixedList.front() : fixedList.back();
        const size_t k = static_cast<size_t>(unit(rng) * double(freeList.size() - 1));
        const double w = unit(rng);
        const double a = freeList[k], b = freeList[k + 1];
        const double p = a + w * (b - a);
        auto at = [&](double fr) { return alongV ? s.point(0, fixed, fr) : s.point(0, fr, fixed); };
        const double u = alongV ? fixed : p, v = alongV ? p : fixed;
        targets.push_back({at(p), (1.0 - w) * at(a) + w * at(b), s.normal(0, u, v)});
    }
    return targets;
}

// A ray from outside, at 6 units, towards `target`, arriving within 70° of
// the surface normal there. (A grazing ray aimed at a point of a silhouette
// may rightly pass it by the rounding of its float direction.)
Ray rayTo(const DVec3& target, const DVec3& normal, std::mt19937& rng) {
    std::normal_distribution<double> n;
    DVec3 towards;
    do towards = DVec3(n(rng), n(rng), n(rng));
    while (glm::length(towards) < 1e-3 || glm::dot(glm::normalize(towards), normal) < 0.35);
    Ray ray;
    ray.origin = Vec3(target + 6.0 * glm::normalize(towards));
    ray.dir = Vec3(target) - ray.origin;
    return ray;
}

// How many of the rays miss.
size_t misses(const Accel& accel, const std::vector<Ray>& rays) {
    std::atomic<size_t> missed{0};
    tbb::parallel_for(size_t(0), rays.size(), [&](size_t i) {
        if (!accel.intersect(rays[i]).valid()) ++missed;
    });
    return missed;
}

struct Closed {
    const char* name;
    ParametricSurfacePtr surface;
};

std::vector<Closed> closedSurfaces() {
    return {{"sphere", makeParametricSphere(1.0)}, {"torus", makeParametricTorus(1.0, 0.4)}};
}

TEST(ParametricWatertight, TessellationHasNoCracksAtSeamsAndPoles) {
    // The naive tracer's watertight triangle test (Woop et al.) is the oracle:
    // 10⁶ rays through a tessellation coarse enough to test every triangle.
    // Embree in its default (non-robust) mode may let a ray slip through a
    // vertex shared by many triangles; we allow it 1 in 10⁵ on an adaptive
    // tessellation (measured: 1 in 10⁶). Its robust mode would close that,
    // but changes its t near tnear enough to need its own spawn offsets.
    for (const Closed& c : closedSurfaces()) {
        for (const bool adaptive : {false, true}) {
            ParametricGridOptions options;
            options.initialSegmentsU = options.initialSegmentsV = adaptive ? 4 : 12;
            if (adaptive) options.maxChordError = 2e-3;
            const ParametricGrid grid = buildParametricGrid(*c.surface, options);
            Tessellation t = tessellateParametric(*c.surface, grid, ParametricNormals::Exact);
            t.mesh.reservePadding();
            const std::vector<Target> targets =
                seamTargets(*c.surface, grid.patches[0], kTargets, 1);
            std::mt19937 rng(2);
            std::vector<Ray> rays;
            for (const Target& target : targets) rays.push_back(rayTo(target.onMesh, target.normal, rng));
            const ShapeRef refs[] = {ShapeRef{&t.mesh, nullptr}};
            if (adaptive) {
                EXPECT_LE(misses(*buildEmbreeAccel(std::span<const ShapeRef>(refs), {}), rays), rays.size() / 100000)
                    << c.name;
            } else {
                EXPECT_EQ(misses(*buildNaiveAccel(AccelScene{{refs[0]}, {}, {}}), rays), 0u) << c.name;
            }
        }
    }
}

TEST(ParametricWatertight, DirectModeHasNoHolesAtSeamsAndPoles) {
    for (const Closed& c : closedSurfaces()) {
        const ParametricShape shape(c.surface, Mat4(1.0f), ParametricShapeOptions{});
        // The sub-patch grid's own lines are borders too: aim at those of a
        // grid as fine as the shape's.
        ParametricGridOptions options;
        options.initialSegmentsU = options.initialSegmentsV = 4;
        options.maxChordError = 2e-3 * parametricExtent(*c.surface);
        const ParametricGrid grid = buildParametricGrid(*c.surface, options);
        const std::vector<Target> targets = seamTargets(*c.surface, grid.patches[0], kTargets, 3);
        std::mt19937 rng(4);
        std::vector<Ray> rays;
        for (const Target& target : targets) rays.push_back(rayTo(target.onSurface, target.normal, rng));
        const ShapeRef refs[] = {ShapeRef{nullptr, &shape}};
        EXPECT_EQ(misses(*buildEmbreeAccel(std::span<const ShapeRef>(refs), {}), rays), 0u) << c.name;
        const std::vector<Ray> sample(rays.begin(), rays.begin() + 2000);
        EXPECT_EQ(misses(*buildNaiveAccel(AccelScene{{refs[0]}, {}, {}}), sample), 0u) << c.name;
    }
}

}  // namespace
}  // namespace strahl
