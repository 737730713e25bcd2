// Tests of the scene-file parser: defaults, every key, transform composition,
// path resolution, comments, and the exact text of every class of error.

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <limits>
#include <string>

#include "scene_test_helpers.h"
#include "strahl/core/error.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::errorWith;
using test::expectNear;
using test::kTriangleShapes;
using test::parseError;
using test::parseJson;

// A scene made of kTriangleShapes plus `sections` (comma-separated top-level members).
SceneDesc parseWith(const std::string& sections) {
    return parseJson("{" + sections + ", " + kTriangleShapes + "}");
}

// A shape list holding one inline triangle with extra members `extra`.
std::string triangleWith(const std::string& extra) {
    return R"({"shapes": [{"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]],)"
           R"( "indices": [0,1,2], )" +
           extra + "}]}";
}

using test::writeFile;

Vec3 apply(const Mat4& m, const Vec3& p) {
    return Vec3(m * Vec4(p, 1.0f));
}

// --- values --------------------------------------------------------------------

TEST(SceneParser, DefaultsForAMinimalScene) {
    const SceneDesc s = parseJson("{" + kTriangleShapes + "}");
    EXPECT_EQ(s.camera.projection, Projection::Perspective);
    EXPECT_EQ(s.camera.eye, Vec3(0.0f, 0.0f, 5.0f));
    ASSERT_TRUE(s.camera.lookAt.has_value());
    EXPECT_EQ(*s.camera.lookAt, Vec3(0.0f));
    EXPECT_FALSE(s.camera.back.has_value());
    EXPECT_EQ(s.camera.up, Vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(s.camera.focalDistance, 1.0f);
    ASSERT_TRUE(s.camera.fovYDegrees.has_value());
    EXPECT_EQ(*s.camera.fovYDegrees, 45.0f);
    EXPECT_FALSE(s.camera.window.has_value());

    EXPECT_EQ(s.film.width, 640);
    EXPECT_EQ(s.film.height, 480);
    EXPECT_TRUE(s.film.outputs.empty());
    EXPECT_TRUE(s.film.aovs.empty());
    EXPECT_FALSE(s.film.exrFloat);
    EXPECT_EQ(s.render.integrator, "direct");
    EXPECT_EQ(s.render.spp, 1);
    EXPECT_EQ(s.render.seed, 0u);
    EXPECT_EQ(s.background, Color(0.0f));
    EXPECT_TRUE(s.materials.empty());
    EXPECT_TRUE(s.lights.empty());

    ASSERT_EQ(s.shapes.size(), 1u);
    const ShapeDesc& shape = s.shapes[0];
    EXPECT_EQ(shape.name, "/shapes/0");
    EXPECT_EQ(shape.where, "/shapes/0");
    EXPECT_TRUE(shape.file.empty());
    EXPECT_EQ(shape.material, "default");
    EXPECT_EQ(shape.transform, Mat4(1.0f));
    EXPECT_EQ(shape.inlineMesh.positions.size(), 3u);
    EXPECT_EQ(shape.inlineMesh.positions[1], Vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(shape.inlineMesh.indices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_TRUE(shape.inlineMesh.normals.empty());
    EXPECT_TRUE(shape.inlineMesh.uvs.empty());

    EXPECT_TRUE(s.file.is_absolute());
    EXPECT_EQ(s.file.filename(), "scene.json");
}

TEST(SceneParser, OrthographicCameraDefaultsToTheUnitWindow) {
    const SceneDesc s = parseWith(R"("camera": {"type": "orthographic"})");
    EXPECT_EQ(s.camera.projection, Projection::Orthographic);
    EXPECT_FALSE(s.camera.fovYDegrees.has_value());
    ASSERT_TRUE(s.camera.window.has_value());
    EXPECT_EQ(s.camera.window->l, -1.0f);
    EXPECT_EQ(s.camera.window->r, 1.0f);
    EXPECT_EQ(s.camera.window->b, -1.0f);
    EXPECT_EQ(s.camera.window->t, 1.0f);
}

TEST(SceneParser, CameraKeys) {
    const SceneDesc ortho = parseWith(
        R"("camera": {"type": "orthographic", "eye": [1, 2, 3], "back": [0, 0, 2],
                      "up": [0.5, 1, 0], "focal_distance": 2.5, "window": [-2, 3, -0.5, 0.25]})");
    const CameraDesc& c = ortho.camera;
    EXPECT_EQ(c.projection, Projection::Orthographic);
    EXPECT_EQ(c.eye, Vec3(1.0f, 2.0f, 3.0f));
    EXPECT_FALSE(c.lookAt.has_value());
    ASSERT_TRUE(c.back.has_value());
    EXPECT_EQ(*c.back, Vec3(0.0f, 0.0f, 2.0f));
    EXPECT_EQ(c.up, Vec3(0.5f, 1.0f, 0.0f));
    EXPECT_EQ(c.focalDistance, 2.5f);
    ASSERT_TRUE(c.window.has_value());
    EXPECT_EQ(c.window->l, -2.0f);
    EXPECT_EQ(c.window->r, 3.0f);
    EXPECT_EQ(c.window->b, -0.5f);
    EXPECT_EQ(c.window->t, 0.25f);
    EXPECT_FALSE(c.fovYDegrees.has_value());

    const SceneDesc persp = parseWith(
        R"("camera": {"type": "perspective", "eye": [0, 1, 0], "look_at": [4, 1, 0], "fov": 60})");
    EXPECT_EQ(persp.camera.projection, Projection::Perspective);
    ASSERT_TRUE(persp.camera.lookAt.has_value());
    EXPECT_EQ(*persp.camera.lookAt, Vec3(4.0f, 1.0f, 0.0f));
    ASSERT_TRUE(persp.camera.fovYDegrees.has_value());
    EXPECT_EQ(*persp.camera.fovYDegrees, 60.0f);
    EXPECT_FALSE(persp.camera.window.has_value());

    const SceneDesc windowed = parseWith(R"("camera": {"window": [-0.5, 0.5, -0.25, 0.25]})");
    EXPECT_FALSE(windowed.camera.fovYDegrees.has_value());
    ASSERT_TRUE(windowed.camera.window.has_value());
    EXPECT_EQ(windowed.camera.window->t, 0.25f);
}

TEST(SceneParser, FilmRenderAndBackgroundKeys) {
    const SceneDesc s = parseWith(
        R"("film": {"width": 32, "height": 2.0e1, "outputs": ["a.exr", "/abs/b.PNG"],
                    "aovs": ["depth", "albedo", "normal"], "exr_float": true},
           "render": {"integrator": "primid", "spp": 65536, "seed": 18446744073709551615},
           "background": [0.25, 0.5, 2])");
    EXPECT_EQ(s.film.width, 32);
    EXPECT_EQ(s.film.height, 20);  // an integral number written as a float is an integer
    ASSERT_EQ(s.film.outputs.size(), 2u);
    EXPECT_EQ(s.film.outputs[0], fs::absolute("a.exr"));
    EXPECT_EQ(s.film.outputs[1], fs::path("/abs/b.PNG"));
    EXPECT_EQ(s.film.aovs,
              (std::vector<AovKind>{AovKind::Depth, AovKind::Albedo, AovKind::Normal}));
    EXPECT_TRUE(s.film.exrFloat);
    EXPECT_EQ(s.render.integrator, "primid");
    EXPECT_EQ(s.render.spp, 65536);
    EXPECT_EQ(s.render.seed, std::numeric_limits<uint64_t>::max());
    EXPECT_EQ(s.background, Color(0.25f, 0.5f, 2.0f));

    EXPECT_EQ(parseWith(R"("background": 0.5)").background, Color(0.5f));
    EXPECT_EQ(parseWith(R"("film": {"width": 32768, "height": 8192})").film.height, 8192);
    for (const char* integrator : {"eyelight", "normal", "depth", "direct"}) {
        const std::string render = concat(R"("render": {"integrator": ")", integrator, R"("})");
        EXPECT_EQ(parseWith(render).render.integrator, integrator);
    }
}

TEST(SceneParser, MaterialsAndShapeReferences) {
    const SceneDesc s = parseJson(
        R"({"materials": [{"name": "red", "type": "diffuse", "color": [0.63, 0.06, 0.04]},
                          {"name": "lamp", "color": 0, "emission": [10, 8, 6]}],
            "shapes": [{"type": "mesh", "name": "tri", "material": "lamp",
                        "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [0,1,2]},
                       {"type": "mesh", "material": "default",
                        "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [0,1,2]},
                       {"type": "mesh", "material": "",
                        "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [0,1,2]}]})");
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.materials[0].name, "red");
    EXPECT_EQ(std::get<DiffuseMaterial>(s.materials[0].material.kind).color.value,
              Color(0.63f, 0.06f, 0.04f));
    EXPECT_EQ(s.materials[0].material.emission.value, Color(0.0f));
    EXPECT_EQ(s.materials[0].where, "/materials/0");
    EXPECT_EQ(s.materials[1].name, "lamp");
    EXPECT_EQ(std::get<DiffuseMaterial>(s.materials[1].material.kind).color.value, Color(0.0f));
    EXPECT_EQ(s.materials[1].material.emission.value, Color(10.0f, 8.0f, 6.0f));
    EXPECT_EQ(s.materials[1].where, "/materials/1");

    ASSERT_EQ(s.shapes.size(), 3u);
    EXPECT_EQ(s.shapes[0].name, "tri");
    EXPECT_EQ(s.shapes[0].material, "lamp");
    EXPECT_EQ(s.shapes[1].material, "default");
    EXPECT_EQ(s.shapes[2].material, "default");  // empty on an inline mesh: the default
    EXPECT_EQ(s.shapes[2].where, "/shapes/2");
}

TEST(SceneParser, InlineMeshWithNormalsAndUvs) {
    const SceneDesc s = parseJson(
        triangleWith(R"("normals": [[0,0,1],[0,0,1],[0,0,1]], "uvs": [[0,0],[1,0],[0,1]])"));
    const TriangleMesh& mesh = s.shapes[0].inlineMesh;
    ASSERT_EQ(mesh.normals.size(), 3u);
    EXPECT_EQ(mesh.normals[2], Vec3(0.0f, 0.0f, 1.0f));
    ASSERT_EQ(mesh.uvs.size(), 3u);
    EXPECT_EQ(mesh.uvs[1], Vec2(1.0f, 0.0f));
    EXPECT_EQ(mesh.uvs[2], Vec2(0.0f, 1.0f));
}

TEST(SceneParser, Lights) {
    const SceneDesc s = parseWith(
        R"("lights": [{"type": "point", "position": [0, 4, 0], "intensity": [10, 20, 30]},
                      {"type": "directional", "direction": [0, -3, 4], "irradiance": 2},
                      {"type": "point", "position": [1, 2, 3]}])");
    ASSERT_EQ(s.lights.size(), 3u);
    const auto& point = std::get<PointLight>(s.lights[0].light.kind);
    EXPECT_EQ(point.position, Vec3(0.0f, 4.0f, 0.0f));
    EXPECT_EQ(point.intensity, Color(10.0f, 20.0f, 30.0f));
    EXPECT_EQ(s.lights[0].where, "/lights/0");
    const auto& directional = std::get<DirectionalLight>(s.lights[1].light.kind);
    expectNear(directional.direction, Vec3(0.0f, -0.6f, 0.8f));  // normalised
    EXPECT_EQ(directional.irradiance, Color(2.0f));
    EXPECT_EQ(directional.angularRadius, 0.0f);
    EXPECT_EQ(s.lights[1].where, "/lights/1");
    EXPECT_EQ(std::get<PointLight>(s.lights[2].light.kind).intensity, Color(1.0f));  // default
}

TEST(SceneParser, DirectionsOfExtremeMagnitude) {
    // Squaring 1e30 or 1e-30 over- or underflows a float; the parser must not.
    const SceneDesc s = parseWith(
        R"("camera": {"back": [1e-30, 0, 0], "up": [0, 1e30, 0]},
           "lights": [{"type": "directional", "direction": [0, 0, -1e30]},
                      {"type": "directional", "direction": [3e-30, 4e-30, 0]}])");
    EXPECT_EQ(*s.camera.back, Vec3(1e-30f, 0.0f, 0.0f));
    EXPECT_EQ(std::get<DirectionalLight>(s.lights[0].light.kind).direction, Vec3(0.0f, 0.0f, -1.0f));
    expectNear(std::get<DirectionalLight>(s.lights[1].light.kind).direction, Vec3(0.6f, 0.8f, 0.0f));
}

TEST(SceneParser, DuplicateKeysKeepTheLastValue) {
    EXPECT_EQ(parseWith(R"("film": {"width": 10, "width": 20})").film.width, 20);
}

TEST(SceneParser, CommentsAreAccepted) {
    const SceneDesc s = parseJson(R"(// a scene
{
  /* the film,
     in pixels */
  "film": {"width": 8, // eight
           "height": /* inline */ 4},
  )" + kTriangleShapes + R"(  // one triangle
}
// trailing comment)");
    EXPECT_EQ(s.film.width, 8);
    EXPECT_EQ(s.film.height, 4);
    EXPECT_EQ(s.shapes.size(), 1u);
}

// --- transforms ----------------------------------------------------------------

TEST(SceneParser, TransformOperationsApplyInTheOrderListed) {
    // (1,0,0) scaled by 2 -> (2,0,0), rotated 90 degrees about +z -> (0,2,0),
    // translated by (1,0,0) -> (1,2,0).
    const SceneDesc s = parseJson(triangleWith(
        R"("transform": [{"scale": 2}, {"rotate": {"axis": [0, 0, 3], "angle": 90}},
                         {"translate": [1, 0, 0]}])"));
    expectNear(apply(s.shapes[0].transform, Vec3(1.0f, 0.0f, 0.0f)), Vec3(1.0f, 2.0f, 0.0f));

    // Reversed: translate -> (2,0,0), rotate -> (0,2,0), scale -> (0,4,0).
    const SceneDesc r = parseJson(triangleWith(
        R"("transform": [{"translate": [1, 0, 0]}, {"rotate": {"axis": [0, 0, 1], "angle": 90}},
                         {"scale": 2}])"));
    expectNear(apply(r.shapes[0].transform, Vec3(1.0f, 0.0f, 0.0f)), Vec3(0.0f, 4.0f, 0.0f));
}

TEST(SceneParser, RotationFollowsTheRightHandRule) {
    const SceneDesc s =
        parseJson(triangleWith(R"("transform": [{"rotate": {"axis": [1, 0, 0], "angle": 90}}])"));
    // About +x, +y turns towards +z.
    expectNear(apply(s.shapes[0].transform, Vec3(0.0f, 1.0f, 0.0f)), Vec3(0.0f, 0.0f, 1.0f));
}

TEST(SceneParser, NonUniformScaleAndRowMajorMatrix) {
    const SceneDesc scaled = parseJson(triangleWith(R"("transform": [{"scale": [1, -2, 3]}])"));
    expectNear(apply(scaled.shapes[0].transform, Vec3(1.0f)), Vec3(1.0f, -2.0f, 3.0f));

    // Row-major: the translation is the last column as written.
    const SceneDesc m = parseJson(triangleWith(
        R"("transform": [{"matrix": [1, 2, 0, 5,  0, 1, 0, 6,  0, 0, 1, 7,  0, 0, 0, 1]}])"));
    const Mat4& t = m.shapes[0].transform;
    EXPECT_EQ(t[3], Vec4(5.0f, 6.0f, 7.0f, 1.0f));
    EXPECT_EQ(t[1][0], 2.0f);  // glm: column 1, row 0
    expectNear(apply(t, Vec3(0.0f, 1.0f, 0.0f)), Vec3(7.0f, 7.0f, 7.0f));
}

// --- paths ---------------------------------------------------------------------

TEST(SceneParser, RelativePathsResolveAgainstTheSceneFolder) {
    const fs::path dir = test::scratchDir("scene-parser-paths");
    writeFile(dir / "sub" / "meshes" / "tri.obj", "v 0 0 0\n");
    writeFile(dir / "abs.ply", "ply\n");
    const fs::path sceneFile = dir / "sub" / "scene.json";
    writeFile(sceneFile, R"({
        "film": {"outputs": ["../renders/out.exr", "out.png"]},
        "shapes": [{"type": "mesh", "file": "meshes/tri.obj"},
                   {"type": "mesh", "file": ")" +
                             (dir / "abs.ply").string() + R"(",
                    "name": "absolute"}]})");

    const SceneDesc s = parseSceneFile(sceneFile);
    EXPECT_EQ(s.file, sceneFile);
    ASSERT_EQ(s.film.outputs.size(), 2u);
    EXPECT_EQ(s.film.outputs[0], dir / "renders" / "out.exr");
    EXPECT_EQ(s.film.outputs[1], dir / "sub" / "out.png");
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(s.shapes[0].file, dir / "sub" / "meshes" / "tri.obj");
    EXPECT_EQ(s.shapes[0].name, "tri");   // the file stem
    EXPECT_EQ(s.shapes[0].material, "");  // the file's own materials
    EXPECT_TRUE(s.shapes[0].inlineMesh.positions.empty());
    EXPECT_EQ(s.shapes[1].file, dir / "abs.ply");
    EXPECT_EQ(s.shapes[1].name, "absolute");
}

TEST(SceneParser, MissingMeshFileNamesTheLookedAtPath) {
    const fs::path dir = test::scratchDir("scene-parser-missing-mesh");
    const fs::path sceneFile = dir / "scene.json";
    writeFile(sceneFile, R"({"shapes": [{"type": "mesh", "file": "x.ply"}]})");
    try {
        parseSceneFile(sceneFile);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), sceneFile.string() + ": /shapes/0/file: no such file " +
                                             "'x.ply' (looked at " + (dir / "x.ply").string() +
                                             ")");
    }
}

TEST(SceneParser, MeshFileMustBeARegularObjOrPlyFile) {
    const fs::path dir = test::scratchDir("scene-parser-mesh-kind");
    writeFile(dir / "mesh.stl", "solid\n");
    fs::create_directories(dir / "folder.obj");
    const fs::path scene = dir / "scene.json";
    auto errorFor = [&](const std::string& file) {
        try {
            parseSceneText(R"({"shapes": [{"type": "mesh", "file": ")" + file + R"("}]})", scene);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(errorFor("mesh.stl"), scene.string() + ": /shapes/0/file: 'mesh.stl' is not a " +
                                        "supported mesh format (extensions: .obj, .ply, .ply.gz, .gltf, .glb, .serialized)");
    EXPECT_EQ(errorFor("folder.obj"), scene.string() +
                                          ": /shapes/0/file: 'folder.obj' is not a regular file " +
                                          "(looked at " + (dir / "folder.obj").string() + ")");
}

TEST(SceneParser, UnreadableSceneFiles) {
    const fs::path dir = test::scratchDir("scene-parser-open");
    auto errorFor = [](const fs::path& file) {
        try {
            parseSceneFile(file);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(errorFor(dir / "scene.json"),
              (dir / "scene.json").string() + ": cannot open: No such file or directory");
    EXPECT_EQ(errorFor(dir), dir.string() + ": cannot read: Is a directory");
}

// --- syntax errors -------------------------------------------------------------

TEST(SceneParser, SyntaxErrorsGiveLineAndColumn) {
    EXPECT_EQ(parseError("{\n  \"film\": {\"width\": 10,}\n}"),
              "scene.json:2:24: syntax error: unexpected '}'; expected string literal");
    EXPECT_EQ(parseError("{\"film\" 1}"),
              "scene.json:1:9: syntax error: unexpected number literal; expected ':'");
    EXPECT_EQ(parseError("// only a comment\n/* and\n   another */ {\"film\": tru}"),
              "scene.json:3:27: syntax error: invalid literal");
    EXPECT_EQ(parseError("{\n/* never closed\n"),
              "scene.json:3:1: syntax error: invalid comment; missing closing '*/'; expected "
              "string literal");
    EXPECT_EQ(parseError(""),
              "scene.json:1:1: syntax error: unexpected end of input; expected '[', '{', or a "
              "literal");
    EXPECT_EQ(parseError("{} {}"),
              "scene.json:1:4: syntax error: unexpected '{'; expected end of input");
}

TEST(SceneParser, NumberOverflowIsASyntaxErrorAtTheNumber) {
    EXPECT_EQ(parseError("{\"background\":\n  1e400}"),
              "scene.json:2:3: syntax error: number overflow parsing '1e400'");
}

// --- content errors ------------------------------------------------------------

TEST(SceneParser, TopLevelMustBeAnObject) {
    EXPECT_EQ(parseError("[1, 2]"), "scene.json: top level: expected an object, got array");
    EXPECT_EQ(parseError("{\"camra\": {}}"),
              "scene.json: top level: unknown key 'camra' (allowed: camera, film, render, "
              "background, materials, groups, shapes, lights)");
}

TEST(SceneParser, UnknownKeysNameTheObjectAndTheAllowedKeys) {
    EXPECT_EQ(errorWith(R"("camera": {"fvo": 30})"),
              "scene.json: /camera: unknown key 'fvo' (allowed: type, eye, look_at, back, up, "
              "focal_distance, fov, window, aperture_radius, focus_distance, shutter)");
    EXPECT_EQ(errorWith(R"("film": {"widht": 30})"),
              "scene.json: /film: unknown key 'widht' (allowed: width, height, outputs, aovs, "
              "exr_float, filter, crop)");
    EXPECT_EQ(errorWith(R"("render": {"samples": 4})"),
              "scene.json: /render: unknown key 'samples' (allowed: integrator, spp, seed, "
              "max_depth, russian_roulette, russian_roulette_depth, russian_roulette_threshold, "
              "ao_distance, ao_samples, "
              "clamp_direct, clamp_indirect, filter_glossy, light_selection, hide_emitters, denoise, "
              "adaptive)");
    EXPECT_EQ(errorWith(R"("materials": [{"name": "a", "colour": 1}])"),
              "scene.json: /materials/0: unknown key 'colour' for a diffuse material (allowed: "
              "name, type, emission, two_sided, normal_map, bump_map, mapping, opacity, opacity_cutoff, color, diffuse)");
    EXPECT_EQ(errorWith(R"("materials": [{"name": "a", "type": "conductor", "color": 1}])"),
              "scene.json: /materials/0: unknown key 'color' for a conductor material (allowed: "
              "name, type, emission, two_sided, normal_map, bump_map, mapping, opacity, opacity_cutoff, metal, eta, k, "
              "roughness, roughness_u, roughness_v, distribution, masking)");
    EXPECT_EQ(parseError(triangleWith(R"("faces": [0, 1, 2])")),
              "scene.json: /shapes/0: unknown key 'faces' (allowed: type, name, file, positions, "
              "indices, normals, uvs, material, transform, motion, flip_normals, shape_index, subdivision, deform)");
    EXPECT_EQ(
        errorWith(R"("lights": [{"type": "point", "position": [0,0,0], "direction": [1,0,0]}])"),
        "scene.json: /lights/0: unknown key 'direction' (allowed: type, position, intensity)");
    EXPECT_EQ(
        errorWith(R"("lights": [{"type": "directional", "direction": [1,0,0], "intensity": 1}])"),
        "scene.json: /lights/0: unknown key 'intensity' (allowed: type, direction, "
        "irradiance, angular_diameter)");
    EXPECT_EQ(
        errorWith(R"("lights": [{"type": "sky", "intensity": 1}])"),
        "scene.json: /lights/0: unknown key 'intensity' (allowed: type, "
        "radiance)");
    EXPECT_EQ(
        errorWith(R"("lights": [{"type": "sun", "direction": [1,0,0], "intensity": 1}])"),
        "scene.json: /lights/0: unknown key 'intensity' (allowed: type, direction, "
        "irradiance, angular_diameter)");
    EXPECT_EQ(
        parseError(triangleWith(R"("transform": [{"rotate": {"axis": [0,1,0], "degrees": 3}}])")),
        "scene.json: /shapes/0/transform/0/rotate: unknown key 'degrees' (allowed: axis, "
        "angle)");
}

TEST(SceneParser, WrongTypesNameTheValue) {
    EXPECT_EQ(errorWith(R"("film": {"width": "640"})"),
              "scene.json: /film/width: expected an integer, got string");
    EXPECT_EQ(errorWith(R"("film": {"width": 64.5})"),
              "scene.json: /film/width: expected an integer, got number 64.5");
    EXPECT_EQ(errorWith(R"("film": {"exr_float": 1})"),
              "scene.json: /film/exr_float: expected true or false, got number 1");
    EXPECT_EQ(errorWith(R"("film": {"outputs": "a.png"})"),
              "scene.json: /film/outputs: expected an array, got string");
    EXPECT_EQ(errorWith(R"("camera": [])"), "scene.json: /camera: expected an object, got array");
    EXPECT_EQ(errorWith(R"("camera": {"eye": [0, "1", 2]})"),
              "scene.json: /camera/eye/1: expected a number, got string");
    EXPECT_EQ(errorWith(R"("camera": {"eye": [0, 1]})"),
              "scene.json: /camera/eye: expected an array of 3 numbers, got an array of 2");
    EXPECT_EQ(errorWith(R"("camera": {"up": null})"),
              "scene.json: /camera/up: expected an array of 3 numbers, got null");
    EXPECT_EQ(errorWith(R"("camera": {"type": 1})"),
              "scene.json: /camera/type: expected a string, got number 1");
    EXPECT_EQ(errorWith(R"("background": "black")"),
              "scene.json: /background: expected a number or an array of 3 numbers, got string");
    EXPECT_EQ(errorWith(R"("render": {"seed": 1.5})"),
              "scene.json: /render/seed: expected an integer, got number 1.5");
    EXPECT_EQ(parseError(triangleWith(R"("uvs": [[0,0],[1,0],[0,1,2]])")),
              "scene.json: /shapes/0/uvs/2: expected an array of 2 numbers, got an array of 3");
}

TEST(SceneParser, OutOfRangeValues) {
    EXPECT_EQ(errorWith(R"("film": {"width": 0})"),
              "scene.json: /film/width: must be between 1 and 32768, got 0");
    EXPECT_EQ(errorWith(R"("film": {"height": 32769})"),
              "scene.json: /film/height: must be between 1 and 32768, got 32769");
    EXPECT_EQ(errorWith(R"("film": {"width": 32768, "height": 8193})"),
              "scene.json: /film: width x height = 268468224 pixels, more than the limit of "
              "268435456 (2^28)");
    EXPECT_EQ(errorWith(R"("render": {"spp": 0})"),
              "scene.json: /render/spp: must be between 1 and 65536, got 0");
    EXPECT_EQ(errorWith(R"("render": {"spp": 1e9})"),
              "scene.json: /render/spp: must be between 1 and 65536, got 1000000000.0");
    EXPECT_EQ(errorWith(R"("render": {"seed": -1})"),
              "scene.json: /render/seed: must be a non-negative integer, got -1");
    EXPECT_EQ(errorWith(R"("render": {"seed": 1e20})"),
              "scene.json: /render/seed: must be a non-negative integer, got 1e+20");
    EXPECT_EQ(errorWith(R"("camera": {"fov": 180})"),
              "scene.json: /camera/fov: must be greater than 0 and less than 180, got 180");
    EXPECT_EQ(errorWith(R"("camera": {"focal_distance": 0})"),
              "scene.json: /camera/focal_distance: must be greater than 0, got 0");
    EXPECT_EQ(
        errorWith(R"("camera": {"window": [0, 1, -1, 1]})"),
        "scene.json: /camera/window: must satisfy l < 0 < r and b < 0 < t, got [0, 1, -1, 1]");
    EXPECT_EQ(errorWith(R"("camera": {"window": [-1, 1, -1]})"),
              "scene.json: /camera/window: expected an array of 4 numbers [l, r, b, t], got an "
              "array of 3");
    EXPECT_EQ(errorWith(R"("camera": {"eye": [0, 1e39, 0]})"),
              "scene.json: /camera/eye/1: must be a finite number within float range, got 1e+39");
    EXPECT_EQ(errorWith(R"("background": [0.5, -0.1, 0])"),
              "scene.json: /background/1: must be >= 0, got -0.1");
    EXPECT_EQ(errorWith(R"("background": -1)"), "scene.json: /background: must be >= 0, got -1");
}

TEST(SceneParser, EnumerationsListTheChoices) {
    EXPECT_EQ(errorWith(R"("camera": {"type": "fisheye"})"),
              "scene.json: /camera/type: must be one of perspective, orthographic, got 'fisheye'");
    EXPECT_EQ(errorWith(R"("render": {"integrator": "whitted"})"),
              "scene.json: /render/integrator: must be one of eyelight, normal, depth, primid, "
              "direct, ao, path, got 'whitted'");
    EXPECT_EQ(errorWith(R"("film": {"aovs": ["normal", "uv"]})"),
              "scene.json: /film/aovs/1: must be one of normal, depth, albedo, position, "
              "objectid, variance, samples, got 'uv'");
    EXPECT_EQ(errorWith(R"("film": {"aovs": ["depth", "normal", "depth"]})"),
              "scene.json: /film/aovs/2: 'depth' is listed twice");
    EXPECT_EQ(errorWith(R"("film": {"outputs": ["a.png", "b.bmp"]})"),
              "scene.json: /film/outputs/1: 'b.bmp' is not a supported image format (extensions: "
              ".exr, .png, .jpg, .jpeg, .tif, .tiff)");
    EXPECT_EQ(errorWith(R"("film": {"outputs": [""]})"),
              "scene.json: /film/outputs/0: expected a path, got an empty string");
    EXPECT_EQ(errorWith(R"("materials": [{"name": "a", "type": "glass"}])"),
              "scene.json: /materials/0/type: must be one of diffuse, phong, blinn, conductor, "
              "dielectric, thin_dielectric, diffuse_transmission, plastic, coated_conductor, metallic_roughness, principled, hair, blend, emissive, got 'glass'");
    EXPECT_EQ(errorWith(R"("lights": [{"type": "area"}])"),
              "scene.json: /lights/0/type: must be one of point, spot, projector, directional, "
              "sun, environment, sky, got 'area'");
}

TEST(SceneParser, CameraConsistency) {
    EXPECT_EQ(errorWith(R"("camera": {"look_at": [0, 0, 0], "back": [0, 0, 1]})"),
              "scene.json: /camera: 'look_at' and 'back' are exclusive: give one");
    EXPECT_EQ(errorWith(R"("camera": {"fov": 30, "window": [-1, 1, -1, 1]})"),
              "scene.json: /camera: 'fov' and 'window' are exclusive: give one");
    EXPECT_EQ(errorWith(R"("camera": {"type": "orthographic", "fov": 30})"),
              "scene.json: /camera/fov: only for a perspective camera (this one is orthographic)");
    EXPECT_EQ(errorWith(R"("camera": {"eye": [1, 2, 3], "look_at": [1, 2, 3]})"),
              "scene.json: /camera/look_at: the camera looks at its own eye position");
    EXPECT_EQ(errorWith(R"("camera": {"eye": [3e38, 0, 0], "look_at": [-3e38, 0, 0]})"),
              "scene.json: /camera/look_at: eye - look_at exceeds the float range");
    EXPECT_EQ(errorWith(R"("camera": {"back": [0, 0, 0]})"),
              "scene.json: /camera/back: must be non-zero");
    EXPECT_EQ(errorWith(R"("camera": {"up": [0, 0, -2]})"),
              "scene.json: /camera/up: is parallel to the viewing direction");
    EXPECT_EQ(errorWith(R"("camera": {"eye": [0, 5, 0]})"),
              "scene.json: /camera: the viewing direction is vertical: give an 'up' not parallel "
              "to it");
}

TEST(SceneParser, MaterialErrors) {
    EXPECT_EQ(errorWith(R"("materials": [{"color": 1}])"),
              "scene.json: /materials/0: missing key 'name'");
    EXPECT_EQ(errorWith(R"("materials": [{"name": ""}])"),
              "scene.json: /materials/0/name: must not be empty");
    EXPECT_EQ(
        errorWith(R"("materials": [{"name": "default"}])"),
        "scene.json: /materials/0/name: 'default' is reserved for the built-in grey material");
    EXPECT_EQ(errorWith(R"("materials": [{"name": "a"}, {"name": "b"}, {"name": "a"}])"),
              "scene.json: /materials/2/name: material 'a' is already defined at /materials/0");
    EXPECT_EQ(parseError(R"({"materials": [{"name": "red"}, {"name": "green"}],)" +
                         triangleWith(R"("material": "blue")").substr(1)),
              "scene.json: /shapes/0/material: unknown material 'blue' (defined: red, green, "
              "default)");
}

TEST(SceneParser, ShapeErrors) {
    EXPECT_EQ(parseError("{}"), "scene.json: scene has no shapes");
    EXPECT_EQ(parseError(R"({"shapes": []})"), "scene.json: scene has no shapes");
    EXPECT_EQ(parseError(R"({"shapes": [{"positions": [[0,0,0]], "indices": [0,0,0]}]})"),
              "scene.json: /shapes/0: missing key 'type'");
    EXPECT_EQ(parseError(R"({"shapes": [{"type": "sphere"}]})"),
              "scene.json: /shapes/0/type: must be one of mesh, implicit, parametric, curves, subdivision, instance, got 'sphere'");
    EXPECT_EQ(parseError(R"({"shapes": [{"type": "mesh"}]})"),
              "scene.json: /shapes/0: needs 'file' (a mesh file) or 'positions' (an inline mesh)");
    EXPECT_EQ(parseError(triangleWith(R"("file": "a.ply")")),
              "scene.json: /shapes/0: 'file' and 'positions' are exclusive: give one");
    EXPECT_EQ(
        parseError(R"({"shapes": [{"type": "mesh", "file": "a.ply", "indices": [0, 1, 2]}]})"),
        "scene.json: /shapes/0/indices: only for inline meshes (with 'positions'), not with "
        "'file'");
    EXPECT_EQ(
        parseError(R"({"shapes": [{"type": "mesh", "file": "a.ply", "normals": [[0, 0, 1]]}]})"),
        "scene.json: /shapes/0/normals: with 'file': \"file\", \"flat\" or \"smooth\" (an "
        "array of normals is for inline meshes)");
    EXPECT_EQ(parseError(R"({"shapes": [{"type": "mesh", "positions": [[0,0,0]]}]})"),
              "scene.json: /shapes/0: missing key 'indices'");
    EXPECT_EQ(parseError(R"({"shapes": [{"type": "mesh", "positions": [], "indices": []}]})"),
              "scene.json: /shapes/0/indices: must contain at least one triangle");
    EXPECT_EQ(
        parseError(R"({"shapes": [{"type": "mesh", "positions": [[0,0,0]], "indices": [0,0]}]})"),
        "scene.json: /shapes/0/indices: has 2 entries, not a multiple of 3 (triangles only)");
    EXPECT_EQ(parseError(
                  R"({"shapes": [{"type": "mesh", "positions": [[0,0,0]], "indices": [0,-1,0]}]})"),
              "scene.json: /shapes/0/indices/1: must be between 0 and 4294967295, got -1");
    EXPECT_EQ(
        parseError(
            R"({"shapes": [{"type": "mesh", "positions": [[0,0,0]], "indices": [0,0,0.5]}]})"),
        "scene.json: /shapes/0/indices/2: expected an integer, got number 0.5");
    // TriangleMesh::validate, with the shape's pointer as the source.
    EXPECT_EQ(parseError(R"({"shapes": [{"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]],
                                      "indices": [0, 1, 2, 2, 1, 5]}]})"),
              "scene.json: /shapes/0: triangle 1 refers to vertex 5 but there are only 3 vertices");
    EXPECT_EQ(parseError(triangleWith(R"("normals": [[0,0,1]])")),
              "scene.json: /shapes/0: 1 normals for 3 vertices");
}

TEST(SceneParser, TransformErrors) {
    auto transformError = [](const std::string& ops) {
        return parseError(triangleWith(R"("transform": )" + ops));
    };
    EXPECT_EQ(transformError(R"({"scale": 2})"),
              "scene.json: /shapes/0/transform: expected an array, got object");
    EXPECT_EQ(transformError(R"([{"scale": 2, "translate": [1, 0, 0]}])"),
              "scene.json: /shapes/0/transform/0: expected an object with exactly one of "
              "translate, scale, rotate, matrix, got an object with 2 keys");
    EXPECT_EQ(transformError(R"([[1, 0, 0]])"),
              "scene.json: /shapes/0/transform/0: expected an object with exactly one of "
              "translate, scale, rotate, matrix, got array");
    EXPECT_EQ(transformError(R"([{"shear": 2}])"),
              "scene.json: /shapes/0/transform/0: unknown key 'shear' (allowed: translate, scale, "
              "rotate, matrix)");
    EXPECT_EQ(transformError(R"([{"scale": [1, 0, 1]}])"),
              "scene.json: /shapes/0/transform/0/scale: must be non-zero, got [1,0,1]");
    EXPECT_EQ(transformError(R"([{"scale": "2"}])"),
              "scene.json: /shapes/0/transform/0/scale: expected a number or an array of 3 "
              "numbers, got string");
    EXPECT_EQ(transformError(R"([{"rotate": {"axis": [0, 0, 0], "angle": 5}}])"),
              "scene.json: /shapes/0/transform/0/rotate/axis: must be non-zero");
    EXPECT_EQ(transformError(R"([{"rotate": {"axis": [0, 1, 0]}}])"),
              "scene.json: /shapes/0/transform/0/rotate: missing key 'angle'");
    EXPECT_EQ(transformError(R"([{"matrix": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0]}])"),
              "scene.json: /shapes/0/transform/0/matrix: expected an array of 16 numbers, got an "
              "array of 12");
    EXPECT_EQ(transformError(R"([{"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,1,1]}])"),
              "scene.json: /shapes/0/transform/0/matrix: must be affine: the last row must be "
              "0 0 0 1, got 0 0 1 1");
    EXPECT_EQ(
        transformError(R"([{"matrix": [1,0,0,0, 0,1,0,0, 0,0,0,0, 0,0,0,1]}])"),
        "scene.json: /shapes/0/transform: the composed transform is singular (determinant 0)");
    // Columns (1,0,0) and (1,1e-9,0) are all but parallel.
    EXPECT_EQ(transformError(R"([{"matrix": [1,1,0,0, 0,1e-9,0,0, 0,0,1,0, 0,0,0,1]}])"),
              "scene.json: /shapes/0/transform: the composed transform is singular (determinant "
              "1e-09)");
    EXPECT_EQ(transformError(R"([{"scale": 1e30}, {"scale": 1e30}])"),
              "scene.json: /shapes/0/transform: the composed transform exceeds the float range");
}

TEST(SceneParser, LightErrors) {
    EXPECT_EQ(errorWith(R"("lights": [{"position": [0, 1, 0]}])"),
              "scene.json: /lights/0: missing key 'type'");
    EXPECT_EQ(errorWith(R"("lights": [{"type": "point"}])"),
              "scene.json: /lights/0: missing key 'position'");
    EXPECT_EQ(errorWith(R"("lights": [{"type": "directional", "direction": [0, 0, 0]}])"),
              "scene.json: /lights/0/direction: must be non-zero");
    EXPECT_EQ(
        errorWith(R"("lights": [{"type": "point", "position": [0,0,0], "intensity": [1,-1,1]}])"),
        "scene.json: /lights/0/intensity/1: must be >= 0, got -1");
    EXPECT_EQ(errorWith(R"("lights": {"type": "point"})"),
              "scene.json: /lights: expected an array, got object");
}

}  // namespace
}  // namespace strahl
