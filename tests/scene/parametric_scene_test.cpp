// Parametric shapes in scene files (docs/scene-format.md, "Parametric
// shapes"): every surface type parses and builds in both modes, the mode's
// settings reach the shape, and every class of bad input gets one message
// naming the JSON pointer (or the file and line of a patch file).

#include <gtest/gtest.h>

#include <string>

#include "geometry/ray_probes.h"
#include "scene_test_helpers.h"
#include "strahl/core/ray.h"
#include "strahl/geometry/parametric_shape.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

using test::contains;
using test::sceneWith;

std::string parametric(const std::string& surface, const std::string& extra = "") {
    return R"({"type": "parametric", "surface": )" + surface + (extra.empty() ? "" : ", " + extra) + "}";
}

SceneDesc parseAs(const std::filesystem::path& file, const std::string& text) {
    return parseSceneText(text, file);
}

SceneDesc parseInScenes(const std::string& text) { return parseAs(test::sourceDir() / "scenes" / "scene.json", text); }

// The error of parsing the scene or, for files the surface names (read by
// the builder), of building it.
std::string parametricError(const std::string& surface, const std::string& extra = "") {
    return test::errorMessage([&] {
        BuildOptions naive;
        naive.accel = AccelKind::Naive;
        buildWorld(parseInScenes(sceneWith(parametric(surface, extra))), naive);
    });
}

const char* kSurfaces[] = {
    R"({"type": "sphere", "radius": 0.5})",
    R"({"type": "torus", "major_radius": 1, "minor_radius": 0.2})",
    R"({"type": "cylinder", "radius": 0.5, "z_min": 0, "z_max": 2})",
    R"({"type": "cone", "radius": 0.5, "height": 1})",
    R"({"type": "mobius", "radius": 1, "half_width": 0.3})",
    R"({"type": "revolution", "profile": [[0, 0], [0.5, 0.2], [0.6, 0.8], [0, 1]]})",
    R"({"type": "bezier", "file": "data/teapot.bpt", "reverse": true})",
    R"J({"type": "formula", "x": "(R + r*cos(v))*cos(u)", "y": "(R + r*cos(v))*sin(u)",
        "z": "r*sin(v)", "u": [0, "2*pi"], "v": [0, "2*pi"], "periodic_u": true,
        "periodic_v": true, "parameters": {"R": 1, "r": 0.3}})J",
    // A saddle and a flat patch beside it, sharing an edge.
    R"({"type": "bilinear", "positions": [[-1, -1, 1], [1, -1, -1], [1, 1, 1], [-1, 1, -1], [3, -1, -1], [3, 1, 1]],
        "patches": [0, 1, 2, 3, 1, 4, 5, 2]})",
};

TEST(ParametricScene, EverySurfaceBuildsInBothModes) {
    for (const char* surface : kSurfaces) {
        for (const std::string mode : {"tessellated", "direct"}) {
            const SceneDesc desc = parseInScenes(sceneWith(parametric(surface, R"("mode": ")" + mode + "\"")));
            ASSERT_EQ(desc.shapes.size(), 1u);
            EXPECT_EQ(desc.shapes[0].kind, ShapeKind::Parametric);
            const World world = buildWorld(desc, BuildOptions{});
            ASSERT_EQ(world.shapes.size(), 1u);
            const SceneShape& shape = world.shapes[0];
            if (mode == "direct") {
                ASSERT_NE(shape.user, nullptr) << surface;
                EXPECT_GT(shape.user->primitiveCount(), 0u);
                EXPECT_TRUE(contains(shape.user->describe(), "(direct)"));
            } else {
                ASSERT_NE(shape.tessellated, nullptr) << surface;
                EXPECT_GT(shape.mesh.triangleCount(), 0u);
            }
        }
    }
}

TEST(ParametricScene, TessellationSettingsReachTheMesh) {
    const char* sphere = R"({"type": "sphere", "radius": 1})";
    auto triangles = [&](const std::string& tessellation) {
        const SceneDesc desc = parseInScenes(sceneWith(parametric(sphere, R"("tessellation": )" + tessellation)));
        return buildWorld(desc, BuildOptions{}).shapes[0].mesh.triangleCount();
    };
    // Uniform: 8 x 16 cells, two triangles each, minus one per pole cell.
    EXPECT_EQ(triangles(R"({"segments": [8, 16]})"), 2u * 8u * 16u - 2u * 16u);
    // A tighter chordal bound, more triangles.
    EXPECT_GT(triangles(R"({"max_error": 0.0001})"), 4 * triangles(R"({"max_error": 0.01})"));
    // Edge length on screen: one pixel gives more than eight.
    EXPECT_GT(triangles(R"({"max_edge_pixels": 1})"), triangles(R"({"max_edge_pixels": 8})"));
    const SceneDesc interpolated =
        parseInScenes(sceneWith(parametric(sphere, R"("tessellation": {"segments": 8, "normals": "interpolated"})")));
    const World world = buildWorld(interpolated, BuildOptions{});
    EXPECT_EQ(world.shapes[0].tessellated->normals(), ParametricNormals::Interpolated);
    EXPECT_FALSE(world.shapes[0].mesh.normals.empty());
}

TEST(ParametricScene, DomainsTakeExactConstantFormulas) {
    const SceneDesc desc = parseInScenes(sceneWith(parametric(
        R"J({"type": "formula", "x": "cos(u)", "y": "sin(u)", "z": "v", "u": [0, "2*pi"], "v": [-1, 1],
            "periodic_u": true})J")));
    const ParamDomain& d = desc.shapes[0].parametric.surface->domain();
    EXPECT_EQ(d.u1, 2.0 * num::kPiD);
    EXPECT_TRUE(d.periodicU);
    EXPECT_FALSE(d.periodicV);
}

TEST(ParametricScene, BadSurfacesNameTheirPlace) {
    EXPECT_TRUE(contains(parametricError(R"({"type": "sphere", "radius": -1})"),
                         "scene.json: /shapes/0/surface: radius must be a positive finite number"));
    EXPECT_TRUE(contains(parametricError(R"({"type": "klein"})"), "/shapes/0/surface/type: must be one of"));
    EXPECT_TRUE(
        contains(parametricError(R"({"type": "torus", "major_radius": 1, "minor_radius": 2})"),
                 "/shapes/0/surface: minor_radius"));
    EXPECT_TRUE(contains(
        parametricError(
            R"({"type": "formula", "x": "u +", "y": "v", "z": "0", "u": [0, 1], "v": [0, 1]})"),
        "/shapes/0/surface: x: column"));
    EXPECT_TRUE(contains(
        parametricError(
            R"({"type": "formula", "x": "1/u", "y": "v", "z": "0", "u": [0, 1], "v": [0, 1]})"),
        "/shapes/0/surface: formula"));
    EXPECT_TRUE(contains(
        parametricError(
            R"({"type": "formula", "x": "u", "y": "v", "z": "0", "u": [1, 0], "v": [0, 1]})"),
        "/shapes/0/surface/u: the domain is empty or inverted"));
    EXPECT_TRUE(contains(
        parametricError(R"({"type": "formula", "x": "u", "y": "v", "z": "0", "u": [0, "2*pie"], "v": [0, 1]})"),
        "/shapes/0/surface/u/1"));
    EXPECT_TRUE(contains(parametricError(R"({"type": "revolution", "profile": [[-1, 0], [1, 1]]})"),
                         "/shapes/0/surface"));
    EXPECT_TRUE(contains(parametricError(R"({"type": "bezier", "file": "data/missing.bpt"})"),
                         "/shapes/0/surface/file"));
    EXPECT_TRUE(contains(parametricError(R"({"type": "heightfield", "image": "data/teapot.bpt"})"),
                         "/shapes/0/surface/image"));
    EXPECT_TRUE(contains(
        parametricError(R"({"type": "bilinear", "positions": [[0, 0, 0], [1, 0, 0], [1, 1, 0]],
                                    "patches": [0, 1, 2, 3]})"),
        "/shapes/0/surface/patches/3: index 3 is beyond the 3 positions"));
    EXPECT_TRUE(contains(
        parametricError(R"({"type": "bilinear", "positions": [[0, 0, 0], [1, 0, 0], [1, 1, 0]],
                                    "patches": [0, 1, 2]})"),
        "/shapes/0/surface/patches: expected four corner indices per patch, got 3 indices"));
    EXPECT_TRUE(contains(
        parametricError(R"({"type": "bilinear", "positions": [[0, 0], [1, 0, 0], [1, 1, 0]],
                                    "patches": [0, 1, 2, 0]})"),
        "/shapes/0/surface/positions/0: expected [x, y, z]"));
}

TEST(ParametricScene, FlipNormalsTurnsTheFrontAroundInBothModes) {
    const char* sphere = R"({"type": "sphere", "radius": 1})";
    // Tessellated: the triangles' winding and the exact normals both turn.
    const auto tessellatedNormal = [&](bool flip) {
        const SceneDesc desc =
            parseInScenes(sceneWith(parametric(sphere, flip ? R"("flip_normals": true)" : R"("flip_normals": false)")));
        const World world = buildWorld(desc, BuildOptions{});
        const SceneShape& shape = world.shapes[0];
        const SurfaceInteraction si = shape.tessellated->interaction(shape.mesh, 0, 0.3f, 0.3f);
        EXPECT_GT(glm::dot(si.Ng, si.Ns), 0.0f);
        return glm::dot(si.Ns, si.p);  // > 0: outwards
    };
    EXPECT_GT(tessellatedNormal(false), 0.0f);
    EXPECT_LT(tessellatedNormal(true), 0.0f);
    // Direct: the reported geometric normal turns.
    const auto directNormal = [&](bool flip) {
        const SceneDesc desc = parseInScenes(sceneWith(parametric(
            sphere, std::string(R"("mode": "direct", "flip_normals": )") + (flip ? "true" : "false"))));
        const World world = buildWorld(desc, BuildOptions{});
        const UserShape& user = *world.shapes[0].user;
        Ray ray;
        ray.origin = Vec3(0.1f, 0.2f, 5.0f);
        ray.dir = Vec3(0.0f, 0.0f, -1.0f);
        const Hit best = nearestHit(user, ray);
        EXPECT_TRUE(best.valid());
        return user.interaction(ray, best).Ng.z;  // the hit is on the near side, z > 0
    };
    EXPECT_GT(directNormal(false), 0.0f);
    EXPECT_LT(directNormal(true), 0.0f);
}

TEST(ParametricScene, MalformedPatchFilesNameFileAndLine) {
    const auto dir = test::scratchDir("bad-patches");
    test::writeFile(dir / "bad.bpt", "1\n3 3\n0 0 0\n1 0 0\n");  // truncated after 2 of 16 points
    const std::string message = test::errorMessage([&] {
        buildWorld(parseAs(dir / "scene.json",
                           sceneWith(parametric(R"({"type": "bezier", "file": "bad.bpt"})"))),
                   BuildOptions{});
    });
    EXPECT_TRUE(contains(message, "/shapes/0/surface/file")) << message;
    EXPECT_TRUE(contains(message, "bad.bpt:")) << message;
}

TEST(ParametricScene, BadModeSettingsAreNamed) {
    const char* sphere = R"({"type": "sphere"})";
    EXPECT_TRUE(contains(parametricError(sphere, R"("mode": "exact")"), "/shapes/0/mode: must be one of tessellated, direct"));
    EXPECT_TRUE(
        contains(parametricError(sphere, R"("mode": "direct", "tessellation": {"segments": 4})"),
                 "/shapes/0/tessellation: only for \"mode\": \"tessellated\""));
    EXPECT_TRUE(contains(parametricError(sphere, R"("direct": {"tolerance": 1e-6})"),
                         "/shapes/0/direct: only for \"mode\": \"direct\""));
    EXPECT_TRUE(contains(parametricError(sphere, R"("tessellation": {"segments": 0})"), "/shapes/0/tessellation/segments"));
    EXPECT_TRUE(contains(parametricError(sphere, R"("tessellation": {"segments": 100000})"),
                         "/shapes/0/tessellation/segments"));
    EXPECT_TRUE(contains(parametricError(sphere, R"("tessellation": {"max_error": -1})"),
                         "/shapes/0/tessellation/max_error: must be a positive number"));
    EXPECT_TRUE(contains(parametricError(sphere, R"("tessellation": {"normals": "smooth"})"),
                         "/shapes/0/tessellation/normals"));
    EXPECT_TRUE(
        contains(parametricError(sphere, R"("mode": "direct", "direct": {"tolerance": 0.5})"),
                 "/shapes/0/direct/tolerance: must lie in"));
    EXPECT_TRUE(
        contains(parametricError(sphere, R"("box": [[0,0,0],[1,1,1]])"), "unknown key 'box'"));
}

TEST(ParametricScene, SingularTransformIsRejected) {
    EXPECT_TRUE(contains(parametricError(R"({"type": "sphere"})", R"("mode": "direct", "transform": [{"scale": [1, 0, 1]}])"),
                         "/shapes/0/transform/0/scale: must be non-zero"));
}

}  // namespace
}  // namespace strahl
