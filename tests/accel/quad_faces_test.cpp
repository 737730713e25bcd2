// Meshes traced as Embree quads (accel/quad_faces.h): which triangles pair,
// and that every hit on a quad comes back as the hit on the right triangle at
// the right barycentrics — single rays, packets, instances — on a non-planar
// grid split along both diagonals, with rotated index orders and lone
// triangles among the pairs.

#include "strahl/accel/quad_faces.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "strahl/accel/accel.h"
#include "strahl/core/rng.h"
#include "strahl/geometry/cutout.h"

namespace strahl {
namespace {

TriangleMesh fanSplitQuads() {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
    // Faces (0, 1, 2, 3) and (1, 4, 5, 2), each split as a fan from its first corner.
    m.indices = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2};
    m.reservePadding();
    return m;
}

TEST(QuadFaces, FanSplitQuadsNeedNoTable) {
    const QuadFaces quads = pairTriangles(fanSplitQuads());
    EXPECT_EQ(quads.faceCount, 2u);
    EXPECT_TRUE(quads.faces.empty()) << "face k is triangles 2k and 2k + 1";
    EXPECT_EQ(quads.pairedTriangles, 4u);
    // (a, b, c) + (a, c, d) -> Embree's (d, a, b, c), split along a-c.
    EXPECT_EQ(quads.corners, (std::vector<uint32_t>{3, 0, 1, 2, 2, 1, 4, 5}));
    auto pairs = [&]() -> const QuadFaces& { return quads; };
    EXPECT_TRUE(tracesAsQuads(QuadPolicy::Always, 4, pairs));
    EXPECT_FALSE(tracesAsQuads(QuadPolicy::Auto, 4, pairs)) << "too small to pay";
    EXPECT_FALSE(tracesAsQuads(QuadPolicy::Never, 4, pairs));
}

TEST(QuadFaces, AutoTracesLargeWellPairedMeshesAsQuads) {
    QuadFaces quads;
    auto pairs = [&]() -> const QuadFaces& { return quads; };
    const size_t n = kQuadsFromTriangles;
    quads.pairedTriangles = n;
    EXPECT_TRUE(tracesAsQuads(QuadPolicy::Auto, n, pairs));
    EXPECT_FALSE(tracesAsQuads(QuadPolicy::Auto, n - 1, pairs)) << "below the size";
    quads.pairedTriangles = size_t(0.8 * double(n));
    EXPECT_FALSE(tracesAsQuads(QuadPolicy::Auto, n, pairs)) << "too few pairs for auto";
    EXPECT_TRUE(tracesAsQuads(QuadPolicy::Always, n, pairs));
    quads.pairedTriangles = n / 2 - 2;
    EXPECT_FALSE(tracesAsQuads(QuadPolicy::Always, n, pairs)) << "under half paired";
}

TEST(QuadFaces, RotatedPairsAndLoneTrianglesGetATable) {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {5, 5, 5}, {6, 5, 5}, {5, 6, 5}};
    m.indices = {4, 5, 6,            // alone: shares no edge with the next
                 0, 1, 3, 1, 2, 3,   // a cell split along 1-3
                 2, 0, 1};           // alone at the end
    const QuadFaces quads = pairTriangles(m);
    ASSERT_EQ(quads.faceCount, 3u);
    ASSERT_EQ(quads.faces.size(), 3u);
    EXPECT_FALSE(quads.faces[0].pair);
    EXPECT_TRUE(quads.faces[1].pair);
    EXPECT_EQ(quads.faces[1].firstTriangle, 1u);
    EXPECT_FALSE(quads.faces[2].pair);
    EXPECT_EQ(quads.faces[2].firstTriangle, 3u);
    EXPECT_EQ(quads.pairedTriangles, 2u);
    EXPECT_TRUE(tracesAsQuads(QuadPolicy::Always, 4, [&]() -> const QuadFaces& { return quads; }))
        << "half the triangles pair";
    EXPECT_EQ(std::vector<uint32_t>(quads.corners.begin(), quads.corners.begin() + 4),
              (std::vector<uint32_t>{4, 5, 6, 6}))
        << "a lone triangle is the degenerate quad (a, b, c, c)";
    // (0, 1, 3) shares 1->3 with (1, 2, 3)'s 3->1: (a, b, c) = (3, 0, 1), (a, c, d) = (3, 1, 2).
    EXPECT_EQ(std::vector<uint32_t>(quads.corners.begin() + 4, quads.corners.begin() + 8),
              (std::vector<uint32_t>{2, 3, 0, 1}));

    TriangleMesh soup;
    soup.positions = m.positions;
    soup.indices = {4, 5, 6, 0, 1, 2, 1, 2, 3};  // 1->2 twice in one direction: not neighbours of one winding
    const QuadFaces none = pairTriangles(soup);
    EXPECT_EQ(none.pairedTriangles, 0u);
    EXPECT_FALSE(tracesAsQuads(QuadPolicy::Always, 3, [&]() -> const QuadFaces& { return none; }));
}

// A height field over a cells x cells grid, each cell split along a random
// diagonal, every triangle's indices rotated at random, and a lone triangle
// after every seventh cell: the pairing must handle all of it.
TriangleMesh mixedGrid(int cells, uint64_t seed) {
    Pcg32 rng(seed, 3);
    TriangleMesh m;
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i)
            m.positions.emplace_back(float(i), float(j), 0.6f * rng.nextFloat());
    const auto row = static_cast<uint32_t>(cells + 1);
    auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
        const uint32_t r = rng.nextUint() % 3;
        const uint32_t t[3] = {a, b, c};
        m.indices.insert(m.indices.end(), {t[r], t[(r + 1) % 3], t[(r + 2) % 3]});
    };
    int cell = 0;
    for (uint32_t j = 0; j < uint32_t(cells); ++j)
        for (uint32_t i = 0; i < uint32_t(cells); ++i, ++cell) {
            const uint32_t a = j * row + i, b = a + 1, c = a + row + 1, d = a + row;
            if (rng.nextFloat() < 0.5f) {
                emit(a, b, c);
                emit(a, c, d);
            } else {
                emit(a, b, d);
                emit(b, c, d);
            }
            if (cell % 7 == 6) {  // a lone triangle of its own beside the grid
                const auto base = static_cast<uint32_t>(m.positions.size());
                const float y = -2.0f - float(j);
                m.positions.insert(m.positions.end(),
                                   {{float(i), y, 1.0f}, {float(i) + 0.5f, y, 1.0f}, {float(i), y + 0.5f, 1.0f}});
                emit(base, base + 1, base + 2);
            }
        }
    m.reservePadding();
    return m;
}

struct Target {
    uint32_t triangle;
    float u, v;  // barycentrics of the triangle's second and third corner
    Ray ray;     // straight down onto the point
};

// Points well inside random triangles (barycentrics >= 0.05), so no rounding
// can move a hit to a neighbour.
std::vector<Target> targets(const TriangleMesh& m, int count, uint64_t seed) {
    Pcg32 rng(seed, 9);
    std::vector<Target> out;
    while (int(out.size()) < count) {
        const auto t = rng.nextUint() % uint32_t(m.triangleCount());
        const float u = 0.05f + 0.9f * rng.nextFloat(), v = 0.05f + 0.9f * rng.nextFloat();
        if (u + v > 0.95f) continue;
        const uint32_t* i = &m.indices[3 * size_t(t)];
        const Vec3 p = (1.0f - u - v) * m.positions[i[0]] + u * m.positions[i[1]] + v * m.positions[i[2]];
        Ray ray;
        ray.origin = Vec3(p.x, p.y, 10.0f);
        ray.dir = Vec3(0, 0, -1);
        out.push_back({t, u, v, ray});
    }
    return out;
}

void expectTriangleHit(const Hit& hit, const Target& target, const char* what) {
    SCOPED_TRACE(testing::Message() << what << ", triangle " << target.triangle);
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.primID, target.triangle);
    EXPECT_NEAR(hit.u, target.u, 2e-5);
    EXPECT_NEAR(hit.v, target.v, 2e-5);
}

TEST(QuadFaces, EmbreeQuadHitsComeBackAsTheTrianglesHits) {
    const TriangleMesh grid = mixedGrid(24, 5);
    const QuadFaces quads = pairTriangles(grid);
    ASSERT_FALSE(quads.faces.empty());
    ASSERT_TRUE(tracesAsQuads(QuadPolicy::Always, grid.triangleCount(), [&]() -> const QuadFaces& { return quads; }))
        << "the grid must be traced as quads";
    ASSERT_LT(quads.pairedTriangles, grid.triangleCount()) << "and have lone triangles too";

    const TriangleMesh* meshes[] = {&grid};
    AccelBuildOptions asQuads, trianglesOnly;
    asQuads.quads = QuadPolicy::Always;
    trianglesOnly.quads = QuadPolicy::Never;
    const auto accel = buildEmbreeAccel(meshes, asQuads);
    const auto reference = buildEmbreeAccel(meshes, trianglesOnly);
    EXPECT_LT(accel->memoryBytes(), reference->memoryBytes()) << "half the primitives";

    const std::vector<Target> all = targets(grid, 4000, 17);
    for (const Target& target : all) {
        expectTriangleHit(accel->intersect(target.ray), target, "quads");
        expectTriangleHit(reference->intersect(target.ray), target, "triangles");
        EXPECT_TRUE(accel->occluded(target.ray));
    }

    // Packets report what single rays report, lane by lane: the same
    // triangle, and its barycentrics to the last bits (Embree's packet and
    // single-ray quad tests may round differently: on AVX2 machines u and v
    // differ by an ulp in about half of the lanes).
    for (size_t first = 0; first + 16 <= all.size(); first += 16) {
        RayHitPacket16 p16;
        RayHitPacket8 p8;
        alignas(64) int valid16[16];
        alignas(32) int valid8[8];
        for (int lane = 0; lane < 16; ++lane) {
            p16.setRay(lane, all[first + lane].ray);
            valid16[lane] = -1;
            if (lane < 8) {
                p8.setRay(lane, all[first + lane].ray);
                valid8[lane] = -1;
            }
        }
        accel->intersect16(valid16, p16, RayCoherence::Incoherent);
        accel->intersect8(valid8, p8, RayCoherence::Coherent);
        for (int lane = 0; lane < 16; ++lane) {
            const Hit single = accel->intersect(all[first + lane].ray);
            const Hit packed = p16.hit(lane);
            EXPECT_EQ(packed.primID, single.primID);
            EXPECT_NEAR(packed.u, single.u, 1e-6f);
            EXPECT_NEAR(packed.v, single.v, 1e-6f);
            if (lane < 8) {
                EXPECT_EQ(p8.hit(lane).primID, single.primID);
                EXPECT_NEAR(p8.hit(lane).u, single.u, 1e-6f);
                EXPECT_NEAR(p8.hit(lane).v, single.v, 1e-6f);
            }
        }
    }
}

TEST(QuadFaces, HitsInsideInstancesComeBackAsTriangles) {
    const TriangleMesh grid = mixedGrid(8, 11);
    TriangleMesh flat = fanSplitQuads();
    for (Vec3& p : flat.positions) p.y -= 20.0f;  // clear of the grid
    AccelScene scene;
    scene.shapes = {{&flat, nullptr, nullptr}};  // a top-level quad mesh as well
    scene.prototypes = {{{&flat, nullptr, nullptr}, {&grid, nullptr, nullptr}}};
    AccelInstance shifted;
    shifted.prototype = 0;
    shifted.objectToWorld = glm::translate(Mat4(1.0f), Vec3(100.0f, 0.0f, 0.0f));
    scene.instances = {shifted};
    AccelBuildOptions asQuads;
    asQuads.quads = QuadPolicy::Always;
    const auto accel = buildEmbreeAccel(scene, asQuads);

    for (const Target& target : targets(grid, 500, 23)) {
        Ray ray = target.ray;
        ray.origin.x += 100.0f;
        const Hit hit = accel->intersect(ray);
        EXPECT_EQ(hit.instID, scene.instanceId(0));
        EXPECT_EQ(hit.geomID, 1u);
        expectTriangleHit(hit, target, "instanced grid");
    }
    for (const Target& target : targets(flat, 200, 29)) {
        const Hit top = accel->intersect(target.ray);
        EXPECT_EQ(top.instID, kInvalidId);
        expectTriangleHit(top, target, "top-level quads");
        Ray ray = target.ray;
        ray.origin.x += 100.0f;
        const Hit placed = accel->intersect(ray);
        EXPECT_EQ(placed.geomID, 0u);
        expectTriangleHit(placed, target, "instanced quads");
    }
}

// A cut-out sees triangle hits too: a checkerboard over (triangle parity,
// u > 0.5) cuts the same holes traced as quads as traced as triangles.
class TriangleChecker final : public Cutout {
public:
    bool solid(uint32_t prim, float u, float) const noexcept override { return (prim % 2 == 0) == (u > 0.5f); }
};

TEST(QuadFaces, CutoutFiltersSeeTriangleHits) {
    const TriangleMesh grid = mixedGrid(16, 13);
    const TriangleChecker checker;
    const std::vector<ShapeRef> shapes{{&grid, nullptr, &checker}};
    AccelBuildOptions asQuads, trianglesOnly;
    asQuads.quads = QuadPolicy::Always;
    trianglesOnly.quads = QuadPolicy::Never;
    const auto quads = buildEmbreeAccel(std::span<const ShapeRef>(shapes), asQuads);
    const auto triangles = buildEmbreeAccel(std::span<const ShapeRef>(shapes), trianglesOnly);
    int holes = 0;
    for (const Target& target : targets(grid, 2000, 31)) {
        if (std::abs(target.u - 0.5f) < 1e-3f) continue;  // on the checker's edge
        const bool solid = checker.solid(target.triangle, target.u, target.v);
        holes += !solid;
        const Hit a = quads->intersect(target.ray), b = triangles->intersect(target.ray);
        EXPECT_EQ(a.valid(), solid);
        EXPECT_EQ(b.valid(), solid);
        if (solid) expectTriangleHit(a, target, "cut-out quads");
        EXPECT_EQ(quads->occluded(target.ray), solid);
    }
    EXPECT_GT(holes, 500);
}

}  // namespace
}  // namespace strahl
