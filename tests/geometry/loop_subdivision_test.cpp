// Loop subdivision (geometry/loop_subdivision.h): the counts, that a vertex's
// limit position does not depend on the level it is computed at (the limit
// surface is one surface), flat meshes staying flat, symmetry, outward
// normals, and the errors.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "strahl/geometry/loop_subdivision.h"
#include "test_support.h"

namespace strahl {
namespace {

// The regular octahedron, wound counter-clockwise seen from outside.
TriangleMesh octahedron() {
    TriangleMesh m;
    m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    m.indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    return m;
}

TEST(LoopSubdivision, EachLevelSplitsEveryTriangleIntoFour) {
    const TriangleMesh control = octahedron();
    size_t vertices = 6, edges = 12, triangles = 8;
    for (int level = 0; level <= 4; ++level) {
        const TriangleMesh m = loopSubdivide(control, level, "octahedron");
        EXPECT_EQ(m.triangleCount(), triangles);
        EXPECT_EQ(m.vertexCount(), vertices);
        EXPECT_EQ(m.normals.size(), vertices);
        EXPECT_TRUE(m.isPadded());
        // Euler: each level adds a vertex per edge; edges double and gain three per triangle.
        vertices += edges;
        edges = 2 * edges + 3 * triangles;
        triangles *= 4;
    }
}

TEST(LoopSubdivision, LimitPositionsDoNotDependOnTheLevel) {
    // The vertices of level 2 keep their indices in level 4, and both are
    // moved to the same limit surface.
    const TriangleMesh coarse = loopSubdivide(octahedron(), 2, "octahedron");
    const TriangleMesh fine = loopSubdivide(octahedron(), 4, "octahedron");
    for (size_t v = 0; v < coarse.vertexCount(); ++v)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(coarse.positions[v][c], fine.positions[v][c], 1e-6f) << v;
    // The octahedron's vertices have valence 4: beta = 3/32, gamma =
    // 1 / (4 + 3 / (8 beta)) = 1/8, and their four neighbours sum to 0, so
    // their limit is (1 - 4/8) v: half-way to the centre, at every level.
    for (size_t v = 0; v < 6; ++v) EXPECT_NEAR(glm::length(fine.positions[v]), 0.5f, 1e-6f);
}

TEST(LoopSubdivision, NormalsPointOutOfAClosedSurfaceWoundOutwards) {
    const TriangleMesh m = loopSubdivide(octahedron(), 3, "octahedron");
    for (size_t v = 0; v < m.vertexCount(); ++v) {
        EXPECT_GT(glm::dot(m.normals[v], glm::normalize(m.positions[v])), 0.9f) << v;
        EXPECT_NEAR(glm::length(m.normals[v]), 1.0f, 1e-5f);
    }
}

TEST(LoopSubdivision, AFlatMeshWithABoundaryStaysFlatAndInsideItsOutline) {
    TriangleMesh square;
    square.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 0}};
    square.indices = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
    const TriangleMesh m = loopSubdivide(square, 3, "square");
    for (const Vec3& p : m.positions) {
        EXPECT_EQ(p.z, 0.0f);
        EXPECT_GE(p.x, 0.0f);
        EXPECT_LE(p.x, 1.0f);
        EXPECT_GE(p.y, 0.0f);
        EXPECT_LE(p.y, 1.0f);
    }
    // Boundary vertices follow the boundary alone: moving the interior vertex
    // moves the corners' limits not at all (they keep indices 0 ... 3), the
    // centre's (index 4) somewhat.
    TriangleMesh moved = square;
    moved.positions[4] = Vec3(0.3f, 0.6f, 0.0f);
    const TriangleMesh other = loopSubdivide(moved, 3, "square");
    for (size_t v = 0; v < 4; ++v) EXPECT_EQ(other.positions[v], m.positions[v]) << v;
    EXPECT_NE(other.positions[4], m.positions[4]);
    for (const Vec3& n : m.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST(LoopSubdivision, NonManifoldEdgesDegenerateTrianglesAndTooManyLevelsAreErrors) {
    TriangleMesh fan;
    fan.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    fan.indices = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    EXPECT_THAT(test::errorMessage([&] { loopSubdivide(fan, 1, "fan.pbrt:3"); }),
                testing::HasSubstr("fan.pbrt:3: the edge between vertices 0 and 1 belongs to more than two "
                                   "triangles: Loop subdivision needs a manifold surface"));
    TriangleMesh degenerate;
    degenerate.positions = {{0, 0, 0}, {1, 0, 0}};
    degenerate.indices = {0, 1, 1};
    EXPECT_THAT(test::errorMessage([&] { loopSubdivide(degenerate, 1, "d"); }),
                testing::HasSubstr("d: triangle 0 repeats vertex 1 (degenerate)"));
    EXPECT_THAT(test::errorMessage([&] { loopSubdivide(octahedron(), 9, "o"); }),
                testing::HasSubstr("o: 9 subdivision levels (0 ... 8)"));
}

}  // namespace
}  // namespace strahl
