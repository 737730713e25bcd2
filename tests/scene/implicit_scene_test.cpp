// Implicit shapes in scene files (docs/scene-format.md, "Implicit shapes"):
// every surface type and shape key parsed into the function it documents, and
// the exact message — naming the JSON pointer — of every class of bad input,
// including the errors only buildWorld() can find.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "scene_test_helpers.h"
#include "strahl/core/error.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

using test::contains;
using test::kTriangleShape;
using test::parseJson;
using test::sceneWith;

// An implicit shape with `surface` (a JSON object) and extra shape members.
std::string implicitShape(const std::string& surface, const std::string& extra = "") {
    return R"({"type": "implicit", "surface": )" + surface + (extra.empty() ? "" : ", " + extra) +
           "}";
}

const std::string kBox = R"("box": [[-2, -2, -2], [2, 2, 2]])";

// The one implicit shape of a scene made of `surface` and `extra`.
ShapeDesc parseShape(const std::string& surface, const std::string& extra = "") {
    const SceneDesc desc = parseJson(sceneWith(implicitShape(surface, extra)));
    EXPECT_EQ(desc.shapes.size(), 1u);
    return desc.shapes.at(0);
}

std::string implicitError(const std::string& surface, const std::string& extra = "") {
    return test::errorMessage([&] { parseJson(sceneWith(implicitShape(surface, extra))); });
}

double f(const ShapeDesc& shape, double x, double y, double z) {
    return shape.implicitSurface->value(DVec3(x, y, z));
}

constexpr double kPiD = 3.14159265358979323846;

// Bounds are rounded outwards: they must contain [lo, hi] on `axis` and exceed
// it by no more than a few float ulps of the extent.
void expectBoundsOnAxis(const Bounds3& b, int axis, float lo, float hi) {
    const float slack = 1e-5f * std::max(1.0f, hi - lo);
    EXPECT_LE(b.min[axis], lo);
    EXPECT_GE(b.min[axis], lo - slack);
    EXPECT_GE(b.max[axis], hi);
    EXPECT_LE(b.max[axis], hi + slack);
}

// --- surfaces ----------------------------------------------------------------

TEST(ImplicitScene, SphereWithEveryDefault) {
    const ShapeDesc s = parseShape(R"({"type": "sphere"})");
    EXPECT_EQ(s.kind, ShapeKind::Implicit);
    EXPECT_EQ(s.where, "/shapes/0");
    EXPECT_EQ(s.name, "/shapes/0");  // defaults to the pointer
    EXPECT_EQ(s.material, "default");
    EXPECT_EQ(s.transform, Mat4(1.0f));
    EXPECT_TRUE(s.file.empty());
    EXPECT_TRUE(s.inlineMesh.positions.empty());
    ASSERT_NE(s.implicitSurface, nullptr);
    EXPECT_FALSE(s.implicitOptions.box.has_value());
    EXPECT_EQ(s.implicitOptions.cellsPerAxis, 0);  // automatic
    EXPECT_EQ(s.implicitOptions.relativeTolerance, 1e-6);
    // radius 1: f = |x|² − 1
    EXPECT_DOUBLE_EQ(f(s, 0, 0, 0), -1.0);
    EXPECT_DOUBLE_EQ(f(s, 1, 0, 0), 0.0);
    EXPECT_DOUBLE_EQ(f(s, 0, 0, 2), 3.0);
    const auto bounds = s.implicitSurface->bounds();
    ASSERT_TRUE(bounds.has_value());
    EXPECT_EQ(bounds->min, Vec3(-1.0f));
    EXPECT_EQ(bounds->max, Vec3(1.0f));
}

TEST(ImplicitScene, SphereRadius) {
    const ShapeDesc s = parseShape(R"({"type": "sphere", "radius": 2.5})");
    EXPECT_DOUBLE_EQ(f(s, 0, 2.5, 0), 0.0);
    EXPECT_DOUBLE_EQ(f(s, 0, 0, 0), -6.25);
    EXPECT_EQ(s.implicitSurface->bounds()->max, Vec3(2.5f));
    EXPECT_EQ(s.implicitSurface->describe(), "sphere r=2.5");
}

TEST(ImplicitScene, QuadricWithEveryCoefficient) {
    const ShapeDesc s = parseShape(
        R"({"type": "quadric", "coefficients": {"xx": 1, "yy": 2, "zz": 3, "xy": 4, "yz": 5,
            "xz": 6, "x": 7, "y": 8, "z": 9, "c": 10}})",
        kBox);
    const double x = 0.5, y = -1.0, z = 2.0;
    const double expected = 1 * x * x + 2 * y * y + 3 * z * z + 4 * x * y + 5 * y * z + 6 * x * z +
                            7 * x + 8 * y + 9 * z + 10;
    EXPECT_DOUBLE_EQ(f(s, x, y, z), expected);
    EXPECT_FALSE(s.implicitSurface->bounds().has_value());  // needs the box
    ASSERT_TRUE(s.implicitOptions.box.has_value());
    EXPECT_EQ(s.implicitOptions.box->min, Vec3(-2.0f));
    EXPECT_EQ(s.implicitOptions.box->max, Vec3(2.0f));
}

TEST(ImplicitScene, QuadricCoefficientsDefaultToZero) {
    // A cone x² + y² − z² (the apex test of the render tests uses it too).
    const ShapeDesc s =
        parseShape(R"({"type": "quadric", "coefficients": {"xx": 1, "yy": 1, "zz": -1}})", kBox);
    EXPECT_DOUBLE_EQ(f(s, 0, 0, 0), 0.0);
    EXPECT_DOUBLE_EQ(f(s, 1, 0, 1), 0.0);
    EXPECT_DOUBLE_EQ(f(s, 1, 1, 0), 2.0);
    EXPECT_DOUBLE_EQ(f(s, 0, 0, 3), -9.0);
}

TEST(ImplicitScene, TorusRadiiAndDefaults) {
    const ShapeDesc s =
        parseShape(R"({"type": "torus", "major_radius": 2, "minor_radius": 0.5})");
    EXPECT_NEAR(f(s, 2.5, 0, 0), 0.0, 1e-12);
    EXPECT_NEAR(f(s, 0, -1.5, 0), 0.0, 1e-12);
    EXPECT_NEAR(f(s, 2, 0, 0.5), 0.0, 1e-12);  // axis z: the top of the tube
    EXPECT_LT(f(s, 2, 0, 0), 0.0);             // inside the tube
    EXPECT_GT(f(s, 0, 0, 0), 0.0);             // the hole
    const auto b = s.implicitSurface->bounds();
    ASSERT_TRUE(b.has_value());
    EXPECT_EQ(b->min, Vec3(-2.5f, -2.5f, -0.5f));
    EXPECT_EQ(b->max, Vec3(2.5f, 2.5f, 0.5f));
    EXPECT_EQ(s.implicitSurface->describe(), "torus R=2 r=0.5");

    const ShapeDesc d = parseShape(R"({"type": "torus"})");  // R = 1, r = 0.25
    EXPECT_NEAR(f(d, 1.25, 0, 0), 0.0, 1e-12);
    EXPECT_NEAR(f(d, 0.75, 0, 0), 0.0, 1e-12);
    EXPECT_EQ(d.implicitSurface->describe(), "torus R=1 r=0.25");
}

TEST(ImplicitScene, Superellipsoid) {
    // e1 = e2 = 1 is the ellipsoid with the given radii.
    const ShapeDesc s = parseShape(R"({"type": "superellipsoid", "radii": [1, 2, 3]})");
    EXPECT_NEAR(f(s, 1, 0, 0), 0.0, 1e-12);
    EXPECT_NEAR(f(s, 0, 2, 0), 0.0, 1e-12);
    EXPECT_NEAR(f(s, 0, 0, 3), 0.0, 1e-12);
    EXPECT_NEAR(f(s, 0, 0, 0), -1.0, 1e-12);
    EXPECT_EQ(s.implicitSurface->bounds()->max, Vec3(1, 2, 3));

    // Barr's formula with e1 = 0.5, e2 = 2: 2/e2 = 1, e2/e1 = 4, 2/e1 = 4.
    const ShapeDesc b = parseShape(R"({"type": "superellipsoid", "e1": 0.5, "e2": 2})");
    const double x = 0.3, y = -0.2, z = 0.6;
    const double expected = std::pow(std::abs(x) + std::abs(y), 4.0) + std::pow(z, 4.0) - 1.0;
    EXPECT_NEAR(f(b, x, y, z), expected, 1e-12);
    EXPECT_EQ(b.implicitSurface->bounds()->max, Vec3(1.0f));  // radii default to 1
    EXPECT_EQ(b.implicitSurface->describe(), "superellipsoid e1=0.5 e2=2");
}

TEST(ImplicitScene, BlobsWithEveryKeyAndDefaults) {
    const ShapeDesc s = parseShape(
        R"({"type": "blobs", "threshold": 0.25, "blobs": [
              {"center": [1, 0, 0], "radius": 2, "strength": 0.5},
              {}]})");
    // The first blob's centre: field 0.5·1 from itself, and the default blob
    // (centre 0, radius 1, strength 1) does not reach it.
    EXPECT_DOUBLE_EQ(f(s, 1, 0, 0), 0.25 - 0.5);
    // Far from both: f = threshold.
    EXPECT_DOUBLE_EQ(f(s, 0, 5, 0), 0.25);
    // At (−0.5, 0, 0): q1 = 1.5²/4, q0 = 0.25.
    const double expected =
        0.25 - 0.5 * std::pow(1.0 - 2.25 / 4.0, 3) - 1.0 * std::pow(1.0 - 0.25, 3);
    EXPECT_NEAR(f(s, -0.5, 0, 0), expected, 1e-12);
    const auto b = s.implicitSurface->bounds();
    ASSERT_TRUE(b.has_value());
    EXPECT_EQ(b->min, Vec3(-1.0f, -2.0f, -2.0f));
    EXPECT_EQ(b->max, Vec3(3.0f, 2.0f, 2.0f));
    EXPECT_EQ(s.implicitSurface->describe(), "blobs n=2 threshold=0.25");

    const ShapeDesc d = parseShape(R"({"type": "blobs", "blobs": [{}]})");  // threshold 0.5
    // (1 − r²)³ = 0.5 on the surface.
    const double r = std::sqrt(1.0 - std::cbrt(0.5));
    EXPECT_NEAR(f(d, r, 0, 0), 0.0, 1e-12);
    EXPECT_NEAR(f(d, 0, 0, 0), -0.5, 1e-12);
}

struct PeriodicCase {
    const char* type;
    double (*g)(double x, double y, double z);  // at k = 1
};

TEST(ImplicitScene, TriplyPeriodicSurfacesWithPeriodLevelAndThickness) {
    const PeriodicCase cases[] = {
        {"gyroid",
         [](double x, double y, double z) {
             return std::sin(x) * std::cos(y) + std::sin(y) * std::cos(z) + std::sin(z) * std::cos(x);
         }},
        {"schwarz_p",
         [](double x, double y, double z) { return std::cos(x) + std::cos(y) + std::cos(z); }},
        {"schwarz_d",
         [](double x, double y, double z) {
             return std::sin(x) * std::sin(y) * std::sin(z) + std::sin(x) * std::cos(y) * std::cos(z) +
                    std::cos(x) * std::sin(y) * std::cos(z) + std::cos(x) * std::cos(y) * std::sin(z);
         }},
        {"neovius",
         [](double x, double y, double z) {
             return 3.0 * (std::cos(x) + std::cos(y) + std::cos(z)) +
                    4.0 * std::cos(x) * std::cos(y) * std::cos(z);
         }},
    };
    // Scene numbers are floats: these three are exact in float.
    const double period = 2.0, level = 0.25, thickness = 0.125, k = 2.0 * kPiD / period;
    const double points[][3] = {{0.1, 0.2, 0.3}, {-0.7, 0.45, 1.3}, {0.9, -0.8, -0.05}};
    for (const PeriodicCase& c : cases) {
        SCOPED_TRACE(c.type);
        const std::string type = std::string(R"({"type": ")") + c.type + R"(")";
        const ShapeDesc levelSet = parseShape(type + R"(, "period": 2, "level": 0.25})", kBox);
        const ShapeDesc sheet =
            parseShape(type + R"(, "period": 2, "level": 0.25, "thickness": 0.125})", kBox);
        const ShapeDesc defaults = parseShape(type + "}", kBox);  // period 1, level 0, thickness 0
        EXPECT_FALSE(levelSet.implicitSurface->bounds().has_value());
        EXPECT_TRUE(contains(levelSet.implicitSurface->describe(), c.type));
        EXPECT_TRUE(contains(sheet.implicitSurface->describe(), "thickness=0.125"));
        for (const auto& p : points) {
            const double g = c.g(k * p[0], k * p[1], k * p[2]) - level;
            EXPECT_NEAR(f(levelSet, p[0], p[1], p[2]), g, 1e-12);
            EXPECT_NEAR(f(sheet, p[0], p[1], p[2]), std::abs(g) - thickness, 1e-12);
            EXPECT_NEAR(f(defaults, p[0], p[1], p[2]),
                        c.g(2 * kPiD * p[0], 2 * kPiD * p[1], 2 * kPiD * p[2]), 1e-12);
        }
    }
}

TEST(ImplicitScene, FormulaWithParameters) {
    const ShapeDesc s = parseShape(
        R"({"type": "formula", "f": "x^2 + y^2 + z^2 - r^2 + a*x", "parameters": {"r": 1.5, "a": -2}})",
        kBox);
    EXPECT_DOUBLE_EQ(f(s, 0, 1.5, 0), 0.0);
    EXPECT_DOUBLE_EQ(f(s, 1, 0, 0), 1.0 - 2.25 - 2.0);
    EXPECT_FALSE(s.implicitSurface->bounds().has_value());
    EXPECT_EQ(s.implicitSurface->describe(), "formula \"x^2 + y^2 + z^2 - r^2 + a*x\"");
    // parameters are optional
    const ShapeDesc plain = parseShape(R"({"type": "formula", "f": "x*y - z"})", kBox);
    EXPECT_DOUBLE_EQ(f(plain, 2, 3, 1), 5.0);
}

TEST(ImplicitScene, SurfaceTransformMovesTheZeroSet) {
    const ShapeDesc s = parseShape(
        R"({"type": "sphere", "radius": 0.5, "transform": [{"scale": 2}, {"translate": [0, 3, 0]}]})");
    // g(x) = f(M⁻¹x): a sphere of radius 1 around (0, 3, 0).
    EXPECT_NEAR(f(s, 0, 4, 0), 0.0, 1e-9);
    EXPECT_NEAR(f(s, 1, 3, 0), 0.0, 1e-9);
    EXPECT_LT(f(s, 0, 3, 0), 0.0);
    EXPECT_GT(f(s, 0, 0, 0), 0.0);
    const auto b = s.implicitSurface->bounds();
    ASSERT_TRUE(b.has_value());
    expectBoundsOnAxis(*b, 1, 2.0f, 4.0f);
    expectBoundsOnAxis(*b, 0, -1.0f, 1.0f);
    EXPECT_EQ(s.transform, Mat4(1.0f));  // the shape's own transform is separate
}

// Two unit spheres, the second moved by its operand transform to (1.5, 0, 0).
std::string twoSpheres(const std::string& op, const std::string& extra = "") {
    return R"({"type": ")" + op + R"(", )" + extra +
           R"("operands": [{"type": "sphere"},
               {"type": "sphere", "transform": [{"translate": [1.5, 0, 0]}]}]})";
}

TEST(ImplicitScene, CsgUnionIntersectionDifference) {
    const ShapeDesc u = parseShape(twoSpheres("union"));
    EXPECT_NEAR(f(u, 0, 0, 0), -1.0, 1e-12);
    EXPECT_NEAR(f(u, 1.5, 0, 0), -1.0, 1e-12);
    EXPECT_NEAR(f(u, 2.5, 0, 0), 0.0, 1e-12);
    EXPECT_NEAR(f(u, -1, 0, 0), 0.0, 1e-12);
    EXPECT_GT(f(u, 0.75, 1.0, 0), 0.0);
    auto b = u.implicitSurface->bounds();
    ASSERT_TRUE(b.has_value());
    expectBoundsOnAxis(*b, 0, -1.0f, 2.5f);
    expectBoundsOnAxis(*b, 1, -1.0f, 1.0f);

    const ShapeDesc i = parseShape(twoSpheres("intersection"));
    EXPECT_LT(f(i, 0.75, 0, 0), 0.0);
    EXPECT_GT(f(i, 0, 0, 0), 0.0);    // in the first only
    EXPECT_GT(f(i, 1.5, 0, 0), 0.0);  // in the second only
    EXPECT_NEAR(f(i, 0.5, 0, 0), 0.0, 1e-12);
    b = i.implicitSurface->bounds();
    ASSERT_TRUE(b.has_value());
    expectBoundsOnAxis(*b, 0, 0.5f, 1.0f);

    const ShapeDesc d = parseShape(twoSpheres("difference"));
    EXPECT_LT(f(d, -0.5, 0, 0), 0.0);  // in the first, outside the second
    EXPECT_GT(f(d, 0.75, 0, 0), 0.0);  // carved away
    EXPECT_GT(f(d, 1.5, 0, 0), 0.0);
    EXPECT_NEAR(f(d, 0.5, 0, 0), 0.0, 1e-12);
    b = d.implicitSurface->bounds();
    ASSERT_TRUE(b.has_value());
    expectBoundsOnAxis(*b, 0, -1.0f, 1.0f);  // the first operand's box

    // More than two operands.
    const ShapeDesc three = parseShape(
        R"({"type": "union", "operands": [{"type": "sphere"}, {"type": "torus"},
            {"type": "sphere", "radius": 0.5, "transform": [{"translate": [0, 0, 5]}]}]})");
    EXPECT_NEAR(f(three, 0, 0, 5.5), 0.0, 1e-12);
    EXPECT_TRUE(contains(three.implicitSurface->describe(), "union("));
}

TEST(ImplicitScene, SmoothUnionBlends) {
    const ShapeDesc s = parseShape(twoSpheres("smooth_union", R"("blend": 0.5, )"));
    const ShapeDesc u = parseShape(twoSpheres("union"));
    // smin_k(a, b) = min(a, b) − h²k/4 with h = max(k − |a − b|, 0)/k.
    const double k = 0.5;
    for (const double x : {0.75, 0.6, 1.0}) {
        const double a = x * x + 0.64 - 1.0, bb = (x - 1.5) * (x - 1.5) + 0.64 - 1.0;
        const double h = std::max(k - std::abs(a - bb), 0.0) / k;
        EXPECT_NEAR(f(s, x, 0.8, 0), std::min(a, bb) - h * h * k / 4.0, 1e-12) << x;
    }
    EXPECT_LT(f(s, 0.75, 0.8, 0), f(u, 0.75, 0.8, 0));  // the blend fills the crease
    EXPECT_DOUBLE_EQ(f(s, -0.9, 0, 0), f(u, -0.9, 0, 0));  // far from the other: unchanged
    const auto b = s.implicitSurface->bounds();
    ASSERT_TRUE(b.has_value());
    expectBoundsOnAxis(*b, 0, -1.5f, 3.0f);  // the union grown by k
    expectBoundsOnAxis(*b, 2, -1.5f, 1.5f);
}

// --- shape keys --------------------------------------------------------------

TEST(ImplicitScene, ShapeKeysBoxCellsToleranceNameMaterialTransform) {
    const SceneDesc desc = parseJson(R"({
      "materials": [{"name": "gold", "color": [0.9, 0.6, 0.2]}],
      "shapes": [
        {"type": "implicit", "name": "ring", "material": "gold",
         "surface": {"type": "torus"},
         "box": [[-1, -2, -0.1], [1.5, 2, 0.25]], "cells": 7, "tolerance": 1e-4,
         "transform": [{"translate": [0, 1, 0]}]},
        {"type": "implicit", "surface": {"type": "sphere"}, "cells": 1, "tolerance": 2e-12},
        {"type": "implicit", "surface": {"type": "sphere"}, "cells": 256, "tolerance": 0.09}
      ]})");
    ASSERT_EQ(desc.shapes.size(), 3u);
    const ShapeDesc& ring = desc.shapes[0];
    EXPECT_EQ(ring.name, "ring");
    EXPECT_EQ(ring.where, "/shapes/0");
    EXPECT_EQ(ring.material, "gold");
    ASSERT_TRUE(ring.implicitOptions.box.has_value());
    EXPECT_EQ(ring.implicitOptions.box->min, Vec3(-1.0f, -2.0f, -0.1f));
    EXPECT_EQ(ring.implicitOptions.box->max, Vec3(1.5f, 2.0f, 0.25f));
    EXPECT_EQ(ring.implicitOptions.cellsPerAxis, 7);
    EXPECT_NEAR(ring.implicitOptions.relativeTolerance, 1e-4, 1e-11);  // read as a float
    const Vec3 moved = Vec3(ring.transform * Vec4(1, 2, 3, 1));
    EXPECT_EQ(moved, Vec3(1, 3, 3));

    EXPECT_EQ(desc.shapes[1].name, "/shapes/1");
    EXPECT_EQ(desc.shapes[1].implicitOptions.cellsPerAxis, 1);
    EXPECT_NEAR(desc.shapes[1].implicitOptions.relativeTolerance, 2e-12, 1e-19);
    EXPECT_EQ(desc.shapes[2].implicitOptions.cellsPerAxis, 256);
    EXPECT_NEAR(desc.shapes[2].implicitOptions.relativeTolerance, 0.09, 1e-8);
}

// The documented end points of `tolerance`, as written: scene numbers are read
// as floats, and 1e-12f < 1e-12, 0.1f > 0.1, so the range check must allow
// for the rounding.
TEST(ImplicitScene, ToleranceEndPointsAreAccepted) {
    const SceneDesc desc = parseJson(R"({"shapes": [
        {"type": "implicit", "surface": {"type": "sphere"}, "tolerance": 1e-12},
        {"type": "implicit", "surface": {"type": "sphere"}, "tolerance": 0.1}]})");
    ASSERT_EQ(desc.shapes.size(), 2u);
    EXPECT_NEAR(desc.shapes[0].implicitOptions.relativeTolerance, 1e-12, 1e-19);
    EXPECT_NEAR(desc.shapes[1].implicitOptions.relativeTolerance, 0.1, 1e-8);
}

TEST(ImplicitScene, BuildWorldPlacesTheShapeWithItsCellsAndBox) {
    const SceneDesc desc = parseJson(R"({"shapes": [
        {"type": "implicit", "surface": {"type": "torus"}, "cells": 8,
         "box": [[0, -2, -2], [2, 2, 2]], "transform": [{"translate": [10, 0, 0]}]},
        {"type": "implicit", "surface": {"type": "sphere"}},
        {"type": "implicit", "surface": {"type": "gyroid", "thickness": 0.1}, "cells": 4,
         "box": [[-1, -1, -1], [1, 1, 1]]}]})");
    const World world = buildWorld(desc, BuildOptions{});
    ASSERT_EQ(world.shapes.size(), 3u);
    for (const SceneShape& shape : world.shapes) ASSERT_NE(shape.user, nullptr);
    const auto& torus = dynamic_cast<const ImplicitShape&>(*world.shapes[0].user);
    // The torus' own bounds [−1.25, 1.25]² × [−0.25, 0.25], clipped to the box.
    EXPECT_EQ(torus.domainMin(), DVec3(0.0, -1.25, -0.25));
    EXPECT_EQ(torus.domainMax(), DVec3(1.25, 1.25, 0.25));
    EXPECT_GT(torus.primitiveCount(), 0u);
    EXPECT_LE(torus.primitiveCount(), 8u * 8u * 8u);
    EXPECT_GE(torus.bounds().min.x, 10.0f - 1e-3f);  // placed by the transform
    EXPECT_EQ(world.shapes[1].user->primitiveCount(), 1u);  // closed form: one cell
    EXPECT_LE(world.shapes[2].user->primitiveCount(), 64u);
    EXPECT_EQ(world.userPrimitiveCount(), torus.primitiveCount() + 1u +
                                              world.shapes[2].user->primitiveCount());
}

// --- bad input: the message names the place ------------------------------------

TEST(ImplicitSceneErrors, FormulaSyntaxErrorNamesThePointerAndColumn) {
    EXPECT_EQ(implicitError(R"({"type": "formula", "f": "x^2 + * y"})", kBox),
              "scene.json: /shapes/0/surface/f: column 7: expected an operand (a number, a name "
              "or '('), found '*'");
    EXPECT_EQ(implicitError(R"({"type": "formula", "f": "x^2 + (y"})", kBox),
              "scene.json: /shapes/0/surface/f: column 9: expected ')' to close the '(' at column "
              "7, found the end of the formula");
    EXPECT_EQ(implicitError(R"({"type": "formula", "f": ""})", kBox),
              "scene.json: /shapes/0/surface/f: column 1: empty formula");
    // Inside a CSG operand, the pointer goes down to it.
    const std::string nested = implicitError(
        R"({"type": "union", "operands": [{"type": "sphere"}, {"type": "formula", "f": "x +"}]})",
        kBox);
    EXPECT_TRUE(contains(nested, "scene.json: /shapes/0/surface/operands/1/f: column ")) << nested;
}

TEST(ImplicitSceneErrors, UnknownVariableInAFormula) {
    const std::string e = implicitError(R"({"type": "formula", "f": "x^2 + w"})", kBox);
    EXPECT_EQ(e.rfind("scene.json: /shapes/0/surface/f: column 7: unknown name 'w'", 0), 0u) << e;
    // A parameter is known, and misspelling it names it.
    const std::string p =
        implicitError(R"({"type": "formula", "f": "x - rr", "parameters": {"r": 1}})", kBox);
    EXPECT_TRUE(contains(p, "/shapes/0/surface/f: column 5: unknown name 'rr'")) << p;
}

TEST(ImplicitSceneErrors, FormulaParameters) {
    EXPECT_EQ(implicitError(R"({"type": "formula", "f": "x + r", "parameters": {"r": "a"}})", kBox),
              "scene.json: /shapes/0/surface/parameters/r: expected a number, got string");
    EXPECT_EQ(implicitError(R"({"type": "formula", "f": "x + r", "parameters": [1]})", kBox),
              "scene.json: /shapes/0/surface/parameters: expected an object of name: number, got "
              "array");
    EXPECT_EQ(
        implicitError(R"({"type": "formula", "f": "x + r", "parameters": {"r": 1e39}})", kBox),
        "scene.json: /shapes/0/surface/parameters/r: must be a finite number within float "
        "range, got 1e+39");
    const std::string shadow =
        implicitError(R"({"type": "formula", "f": "x + y", "parameters": {"x": 1}})", kBox);
    EXPECT_TRUE(contains(shadow, "/shapes/0/surface")) << shadow;
    EXPECT_TRUE(contains(shadow, "parameter 'x' shadows the variable 'x'")) << shadow;
    EXPECT_EQ(implicitError(R"({"type": "formula"})", kBox),
              "scene.json: /shapes/0/surface: missing key 'f'");
}

TEST(ImplicitSceneErrors, UnboundedSurfacesNeedABox) {
    EXPECT_EQ(implicitError(R"({"type": "formula", "f": "x + y"})"),
              "scene.json: /shapes/0: the surface formula \"x + y\" has no finite bounds of its "
              "own: give the shape a \"box\"");
    EXPECT_EQ(implicitError(R"({"type": "quadric", "coefficients": {"xx": 1, "yy": 1, "c": -1}})"),
              "scene.json: /shapes/0: the surface quadric has no finite bounds of its own: give "
              "the shape a \"box\"");
    EXPECT_EQ(implicitError(R"({"type": "gyroid"})"),
              "scene.json: /shapes/0: the surface gyroid period=1 level=0 has no finite bounds of "
              "its own: give the shape a \"box\"");
    for (const char* type : {"schwarz_p", "schwarz_d", "neovius"}) {
        const std::string e = implicitError(std::string(R"({"type": ")") + type + R"("})");
        EXPECT_TRUE(contains(e, "scene.json: /shapes/0: the surface ")) << e;
        EXPECT_TRUE(contains(e, "give the shape a \"box\"")) << e;
    }
    // A union or difference led by an unbounded operand is unbounded; an
    // intersection with a bounded operand is not.
    EXPECT_TRUE(contains(
        implicitError(R"({"type": "union", "operands": [{"type": "sphere"}, {"type": "gyroid"}]})"),
        "give the shape a \"box\""));
    EXPECT_TRUE(contains(
        implicitError(
            R"({"type": "difference", "operands": [{"type": "gyroid"}, {"type": "sphere"}]})"),
        "give the shape a \"box\""));
    const ShapeDesc ok =
        parseShape(R"({"type": "intersection", "operands": [{"type": "gyroid"}, {"type": "sphere"}]})");
    EXPECT_TRUE(ok.implicitSurface->bounds().has_value());
    // The same shapes with a box are fine.
    EXPECT_NO_THROW(parseShape(R"({"type": "formula", "f": "x + y"})", kBox));
    EXPECT_NO_THROW(parseShape(R"({"type": "gyroid"})", kBox));
}

TEST(ImplicitSceneErrors, ParametersOutOfRange) {
    EXPECT_EQ(implicitError(R"({"type": "sphere", "radius": -1})"),
              "scene.json: /shapes/0/surface: parameter 'radius' must be > 0 (got -1)");
    EXPECT_EQ(implicitError(R"({"type": "torus", "minor_radius": 0})"),
              "scene.json: /shapes/0/surface: parameter 'minor_radius' must be > 0 (got 0)");
    EXPECT_EQ(implicitError(R"({"type": "torus", "major_radius": -2})"),
              "scene.json: /shapes/0/surface: parameter 'major_radius' must be > 0 (got -2)");
    EXPECT_EQ(implicitError(R"({"type": "superellipsoid", "radii": [1, 0, 1]})"),
              "scene.json: /shapes/0/surface: parameter 'radii.y' must be > 0 (got 0)");
    EXPECT_EQ(implicitError(R"({"type": "superellipsoid", "e1": 20})"),
              "scene.json: /shapes/0/surface: superellipsoid exponents e1, e2 must lie in [0.01, "
              "10]");
    EXPECT_EQ(implicitError(R"({"type": "superellipsoid", "e2": 0.001})"),
              "scene.json: /shapes/0/surface: superellipsoid exponents e1, e2 must lie in [0.01, "
              "10]");
    EXPECT_EQ(implicitError(R"({"type": "blobs", "blobs": [{"radius": 0}]})"),
              "scene.json: /shapes/0/surface: parameter 'radius' must be > 0 (got 0)");
    EXPECT_EQ(implicitError(R"({"type": "blobs", "threshold": -0.5, "blobs": [{}]})"),
              "scene.json: /shapes/0/surface: parameter 'threshold' must be > 0 (got -0.5)");
    EXPECT_EQ(implicitError(R"({"type": "blobs", "blobs": []})"),
              "scene.json: /shapes/0/surface: blobs need at least one blob");
    EXPECT_EQ(implicitError(R"({"type": "gyroid", "period": 0})", kBox),
              "scene.json: /shapes/0/surface: parameter 'period' must be > 0 (got 0)");
    EXPECT_EQ(implicitError(R"({"type": "neovius", "thickness": -1})", kBox),
              "scene.json: /shapes/0/surface: parameter 'thickness' must be ≥ 0 (got -1)");
    EXPECT_EQ(implicitError(R"({"type": "quadric", "coefficients": {"c": 1}})", kBox),
              "scene.json: /shapes/0/surface: quadric coefficients are all zero apart from the "
              "constant");
    // Values that are not finite floats are caught where they are read.
    EXPECT_EQ(implicitError(R"({"type": "sphere", "radius": 1e300})"),
              "scene.json: /shapes/0/surface/radius: must be a finite number within float range, "
              "got 1e+300");
    EXPECT_EQ(implicitError(R"({"type": "sphere", "radius": "big"})"),
              "scene.json: /shapes/0/surface/radius: expected a number, got string");
    // Inside an operand, the operand's pointer.
    EXPECT_EQ(
        implicitError(R"({"type": "union", "operands": [{"type": "sphere"}, {"type": "sphere", "radius": -2}]})"),
        "scene.json: /shapes/0/surface/operands/1: parameter 'radius' must be > 0 (got -2)");
}

TEST(ImplicitSceneErrors, CellsOutOfRange) {
    EXPECT_EQ(implicitError(R"({"type": "torus"})", R"("cells": 0)"),
              "scene.json: /shapes/0/cells: must be between 1 and 256, got 0");
    EXPECT_EQ(implicitError(R"({"type": "torus"})", R"("cells": 257)"),
              "scene.json: /shapes/0/cells: must be between 1 and 256, got 257");
    EXPECT_EQ(implicitError(R"({"type": "torus"})", R"("cells": 2.5)"),
              "scene.json: /shapes/0/cells: expected an integer, got number 2.5");
}

TEST(ImplicitSceneErrors, ToleranceOutOfRange) {
    EXPECT_EQ(implicitError(R"({"type": "torus"})", R"("tolerance": 0.5)"),
              "scene.json: /shapes/0/tolerance: must lie in [1e-12, 0.1], got 0.5");
    EXPECT_EQ(implicitError(R"({"type": "torus"})", R"("tolerance": 1e-13)"),
              "scene.json: /shapes/0/tolerance: must lie in [1e-12, 0.1], got 1e-13");
    EXPECT_EQ(implicitError(R"({"type": "torus"})", R"("tolerance": 0)"),
              "scene.json: /shapes/0/tolerance: must lie in [1e-12, 0.1], got 0");
}

TEST(ImplicitSceneErrors, UnknownSurfaceTypeAndKeys) {
    EXPECT_EQ(implicitError(R"({"type": "cube"})"),
              "scene.json: /shapes/0/surface/type: must be one of sphere, quadric, torus, "
              "superellipsoid, blobs, gyroid, schwarz_p, schwarz_d, neovius, formula, union, "
              "intersection, difference, smooth_union, got 'cube'");
    EXPECT_EQ(implicitError(R"({"type": "torus", "radius": 1})"),
              "scene.json: /shapes/0/surface: unknown key 'radius' (allowed: type, transform, "
              "major_radius, minor_radius)");
    EXPECT_EQ(implicitError(R"({"type": "quadric", "coefficients": {"ww": 1}})", kBox),
              "scene.json: /shapes/0/surface/coefficients: unknown key 'ww' (allowed: xx, yy, zz, "
              "xy, yz, xz, x, y, z, c)");
    EXPECT_EQ(implicitError(R"({"type": "blobs", "blobs": [{"colour": 1}]})"),
              "scene.json: /shapes/0/surface/blobs/0: unknown key 'colour' (allowed: center, "
              "radius, strength)");
    EXPECT_EQ(implicitError(R"({"type": "sphere"})", R"("boxx": 1)"),
              "scene.json: /shapes/0: unknown key 'boxx' (allowed: type, name, material, "
              "transform, motion, surface, box, cells, tolerance)");
    EXPECT_EQ(implicitError(R"({"type": "gyroid", "blend": 1})", kBox),
              "scene.json: /shapes/0/surface: unknown key 'blend' (allowed: type, transform, "
              "period, level, thickness)");
    EXPECT_EQ(test::errorMessage([] { parseJson(sceneWith(R"({"type": "implicit"})")); }),
              "scene.json: /shapes/0: missing key 'surface'");
    EXPECT_EQ(implicitError("3"), "scene.json: /shapes/0/surface: expected a surface object, got number 3");
    EXPECT_EQ(implicitError("{}"), "scene.json: /shapes/0/surface: missing key 'type'");
}

TEST(ImplicitSceneErrors, CsgOperands) {
    EXPECT_EQ(implicitError(R"({"type": "union", "operands": [{"type": "sphere"}]})"),
              "scene.json: /shapes/0/surface/operands: needs at least two operands, got 1");
    EXPECT_EQ(implicitError(R"({"type": "difference", "operands": []})"),
              "scene.json: /shapes/0/surface/operands: needs at least two operands, got 0");
    EXPECT_EQ(implicitError(R"({"type": "intersection"})"),
              "scene.json: /shapes/0/surface: missing key 'operands'");
    EXPECT_EQ(implicitError(R"({"type": "smooth_union", "operands": [{"type": "sphere"}, {"type": "torus"}]})"),
              "scene.json: /shapes/0/surface: missing key 'blend'");
    EXPECT_EQ(
        implicitError(R"({"type": "smooth_union", "blend": 0,
                         "operands": [{"type": "sphere"}, {"type": "torus"}]})"),
        "scene.json: /shapes/0/surface: parameter 'blend' must be a finite number > 0 (got 0)");
    EXPECT_EQ(
        implicitError(R"({"type": "smooth_union", "blend": -1,
                         "operands": [{"type": "sphere"}, {"type": "torus"}]})"),
        "scene.json: /shapes/0/surface: parameter 'blend' must be a finite number > 0 (got -1)");
    // blend belongs to smooth_union only
    EXPECT_TRUE(contains(implicitError(twoSpheres("union", R"("blend": 0.5, )")),
                         "scene.json: /shapes/0/surface: unknown key 'blend'"));
    // A bad operand transform names the operation inside the operand.
    EXPECT_EQ(
        implicitError(R"({"type": "union", "operands": [{"type": "sphere"},
                         {"type": "sphere", "transform": [{"scale": 0}]}]})"),
        "scene.json: /shapes/0/surface/operands/1/transform/0/scale: must be non-zero, got 0");
}

TEST(ImplicitSceneErrors, BadBox) {
    EXPECT_EQ(implicitError(R"({"type": "sphere"})", R"("box": [[1, -1, -1], [-1, 1, 1]])"),
              "scene.json: /shapes/0/box: the minimum corner must be below the maximum corner on "
              "every axis");
    EXPECT_EQ(implicitError(R"({"type": "sphere"})", R"("box": [[1, 1, 1]])"),
              "scene.json: /shapes/0/box: expected [[xmin, ymin, zmin], [xmax, ymax, zmax]]");
    EXPECT_EQ(implicitError(R"({"type": "sphere"})", R"("box": [[0, 0, 0], [1, 0, 1]])"),
              "scene.json: /shapes/0/box: the minimum corner must be below the maximum corner on "
              "every axis");
}

// --- errors only buildWorld() finds ---------------------------------------------

std::string buildError(const std::string& shapes) {
    const SceneDesc desc = parseJson(R"({"shapes": [)" + shapes + "]}");
    return test::errorMessage([&] { buildWorld(desc, BuildOptions{}); });
}

TEST(ImplicitSceneBuild, BoxThatMissesTheSurfaceBoundsNamesTheShape) {
    EXPECT_EQ(buildError(kTriangleShape + ", " +
                         implicitShape(R"({"type": "sphere"})", R"("box": [[5, 5, 5], [6, 6, 6]])")),
              "scene.json: /shapes/1: the surface sphere r=1 has no point inside the shape's box "
              "(they do not overlap)");
    EXPECT_EQ(buildError(implicitShape(R"({"type": "torus"})", R"("box": [[-1, -1, 1], [1, 1, 2]])")),
              "scene.json: /shapes/0: the surface torus R=1 r=0.25 has no point inside the "
              "shape's box (they do not overlap)");
}

TEST(ImplicitSceneBuild, BoxWithoutSurfaceInsideNamesTheShape) {
    // The box overlaps nothing of the zero set: every cell is proven empty.
    EXPECT_EQ(buildError(kTriangleShape + ", " + kTriangleShape + ", " +
                         implicitShape(R"({"type": "formula", "f": "x^2 + y^2 + z^2 - 1"})",
                                       R"("box": [[2, 2, 2], [3, 3, 3]])")),
              "scene.json: /shapes/2: the surface formula \"x^2 + y^2 + z^2 - 1\" has no point "
              "inside its domain");
}

TEST(ImplicitSceneBuild, TheFirstBadShapeInOrderIsReported) {
    // Shapes are built in parallel; the message must not depend on timing.
    const std::string bad0 = implicitShape(R"({"type": "sphere"})", R"("box": [[5, 5, 5], [6, 6, 6]])");
    const std::string bad1 = implicitShape(R"({"type": "torus"})", R"("box": [[5, 5, 5], [6, 6, 6]])");
    for (int run = 0; run < 5; ++run) {
        const std::string e = buildError(kTriangleShape + ", " + bad0 + ", " + bad1);
        EXPECT_EQ(e.rfind("scene.json: /shapes/1: the surface sphere r=1", 0), 0u) << e;
    }
}

}  // namespace
}  // namespace strahl
