// Catmull-Clark refinement (geometry/catmull_clark.h) and the surface built
// on it (subdivision_surface.h) against closed forms: the limit of a cube's
// face centre, the bicubic B-spline patch of a regular region, the cubic
// B-spline of a boundary, bilinear patches when everything is pinned; uvs,
// normals and every refused cage.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "strahl/core/error.h"
#include "strahl/geometry/subdivision_surface.h"
#include "test_scene_pieces.h"

namespace strahl {
namespace {

// An n × n grid of quads over [0, n]², vertex (i, j) at index j (n + 1) + i,
// with heights z(i, j).
SubdivisionCage gridCage(int n, const std::function<double(int, int)>& z) {
    SubdivisionCage c;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) c.positions.emplace_back(double(i), double(j), z(i, j));
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = uint32_t(j * (n + 1) + i);
            c.faceSizes.push_back(4);
            c.indices.insert(c.indices.end(), {a, a + 1, a + uint32_t(n) + 2, a + uint32_t(n) + 1});
        }
    return c;
}

SubdivisionSurface surfaceOf(SubdivisionCage cage, int levels) {
    SubdivisionDesc desc;
    desc.name = "test";
    desc.cage = std::move(cage);
    desc.levels = levels;
    return SubdivisionSurface(std::move(desc));
}

// The uniform cubic B-spline basis.
double bspline(int k, double t) {
    const double s = 1.0 - t;
    switch (k) {
        case 0: return s * s * s / 6.0;
        case 1: return (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0;
        case 2: return (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0;
        default: return t * t * t / 6.0;
    }
}

TEST(CatmullClark, CubeFaceCentreReachesItsLimit) {
    // After one level the top face's centre F = (0, 0, 1) is a regular
    // vertex; its edge neighbours are edge points such as (3/4, 0, 3/4), its
    // diagonal ones the cube's corners moved to (5/9, 5/9, 5/9). The limit
    // rule (16 F + 4 Σ e + Σ d) / 36 gives z = (16 + 12 + 20/9) / 36 = 68/81.
    for (int levels : {1, 3, 6}) {
        const SubdivisionSurface s = surfaceOf(test::cubeCage(), levels);
        const DVec3 p = s.pointAt(1, 0.5f, 0.5f);
        EXPECT_NEAR(p.z, 68.0 / 81.0, 1e-12) << levels;
        EXPECT_NEAR(p.x, 0.0, 1e-12);
        EXPECT_NEAR(p.y, 0.0, 1e-12);
    }
}

TEST(CatmullClark, RegularRegionIsTheBicubicBSplinePatch) {
    // Away from the boundary every vertex has valence 4: the limit surface
    // of face (2, 2) of a 6 × 6 grid is the B-spline patch of the 4 × 4
    // control points around it, at every refined point.
    const auto z = [](int i, int j) { return std::sin(1.3 * i) + 0.4 * std::cos(0.7 * j * i) + 0.1 * j; };
    const int n = 6;
    const SubdivisionSurface s = surfaceOf(gridCage(n, z), 4);
    const uint32_t face = 2 * n + 2;
    for (int a = 0; a <= 16; a += 3)
        for (int b = 0; b <= 16; b += 5) {
            const double u = a / 16.0, v = b / 16.0;
            double expected = 0.0;
            for (int k = 0; k < 4; ++k)
                for (int l = 0; l < 4; ++l) expected += bspline(k, u) * bspline(l, v) * z(1 + k, 1 + l);
            const DVec3 p = s.pointAt(face, float(u), float(v));
            EXPECT_NEAR(p.z, expected, 1e-12) << u << ", " << v;
            EXPECT_NEAR(p.x, 2.0 + u, 1e-12);
            EXPECT_NEAR(p.y, 2.0 + v, 1e-12);
        }
}

TEST(CatmullClark, SmoothBoundaryIsTheCubicBSplineOfItsPolygon) {
    // The boundary edge from vertex (2, 0) to (3, 0) of a grid: its midpoint
    // tends to (P1 + 23 P2 + 23 P3 + P4) / 48 of the boundary polygon.
    const auto z = [](int i, int j) { return j == 0 ? std::cos(double(i)) : 0.3 * i * j; };
    const SubdivisionSurface s = surfaceOf(gridCage(5, z), 3);
    const DVec3 p = s.pointAt(2, 0.5f, 0.0f);  // face (2, 0), on its bottom edge
    EXPECT_NEAR(p.z, (z(1, 0) + 23.0 * z(2, 0) + 23.0 * z(3, 0) + z(4, 0)) / 48.0, 1e-12);
    EXPECT_NEAR(p.y, 0.0, 1e-12);
    // Pinned boundary: the polygon itself.
    SubdivisionCage pinned = gridCage(5, z);
    pinned.boundary = SubdivisionBoundary::PinBoundary;
    EXPECT_NEAR(surfaceOf(pinned, 3).pointAt(2, 0.5f, 0.0f).z, 0.5 * (z(2, 0) + z(3, 0)), 1e-12);
}

TEST(CatmullClark, InfinitelySharpCreaseIsACubicBSplineCurve) {
    // A crease along the grid's middle row j = 2 (vertices 0 … 5): the
    // surface there is the crease polygon's B-spline, like a boundary.
    const auto z = [](int i, int j) { return j == 2 ? 0.5 * std::sin(double(i)) : 0.2 * (i + j); };
    SubdivisionCage creased = gridCage(5, z);
    for (uint32_t i = 0; i < 5; ++i) {
        creased.creaseEdges.insert(creased.creaseEdges.end(), {12 + i, 13 + i});
        creased.creaseWeights.push_back(INFINITY);
    }
    const SubdivisionSurface s = surfaceOf(creased, 3);
    const DVec3 p = s.pointAt(2 * 5 + 2, 0.5f, 0.0f);  // face (2, 2), on its edge along j = 2
    EXPECT_NEAR(p.z, (z(1, 2) + 23.0 * z(2, 2) + 23.0 * z(3, 2) + z(4, 2)) / 48.0, 1e-12);
}

TEST(CatmullClark, PinAllGivesBilinearPatches) {
    SubdivisionCage quad;
    quad.positions = {{0, 0, 0}, {2, 0, 1}, {2, 1, -1}, {0, 1, 0.5}};
    quad.faceSizes = {4};
    quad.indices = {0, 1, 2, 3};
    quad.boundary = SubdivisionBoundary::PinAll;
    const SubdivisionSurface s = surfaceOf(quad, 3);
    const double u = 0.25, v = 0.625;
    const DVec3 expected = (1 - u) * (1 - v) * quad.positions[0] + u * (1 - v) * quad.positions[1] +
                           u * v * quad.positions[2] + (1 - u) * v * quad.positions[3];
    const DVec3 p = s.pointAt(0, float(u), float(v));
    EXPECT_NEAR(glm::length(p - expected), 0.0, 1e-12);
}

TEST(CatmullClark, UvsAreSubdividedLikePositions) {
    // Affine data stays affine: uv = (x, y) on a flat grid, everywhere.
    SubdivisionCage grid = gridCage(4, [](int, int) { return 0.0; });
    for (const DVec3& p : grid.positions) grid.uvs.emplace_back(p.x, p.y);
    const RefinedSurface r = refineCatmullClark(grid, 3, "grid");
    ASSERT_EQ(r.uvs.size(), r.positions.size());
    for (size_t i = 0; i < r.positions.size(); ++i) {
        EXPECT_NEAR(r.uvs[i].x, r.positions[i].x, 1e-12);
        EXPECT_NEAR(r.uvs[i].y, r.positions[i].y, 1e-12);
    }
}

TEST(CatmullClark, NormalsKinkOnlyAtCreases) {
    // A smooth closed surface: one normal group per refined vertex. A crease
    // loop splits its vertices' corners into two groups each.
    const RefinedSurface smooth = refineCatmullClark(test::cubeCage(), 2, "cube");
    EXPECT_EQ(smooth.groupCount, smooth.positions.size());
    SubdivisionCage creased = test::cubeCage();
    creased.creaseEdges = {0, 2, 2, 3, 3, 1, 1, 0};
    creased.creaseWeights = {INFINITY, INFINITY, INFINITY, INFINITY};
    const RefinedSurface kinked = refineCatmullClark(creased, 2, "cube");
    EXPECT_EQ(kinked.groupCount, kinked.positions.size() + 4 * 4);  // 4 edges × 4 segments, each end shared
    const auto normals = cornerNormals(smooth, smooth.positions);
    for (const auto& corners : normals)
        for (const DVec3& n : corners) EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
}

TEST(CatmullClark, DisplacementMovesAlongTheNormal) {
    SubdivisionDesc desc;
    desc.name = "cube";
    desc.cage = test::cubeCage();
    desc.levels = 3;
    desc.displacement = [](const DVec3&, const DVec3&, const DVec2&) { return 0.25; };
    desc.displacementText = "0.25";
    const SubdivisionSurface s(std::move(desc));
    ASSERT_TRUE(s.displaced());
    // The face centre's normal is +z by symmetry.
    EXPECT_NEAR(s.pointAt(1, 0.5f, 0.5f).z, 68.0 / 81.0 + 0.25, 1e-12);
    EXPECT_NEAR(s.displacementAt(1, 0.5f, 0.5f).z, 0.25, 1e-12);
    SubdivisionDesc bad;
    bad.name = "cube";
    bad.cage = test::cubeCage();
    bad.displacement = [](const DVec3&, const DVec3&, const DVec2&) { return std::nan(""); };
    EXPECT_THROW(SubdivisionSurface{std::move(bad)}, Error);
}

void expectRefused(const SubdivisionCage& cage, const std::string& fragment, int levels = 2) {
    try {
        refineCatmullClark(cage, levels, "cage");
        ADD_FAILURE() << "accepted; expected an error containing: " << fragment;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
}

TEST(CatmullClark, RefusesBadCages) {
    SubdivisionCage c = test::cubeCage();
    c.faceSizes[0] = 2;
    c.faceSizes[1] = 6;
    expectRefused(c, "face 0 has 2 vertices (3 to 15)");
    c = test::cubeCage();
    c.indices[5] = 99;
    expectRefused(c, "face 1 uses vertex 99, but there are 8");
    c = test::cubeCage();
    c.indices[1] = c.indices[0];
    expectRefused(c, "face 0 uses vertex 0 twice");
    c = test::cubeCage();
    std::swap(c.indices[0], c.indices[1]);  // face 0 wound the other way
    expectRefused(c, "used twice in the same direction");
    c = test::cubeCage();
    c.faceSizes.push_back(4);  // a copy of face 0, reversed: a third face on its edges
    c.indices.insert(c.indices.end(), {1, 3, 2, 0});
    expectRefused(c, "shared by more than two faces");
    c = test::cubeCage();
    c.creaseEdges = {0, 7};
    c.creaseWeights = {1.0f};
    expectRefused(c, "crease 0 (0-7) is not an edge of the mesh");
    c.creaseEdges = {0, 1};
    c.creaseWeights = {std::nanf("")};
    expectRefused(c, "crease 0 has weight nan");
    c = test::cubeCage();
    c.holes = {6};
    expectRefused(c, "hole 6 is not a face (6 faces)");
    c.holes = {0, 1, 2, 3, 4, 5};
    expectRefused(c, "every face is a hole");
    c = test::cubeCage();
    c.cornerVertices = {8};
    c.cornerWeights = {1.0f};
    expectRefused(c, "corner 0 names vertex 8, but there are 8");
    c = test::cubeCage();
    c.uvs = {{0, 0}};
    expectRefused(c, "1 uvs for 8 positions");
    c = test::cubeCage();
    c.positions[3].y = INFINITY;
    expectRefused(c, "position 3 is not finite");
    expectRefused(test::cubeCage(), "0 subdivision levels (1 to 8)", 0);
    expectRefused(test::cubeCage(), "9 subdivision levels (1 to 8)", 9);
}

TEST(CatmullClark, BoundaryModeNames) {
    for (SubdivisionBoundary m : {SubdivisionBoundary::Smooth, SubdivisionBoundary::PinCorners,
                                  SubdivisionBoundary::PinBoundary, SubdivisionBoundary::PinAll})
        EXPECT_EQ(subdivisionBoundaryFromName(subdivisionBoundaryName(m)), m);
    EXPECT_THROW(subdivisionBoundaryFromName("none"), Error);
}

}  // namespace
}  // namespace strahl
