#include "strahl/geometry/triangle_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "strahl/core/error.h"

namespace strahl {
namespace {

TriangleMesh oneTriangle() {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
    m.indices = {0, 1, 2};
    return m;
}

TEST(TriangleMesh, InteractionRebuildsThePointFromBarycentrics) {
    TriangleMesh m = oneTriangle();
    m.uvs = {{0, 0}, {1, 0}, {0, 1}};
    const SurfaceInteraction si = triangleInteraction(m, 0, 0.25f, 0.5f);
    EXPECT_FLOAT_EQ(si.p.x, 0.5f);
    EXPECT_FLOAT_EQ(si.p.y, 1.0f);
    EXPECT_EQ(si.p.z, 0.0f);
    EXPECT_EQ(si.Ng, Vec3(0, 0, 1));
    EXPECT_EQ(si.Ns, si.Ng);
    EXPECT_FLOAT_EQ(si.uv.x, 0.25f);
    EXPECT_FLOAT_EQ(si.uv.y, 0.5f);
    EXPECT_GT(si.pError.x, 0.0f);
    EXPECT_LT(si.pError.x, 1e-5f);
}

TEST(TriangleMesh, ShadingNormalsAreInterpolatedAndGeometricNormalFollowsThem) {
    TriangleMesh m = oneTriangle();
    m.normals = {{0, 0, -1}, {0, 0, -1}, {0, 0, -1}};  // authored facing the other way
    const SurfaceInteraction si = triangleInteraction(m, 0, 0.2f, 0.2f);
    EXPECT_EQ(si.Ns, Vec3(0, 0, -1));
    EXPECT_EQ(si.Ng, Vec3(0, 0, -1));
}

TEST(TriangleMesh, TransformMovesPointsAndKeepsNormalsUnitAndPerpendicular) {
    TriangleMesh m = oneTriangle();
    m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    Mat4 t(1.0f);
    t[0][0] = 3.0f;             // non-uniform scale in x
    t[3] = Vec4(1, 2, 3, 1);    // translation
    m.transform(t);
    EXPECT_EQ(m.positions[1], Vec3(7, 2, 3));
    EXPECT_FLOAT_EQ(glm::length(m.normals[0]), 1.0f);
}

TEST(TriangleMesh, MirroringTransformKeepsFrontFaces) {
    TriangleMesh m = oneTriangle();
    Mat4 mirror(1.0f);
    mirror[0][0] = -1.0f;
    m.transform(mirror);
    const SurfaceInteraction si = triangleInteraction(m, 0, 0.2f, 0.2f);
    EXPECT_EQ(si.Ng, Vec3(0, 0, 1));  // still facing +z
}

TEST(TriangleMesh, ValidateNamesTheProblem) {
    TriangleMesh bad = oneTriangle();
    bad.indices[2] = 3;
    try {
        bad.validate("mesh.ply");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("mesh.ply: triangle 0 refers to vertex 3"),
                  std::string::npos)
            << e.what();
    }
    TriangleMesh nan = oneTriangle();
    nan.positions[1].y = std::nanf("");
    EXPECT_THROW(nan.validate("x"), Error);
    TriangleMesh inf = oneTriangle();
    inf.positions[0].x = kInfinity;
    EXPECT_THROW(inf.validate("x"), Error);
    TriangleMesh normals = oneTriangle();
    normals.normals = {{0, 0, 1}};
    EXPECT_THROW(normals.validate("x"), Error);
    EXPECT_NO_THROW(oneTriangle().validate("x"));
}

// A cube's corner is shared by three faces, each meeting it at a right angle
// however the face is split into triangles: its normal is the diagonal.
TEST(TriangleMesh, VertexNormalsAreAngleWeightedMeansOfTheFaceNormals) {
    TriangleMesh cube;
    for (int i = 0; i < 8; ++i)
        cube.positions.push_back(Vec3(float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)));
    // Six faces, outward and counter-clockwise; the -z face split in three
    // triangles (a fan through a mid-edge vertex) to show the weighting.
    cube.positions.push_back(Vec3(0.5f, 0.0f, 0.0f));  // 8: on the -z face's edge 0-1
    cube.indices = {0, 2, 8,  8, 2, 3,  8, 3, 1,   4, 5, 7, 4, 7, 6,   0, 1, 5, 0, 5, 4,
                    2, 6, 7, 2, 7, 3,  0, 4, 6, 0, 6, 2,   1, 3, 7, 1, 7, 5};
    cube.validate("cube");
    cube.computeVertexNormals();
    ASSERT_EQ(cube.normals.size(), cube.positions.size());
    for (int i = 0; i < 8; ++i) {
        const Vec3 expected = glm::normalize(2.0f * cube.positions[size_t(i)] - Vec3(1.0f));
        EXPECT_NEAR(glm::dot(cube.normals[size_t(i)], expected), 1.0f, 1e-6f) << "corner " << i;
    }
    // The mid-edge vertex belongs to the -z face's triangles only.
    EXPECT_NEAR(glm::dot(cube.normals[8], Vec3(0, 0, -1)), 1.0f, 1e-6f);
    // Degenerate triangles give no direction: an isolated vertex gets +z.
    TriangleMesh sliver;
    sliver.positions = {Vec3(0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
    sliver.indices = {0, 1, 2};
    sliver.computeVertexNormals();
    EXPECT_EQ(sliver.normals[1], Vec3(0, 0, 1));
}

TEST(TriangleMesh, BoundsAndPadding) {
    TriangleMesh m = oneTriangle();
    EXPECT_EQ(m.bounds().max, Vec3(2, 2, 0));
    m.reservePadding();
    EXPECT_TRUE(m.isPadded());
}

}  // namespace

TEST(TriangleMesh, FlipOrientationTurnsTheWindingAndTheNormals) {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.normals = {{0, 0, 1}, {0, 0, 1}, {0.6f, 0, 0.8f}};
    m.indices = {0, 1, 2};
    m.flipOrientation();
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 2, 1}));
    EXPECT_EQ(m.normals[2], Vec3(-0.6f, 0, -0.8f));
    // The geometric normal follows the winding: now -z.
    EXPECT_LT(triangleInteraction(m, 0, 0.25f, 0.25f).Ng.z, 0.0f);
}

namespace {

// One triangle that grows from unit size at time 0 to 3 at time 1, through 2
// at time 1/2 (three keyframes).
TriangleMesh growingTriangle() {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2};
    m.laterPositions = {{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}, {{0, 0, 0}, {3, 0, 0}, {0, 3, 0}}};
    return m;
}

TEST(TriangleMesh, DeformingMeshesInterpolateTheirKeyframes) {
    TriangleMesh m = growingTriangle();
    ASSERT_TRUE(m.deforms());
    EXPECT_EQ(m.keyframeCount(), 3u);
    EXPECT_EQ(m.positionAt(1, 0.0f), Vec3(1, 0, 0));
    EXPECT_EQ(m.positionAt(1, 0.25f), Vec3(1.5f, 0, 0));
    EXPECT_EQ(m.positionAt(1, 0.75f), Vec3(2.5f, 0, 0));
    EXPECT_EQ(m.positionAt(1, 2.0f), Vec3(3, 0, 0));  // clamped to the frame
    EXPECT_EQ(m.bounds().max, Vec3(3, 3, 0));
    // The interaction at a time is on the triangle there.
    EXPECT_NEAR(triangleInteraction(m, 0, 0.5f, 0.0f, 0.75f).p.x, 1.25f, 1e-6f);
    m.computeVertexNormals();
    ASSERT_EQ(m.laterNormals.size(), 2u);
    EXPECT_EQ(m.laterNormals[1][2], Vec3(0, 0, 1));
    m.flipOrientation();
    EXPECT_EQ(m.laterNormals[0][0], Vec3(0, 0, -1));
    m.transform(glm::translate(Mat4(1.0f), Vec3(0, 0, 5)));
    EXPECT_EQ(m.laterPositions[1][1], Vec3(3, 0, 5));
    m.reservePadding();
    EXPECT_TRUE(m.isPadded());
}

TEST(TriangleMesh, DeformingMeshesAreValidated) {
    TriangleMesh m = growingTriangle();
    m.laterPositions[1].pop_back();
    EXPECT_THROW(m.validate("tri"), Error);
    m = growingTriangle();
    m.laterPositions[0][2].y = NAN;
    try {
        m.validate("tri");
        ADD_FAILURE() << "accepted a NaN keyframe";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("tri: vertex 2 has a non-finite coordinate at keyframe 1"), std::string::npos)
            << e.what();
    }
    m = growingTriangle();
    m.laterNormals = {{{0, 0, 1}, {0, 0, 1}, {0, 0, 1}}};  // one list for two later keyframes
    EXPECT_THROW(m.validate("tri"), Error);
}

}  // namespace

}  // namespace strahl
