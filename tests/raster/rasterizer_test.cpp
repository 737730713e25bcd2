// The rasterizer against ray casting, one rule at a time: coverage and depth
// of single triangles (perspective and orthographic, both windings), shared
// edges and a shared vertex lying exactly on pixel centres (covered exactly
// once), a watertight grid, the near plane where camera rays start, the
// z-test and its tie rule, determinism, and what it refuses to draw.
//
// The reference is the naive tracer (watertight, Woop et al.) shooting the
// renderer's own camera rays through the pixel centres.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "raster_test_support.h"
#include "strahl/core/sampler.h"
#include "strahl/reference/watertight_triangle.h"
#include "test_support.h"

namespace strahl {
namespace {

using test::rasterHits;
using test::sameSurface;
using test::sceneFromText;
using test::TestScene;
using test::traceHits;

// How closely a rasterized hit's t, u, v must match the ray tracer's: both are
// float results of different formulas for the same quantities (plane
// intersection in double vs the watertight test in float). t is a difference
// of coordinates of size ~1 in these scenes, so besides a relative part it is
// off by up to ~1e-7 absolute (visible where t is tiny, just past the image
// plane).
constexpr float kRelativeT = 1e-5f;
constexpr float kBarycentric = 1e-5f;
float tTolerance(float t) {
    return kRelativeT * (t + 1.0f);
}

// Every pixel: the same surface (or both nothing) and, on hits, t, u, v and the
// direction of Ng to rounding. Returns the number of covered pixels.
int expectSameHits(const TestScene& scene, const std::vector<Hit>& raster,
                   const std::vector<Hit>& traced) {
    EXPECT_EQ(raster.size(), traced.size());
    int covered = 0, reported = 0;
    for (size_t p = 0; p < std::min(raster.size(), traced.size()); ++p) {
        const Hit& r = raster[p];
        const Hit& t = traced[p];
        const auto where = [&] {
            return "pixel (" + std::to_string(p % size_t(scene.width())) + ", " +
                   std::to_string(p / size_t(scene.width())) + ")";
        };
        if (!sameSurface(r, t)) {
            if (++reported <= 5)
                ADD_FAILURE() << where() << ": raster (" << r.geomID << ", " << r.primID
                              << ") vs traced (" << t.geomID << ", " << t.primID << ")";
            continue;
        }
        if (!r.valid()) continue;
        ++covered;
        EXPECT_NEAR(r.t, t.t, tTolerance(t.t)) << where();
        EXPECT_NEAR(r.u, t.u, kBarycentric) << where();
        EXPECT_NEAR(r.v, t.v, kBarycentric) << where();
        EXPECT_GT(glm::dot(glm::normalize(r.Ng), glm::normalize(t.Ng)), 1.0f - 1e-6f) << where();
    }
    return covered;
}

// Two triangles, one counter-clockwise and one clockwise as seen from the
// camera, tilted against the image plane.
const std::string kTwoTriangles = R"(
  "shapes": [ { "type": "mesh",
                "positions": [[-1.2, -0.9, 0.3], [0.6, -0.7, -0.4], [-0.2, 1.0, 0.1],
                              [0.5, 0.2, 0.5], [1.4, 0.9, -0.6], [1.3, -1.0, 0.0]],
                "indices": [0, 1, 2, 3, 4, 5] } ] })";

TEST(Rasterizer, SingleTrianglesMatchRayCastingInPerspective) {
    const TestScene scene = sceneFromText(
        R"({ "camera": { "eye": [0.3, 0.4, 4], "look_at": [0, 0, 0], "fov": 40 },
             "film": { "width": 64, "height": 48 },)" +
        kTwoTriangles);
    RasterStats stats;
    const std::vector<Hit> raster = rasterHits(scene, &stats);
    const int covered = expectSameHits(scene, raster, traceHits(scene));
    EXPECT_GT(covered, 400);          // both triangles are well in view...
    EXPECT_LT(covered, 64 * 48 / 2);  // ...and do not fill it
    EXPECT_EQ(stats.triangles, 2u);
    EXPECT_EQ(stats.trianglesInView, 2u);
    EXPECT_EQ(stats.coveredPixels, uint64_t(covered));
    EXPECT_EQ(stats.fragments, stats.coveredPixels);  // they do not overlap
}

TEST(Rasterizer, SingleTrianglesMatchRayCastingInOrthographic) {
    const TestScene scene = sceneFromText(
        R"({ "camera": { "type": "orthographic", "eye": [0.2, 0.1, 3], "back": [0.15, 0.25, 1],
                         "up": [0, 1, 0], "window": [-1.6, 1.6, -1.2, 1.2] },
             "film": { "width": 60, "height": 45 },)" +
        kTwoTriangles);
    const int covered = expectSameHits(scene, rasterHits(scene), traceHits(scene));
    EXPECT_GT(covered, 300);
    EXPECT_LT(covered, 60 * 45 / 2);
}

// Point in a simple polygon (crossing number) in double, and the distance of a
// point to the polygon's outline: an independent check of the coverage count.
bool insidePolygon(const std::vector<glm::dvec2>& poly, glm::dvec2 p) {
    bool inside = false;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
        if ((poly[i].y > p.y) != (poly[j].y > p.y) &&
            p.x < (poly[j].x - poly[i].x) * (p.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x)
            inside = !inside;
    return inside;
}

double distanceToOutline(const std::vector<glm::dvec2>& poly, glm::dvec2 p) {
    double best = 1e300;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const glm::dvec2 e = poly[i] - poly[j];
        const double s = glm::clamp(glm::dot(p - poly[j], e) / glm::dot(e, e), 0.0, 1.0);
        best = std::min(best, glm::length(p - (poly[j] + s * e)));
    }
    return best;
}

// An orthographic camera whose 16 x 16 pixel centres are the half-integer
// points of [-8, 8]^2, all exactly representable: pixel (i, j) has its centre
// at (i - 7.5, 7.5 - j).
const std::string kHalfIntegerCamera = R"(
  "camera": { "type": "orthographic", "eye": [0, 0, 5], "back": [0, 0, 1], "up": [0, 1, 0],
              "window": [-8, 8, -8, 8] },
  "film": { "width": 16, "height": 16 },)";

// Rasterizes `mesh` (JSON positions and indices, in the plane z = 0) with the
// half-integer camera and checks that every pixel centre strictly inside
// `outline` is covered exactly once and no other is. Returns the hits.
std::vector<Hit> expectCoveredOnce(const std::string& mesh,
                                   const std::vector<glm::dvec2>& outline) {
    const TestScene scene = sceneFromText("{" + kHalfIntegerCamera +
                                          R"( "shapes": [ { "type": "mesh", )" + mesh + " } ] }");
    RasterStats stats;
    const std::vector<Hit> hits = rasterHits(scene, &stats);
    uint64_t inside = 0;
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) {
            const glm::dvec2 centre(i - 7.5, 7.5 - j);
            // The premise: no centre lies on the outline, where the tie rule
            // (not the ray tracer's closed triangles) would decide.
            EXPECT_GT(distanceToOutline(outline, centre), 1e-3) << i << ", " << j;
            const bool expected = insidePolygon(outline, centre);
            inside += expected;
            EXPECT_EQ(hits[size_t(j) * 16 + size_t(i)].valid(), expected)
                << "pixel (" << i << ", " << j << ")";
        }
    EXPECT_EQ(stats.coveredPixels, inside);
    EXPECT_EQ(stats.fragments, inside) << "some pixel centre was covered twice";
    return hits;
}

TEST(Rasterizer, QuadDiagonalThroughPixelCentresIsCoveredOnce) {
    // The diagonal from (-6.3, -6.3) to (5.8, 5.8) passes exactly through the
    // twelve centres (c, c), c = -5.5 ... 5.5: each is an exact tie (E == 0)
    // between the two triangles, which the tie rule gives to one of them.
    const std::vector<glm::dvec2> outline = {
        {-6.3f, -6.3f}, {5.9f, -6.2f}, {5.8f, 5.8f}, {-6.1f, 5.7f}};
    const std::vector<Hit> hits = expectCoveredOnce(
        R"("positions": [[-6.3, -6.3, 0], [5.9, -6.2, 0], [5.8, 5.8, 0], [-6.1, 5.7, 0]],
           "indices": [0, 1, 2, 0, 2, 3])",
        outline);
    // One rule decides the whole edge, so one triangle gets all twelve; the
    // weight of the vertex off the diagonal is exactly 0 there (B, vertex 1,
    // of triangle 0; D, vertex 2, of triangle 1).
    const uint32_t owner = hits[13 * 16 + 2].primID;
    for (int i = 2; i <= 13; ++i) {  // centre (i - 7.5, 7.5 - j) with j = 15 - i
        const Hit& h = hits[size_t(15 - i) * 16 + size_t(i)];
        ASSERT_TRUE(h.valid()) << i;
        EXPECT_EQ(h.primID, owner) << i;
        EXPECT_EQ(h.primID == 0 ? h.u : h.v, 0.0f) << i;
    }
}

TEST(Rasterizer, FanAroundAVertexOnAPixelCentreIsCoveredOnce) {
    // Eight triangles around the vertex (0.5, 0.5), a pixel centre where all
    // eight meet; three spokes run exactly through further centres
    // (horizontal, vertical, diagonal). Every other triangle is wound
    // clockwise: coverage must not depend on the winding.
    const std::vector<glm::dvec2> outline = {{6.1f, 0.5f},  {4.3f, 5.2f},   {0.5f, 6.3f},
                                             {-4.9f, 4.1f}, {-6.2f, -0.3f}, {-4.7f, -4.7f},
                                             {0.2f, -6.4f}, {4.6f, -3.9f}};
    const std::vector<Hit> hits = expectCoveredOnce(
        R"("positions": [[0.5, 0.5, 0], [6.1, 0.5, 0], [4.3, 5.2, 0], [0.5, 6.3, 0],
                         [-4.9, 4.1, 0], [-6.2, -0.3, 0], [-4.7, -4.7, 0], [0.2, -6.4, 0],
                         [4.6, -3.9, 0]],
           "indices": [0, 1, 2,  0, 3, 2,  0, 3, 4,  0, 5, 4,  0, 5, 6,  0, 7, 6,  0, 7, 8,
                       0, 1, 8])",
        outline);
    EXPECT_TRUE(hits[7 * 16 + 8].valid()) << "the shared vertex's pixel (8, 7)";
}

// A planar grid of jittered vertices, triangles of random winding, larger than
// the view: every pixel centre lies in exactly one triangle.
SceneDesc jitteredGridScene() {
    SceneDesc desc = parseSceneText(
        R"({ "camera": { "eye": [0.2, -0.5, 3], "look_at": [0, 0, 0], "fov": 45 },
             "film": { "width": 96, "height": 72 },
             "shapes": [ { "type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]],
                           "indices": [0, 1, 2] } ] })",
        "grid.json");
    constexpr int kCells = 48;  // 0.125-unit cells over [-3, 3]^2
    constexpr float kCell = 6.0f / kCells;
    // Of a cell: a vertex then moves at most 0.28 cells, two of them 0.57, less
    // than the 0.71-cell height of a half cell — no triangle can flip.
    constexpr float kJitter = 0.2f;
    Pcg32 rng(7, 1);
    TriangleMesh& mesh = desc.shapes[0].inlineMesh;
    mesh = TriangleMesh{};
    for (int j = 0; j <= kCells; ++j)
        for (int i = 0; i <= kCells; ++i) {
            const bool border = i == 0 || j == 0 || i == kCells || j == kCells;
            const float dx = border ? 0.0f : kJitter * kCell * (2.0f * rng.nextFloat() - 1.0f);
            const float dy = border ? 0.0f : kJitter * kCell * (2.0f * rng.nextFloat() - 1.0f);
            mesh.positions.emplace_back(-3.0f + kCell * float(i) + dx,
                                        -3.0f + kCell * float(j) + dy, 0.0f);
        }
    auto vertex = [](int i, int j) { return uint32_t(j * (kCells + 1) + i); };
    auto triangle = [&](uint32_t a, uint32_t b, uint32_t c) {
        if (rng.nextFloat() < 0.5f) std::swap(b, c);
        mesh.indices.insert(mesh.indices.end(), {a, b, c});
    };
    for (int j = 0; j < kCells; ++j)
        for (int i = 0; i < kCells; ++i) {
            // Alternate the diagonal so vertices have 4 to 8 neighbours.
            if ((i + j) % 2 == 0) {
                triangle(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1));
                triangle(vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1));
            } else {
                triangle(vertex(i, j), vertex(i + 1, j), vertex(i, j + 1));
                triangle(vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1));
            }
        }
    return desc;
}

TEST(Rasterizer, JitteredGridIsWatertightInPerspective) {
    const TestScene scene(jitteredGridScene(), AccelKind::Naive);
    RasterStats stats;
    const std::vector<Hit> raster = rasterHits(scene, &stats);
    const uint64_t pixels = 96 * 72;
    EXPECT_EQ(stats.coveredPixels, pixels) << "a pixel fell through a crack";
    EXPECT_EQ(stats.fragments, pixels) << "a pixel was covered twice";
    EXPECT_GT(stats.trianglesInView, 1000u);  // so the image crosses many edges
    // The same triangles as the ray tracer's, except where a centre lies within
    // rounding of an edge (none here, but that is luck, not a rule).
    const std::vector<Hit> traced = traceHits(scene);
    int same = 0;
    for (size_t p = 0; p < raster.size(); ++p) same += sameSurface(raster[p], traced[p]);
    EXPECT_GE(same, int(pixels) - 2);
}

// The pixels whose camera ray, extended backwards from where it starts, meets
// shape `geomID` (one triangle) before that start: what the near plane hides.
// The rasterizer must not draw that shape there (a line meets a triangle once).
// Returns how many such pixels there are.
int expectHiddenBeforeRayStart(const TestScene& scene, const std::vector<Hit>& raster,
                               uint32_t geomID) {
    constexpr float kBackwards = 10.0f;  // well past the eye for these scenes
    const TriangleMesh& mesh = scene.world.shapes[geomID].mesh;
    const TileRayGenerator rays(scene.camera, 0, 1);
    int hidden = 0;
    for (int y = 0; y < scene.desc.film.height; ++y)
        for (int x = 0; x < scene.width(); ++x) {
            Sampler rng;
            Ray line = rays.sampleRay(x, y, 0, rng);
            line.origin -= kBackwards * line.dir;
            line.tfar = kBackwards;
            Hit before;
            if (!intersectTriangleWatertight(line, mesh.positions[0], mesh.positions[1],
                                             mesh.positions[2], before))
                continue;
            ++hidden;
            EXPECT_NE(raster[size_t(y) * size_t(scene.width()) + size_t(x)].geomID, geomID)
                << "pixel (" << x << ", " << y << ")";
        }
    return hidden;
}

TEST(Rasterizer, NothingNearerThanTheImagePlaneIsVisible) {
    // Perspective rays start on the image plane (d = 1 here). A floor triangle
    // with two vertices behind the eye is cut there: its part nearer than the
    // plane (the rows below v = -0.3) is not drawn, and neither is a small
    // triangle wholly between the eye and the plane, nor the near part of a
    // slanted wall that crosses the plane.
    const TestScene scene = sceneFromText(R"({
      "camera": { "eye": [0, 0, 0], "look_at": [0, 0, -1], "fov": 60, "focal_distance": 1 },
      "film": { "width": 64, "height": 48 },
      "shapes": [
        { "type": "mesh", "name": "floor",
          "positions": [[-6, -0.3, 3], [6, -0.3, 3], [0, -0.3, -12]], "indices": [0, 1, 2] },
        { "type": "mesh", "name": "too near",
          "positions": [[-0.2, -0.1, -0.5], [0.2, -0.1, -0.5], [0, 0.2, -0.6]], "indices": [0, 1, 2] },
        { "type": "mesh", "name": "wall",
          "positions": [[0.25, -0.25, -0.4], [0.7, -0.1, -3], [0.35, 0.45, -2.5]], "indices": [0, 1, 2] }
      ] })");
    RasterStats stats;
    const std::vector<Hit> raster = rasterHits(scene, &stats);
    const std::vector<Hit> traced = traceHits(scene);
    expectSameHits(scene, raster, traced);

    int floor = 0, wall = 0, tooNear = 0;
    for (const Hit& h : raster) {
        floor += h.valid() && h.geomID == 0;
        tooNear += h.valid() && h.geomID == 1;
        wall += h.valid() && h.geomID == 2;
    }
    EXPECT_GT(floor, 200);
    EXPECT_GT(wall, 5);
    EXPECT_EQ(tooNear, 0);
    // The bottom row looks at the floor nearer than the image plane: empty.
    for (int x = 0; x < 64; ++x) EXPECT_FALSE(raster[47 * 64 + size_t(x)].valid()) << x;
    // The small triangle and the wall's near part are in view from the eye,
    // between the eye and the image plane: hidden, never drawn.
    EXPECT_GT(expectHiddenBeforeRayStart(scene, raster, 1), 20);
    EXPECT_GT(expectHiddenBeforeRayStart(scene, raster, 2), 2);
}

TEST(Rasterizer, NothingBehindAnOrthographicEyePlaneIsVisible) {
    // Orthographic rays start on the plane through the eye (z = 1 here): the
    // triangle reaching from z = -2 to z = 3 shows only its part below z = 1.
    const TestScene scene = sceneFromText(R"({
      "camera": { "type": "orthographic", "eye": [0, 0, 1], "back": [0, 0, 1], "up": [0, 1, 0],
                  "window": [-2, 2, -2, 2] },
      "film": { "width": 40, "height": 40 },
      "shapes": [ { "type": "mesh", "positions": [[-1.8, -1.5, -2], [1.7, -1.2, 3], [0.1, 1.6, 0.5]],
                    "indices": [0, 1, 2] } ] })");
    const std::vector<Hit> raster = rasterHits(scene);
    const int covered = expectSameHits(scene, raster, traceHits(scene));
    EXPECT_GT(covered, 100);
    EXPECT_GT(expectHiddenBeforeRayStart(scene, raster, 0), 20);
}

TEST(Rasterizer, NearestWinsAndExactTiesGoToTheSmallerIds) {
    // A back quad (geomID 0); in front of it the same triangle three times:
    // geomID 1 holds it reversed (primID 0) and as given (primID 1), geomID 2
    // once more. All three have bit-identical t (a reversed triangle's plane
    // normal is exactly the negated one), so (1, 0) must win everywhere.
    const TestScene scene = sceneFromText("{" + kHalfIntegerCamera + R"(
      "shapes": [
        { "type": "mesh", "positions": [[-7, -7, 0], [7, -7, 0], [7, 7, 0], [-7, 7, 0]],
          "indices": [0, 1, 2, 0, 2, 3] },
        { "type": "mesh", "positions": [[-4.2, -3.9, 0.5], [4.1, -2.2, 1.5], [0.3, 4.4, 1.0]],
          "indices": [0, 2, 1, 0, 1, 2] },
        { "type": "mesh", "positions": [[-4.2, -3.9, 0.5], [4.1, -2.2, 1.5], [0.3, 4.4, 1.0]],
          "indices": [0, 1, 2] } ] })");
    RasterStats stats;
    const std::vector<Hit> raster = rasterHits(scene, &stats);
    const std::vector<Hit> traced = traceHits(scene);
    int front = 0;
    for (size_t p = 0; p < raster.size(); ++p) {
        ASSERT_TRUE(raster[p].valid() == traced[p].valid()) << p;
        if (!raster[p].valid()) continue;
        if (traced[p].geomID == 0) {
            EXPECT_EQ(raster[p].geomID, 0u) << p;
            continue;
        }
        ++front;
        EXPECT_EQ(raster[p].geomID, 1u) << p;
        EXPECT_EQ(raster[p].primID, 0u) << p;
        EXPECT_NEAR(raster[p].t, traced[p].t, tTolerance(traced[p].t)) << p;
    }
    EXPECT_GT(front, 30);
    // Each front pixel got four fragments (quad + three copies).
    EXPECT_EQ(stats.fragments, stats.coveredPixels + 3u * uint64_t(front));
}

TEST(Rasterizer, SameHitsForAnyThreadCountAndTileSize) {
    const TestScene scene(jitteredGridScene(), AccelKind::Naive);
    RasterStats reference;
    const std::vector<Hit> a = rasterHits(scene, &reference, 1, 32);
    for (const auto& [threads, tile] : {std::pair{2, 7}, std::pair{2, 32}, std::pair{0, 5}}) {
        SCOPED_TRACE("threads " + std::to_string(threads) + ", tile " + std::to_string(tile));
        RasterStats stats;
        const std::vector<Hit> b = rasterHits(scene, &stats, threads, tile);
        ASSERT_EQ(a.size(), b.size());
        int differing = 0;
        for (size_t p = 0; p < a.size(); ++p)
            differing += a[p].t != b[p].t || a[p].u != b[p].u || a[p].v != b[p].v ||
                         a[p].Ng != b[p].Ng || !sameSurface(a[p], b[p]);
        EXPECT_EQ(differing, 0);
        EXPECT_EQ(stats.fragments, reference.fragments);
        EXPECT_EQ(stats.coveredPixels, reference.coveredPixels);
    }
}

TEST(Rasterizer, CropRendersTheSameHitsAsTheFullImage) {
    const TestScene scene(jitteredGridScene(), AccelKind::Naive);
    const std::vector<Hit> full = rasterHits(scene);
    const PixelRect crop{13, 9, 61, 40};
    const std::vector<Hit> part = rasterizeHits(scene.world, scene.camera, crop, RenderOptions{});
    ASSERT_EQ(part.size(), size_t(crop.area()));
    for (int y = crop.y0; y < crop.y1; ++y)
        for (int x = crop.x0; x < crop.x1; ++x) {
            const Hit& a = full[size_t(y) * 96 + size_t(x)];
            const Hit& b = part[size_t(y - crop.y0) * size_t(crop.width()) + size_t(x - crop.x0)];
            EXPECT_TRUE(sameSurface(a, b) && a.t == b.t) << x << ", " << y;
        }
}

TEST(Rasterizer, RefusesWhatItCannotDraw) {
    // An implicit surface needs the ray tracer.
    const TestScene implicit = sceneFromText(R"({
      "shapes": [ { "type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [0,1,2] },
                  { "type": "implicit", "name": "ball", "surface": { "type": "sphere" } } ] })");
    const std::string shapeMessage =
        test::errorMessage([&] { requireRasterizable(implicit.world); });
    EXPECT_TRUE(test::contains(shapeMessage, "'ball'")) << shapeMessage;
    EXPECT_TRUE(test::contains(shapeMessage, "triangle meshes only")) << shapeMessage;

    // Cut-outs (material opacity) need the accelerators' filters.
    const TestScene leaf = sceneFromText(R"({
      "materials": [ { "name": "leaf", "opacity": 0.5 } ],
      "shapes": [ { "type": "mesh", "name": "leaf", "material": "leaf",
                    "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [0,1,2] } ] })");
    const std::string cutMessage = test::errorMessage([&] { requireRasterizable(leaf.world); });
    EXPECT_TRUE(test::contains(cutMessage, "'leaf' has a material with an opacity")) << cutMessage;

    // Integrators that trace more than the first hit, and more than one sample.
    const std::string direct = test::errorMessage([] { requireRasterSettings("direct", 1); });
    EXPECT_TRUE(test::contains(direct, "'direct'")) << direct;
    const std::string spp = test::errorMessage([] { requireRasterSettings("eyelight", 4); });
    EXPECT_TRUE(test::contains(spp, "spp must be 1, got 4")) << spp;
    for (std::string_view name : rasterIntegratorNames())
        EXPECT_NO_THROW(requireRasterSettings(name, 1)) << name;

    // rasterizeImage checks all of it before it touches the film.
    const TestScene quad = sceneFromText(R"({ "film": { "width": 8, "height": 8 },
      "shapes": [ { "type": "mesh", "positions": [[-9,-9,0],[9,-9,0],[0,9,0]], "indices": [0,1,2] } ] })");
    Film film(8, 8, PixelRect{0, 0, 8, 8}, {});
    RenderOptions options;
    EXPECT_THROW(rasterizeImage(quad.world, quad.camera, *makeIntegrator("direct", quad.world),
                                film, options),
                 Error);
    options.spp = 2;
    EXPECT_THROW(rasterizeImage(quad.world, quad.camera, *makeIntegrator("eyelight", quad.world),
                                film, options),
                 Error);
    options.spp = 1;
    Film implicitFilm(implicit.desc.film.width, implicit.desc.film.height, implicit.fullImage(),
                      {});
    EXPECT_THROW(rasterizeImage(implicit.world, implicit.camera,
                                *makeIntegrator("eyelight", implicit.world), implicitFilm, options),
                 Error);
    for (float value : film.resolveBeauty()) ASSERT_EQ(value, 0.0f);
    // And with everything right it draws the triangle that fills the view.
    const RasterStats stats = rasterizeImage(
        quad.world, quad.camera, *makeIntegrator("eyelight", quad.world), film, options);
    EXPECT_EQ(stats.coveredPixels, 64u);
    for (float value : film.resolveBeauty()) EXPECT_GT(value, 0.8f);  // |cos| of the view rays
}

}  // namespace
}  // namespace strahl
