// The pbrt-v4 importer (src/scene/pbrt_*.cpp, docs/pbrt.md): the language
// (tokens, parameter lists, transforms, the graphics state, named materials,
// objects and instances, includes), the mappings whose numbers are easy to get
// wrong (the mirrored camera, fov on the shorter axis, roughness remapping,
// light normalisation, checkerboard parity), and one clear error, with file
// and line, for what is malformed or not supported.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include <OpenImageIO/imageio.h>

#include "strahl/core/equal_area.h"
#include "strahl/integrator/world.h"
#include "strahl/material/diffuse.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "strahl/scene/scene_document.h"
#include "geometry/ray_probes.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::HasSubstr;

// A scene around `world`: a camera at (0, 0, 5) looking at the origin, a
// 64 x 32 film, and `options` before WorldBegin.
std::string scene(const std::string& world, const std::string& options = "") {
    return "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
           "Film \"rgb\" \"integer xresolution\" 64 \"integer yresolution\" 32\n" +
           options + "\nWorldBegin\n" + world + "\n";
}
const std::string kTriangle = "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n";

json document(const std::string& text, const fs::path& file = "scene.pbrt") {
    return json::parse(SceneDocument::fromText(text, file).text());
}
std::string errorOf(const std::string& text, const fs::path& file = "scene.pbrt") {
    return test::errorMessage([&] { SceneDocument::fromText(text, file).parse(); });
}
glm::dvec3 vec(const json& v) { return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()}; }
// A shape's transform as a matrix (the importer writes one "matrix" op, row by row).
glm::dmat4 matrixOf(const json& shape) {
    const json& m = shape["transform"][0]["matrix"];
    glm::dmat4 out(1.0);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out[c][r] = m[4 * r + c].get<double>();
    return out;
}
void expectNear(glm::dvec3 a, glm::dvec3 b, double tolerance = 1e-9) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(PbrtImport, TheImageRightIsPbrtsCameraXSoTheWorldIsMirrored) {
    // pbrt's LookAt puts image right along up x dir; strahl's u = v x w is
    // the other way round, so the world is mirrored in x.
    const json doc = document(scene(kTriangle));
    const json& cam = doc["camera"];
    const glm::dvec3 up = vec(cam["up"]), back = vec(cam["back"]);
    const glm::dvec3 right = glm::cross(up, back);  // strahl's u
    // pbrt: dir (0, 0, -1), up (0, 1, 0): right = up x dir = (-1, 0, 0),
    // which the mirror makes (1, 0, 0).
    expectNear(glm::normalize(right), {1, 0, 0});
    expectNear(vec(cam["eye"]), {0, 0, 5});
    const glm::dmat4 m = matrixOf(doc["shapes"][0]);
    expectNear(glm::dvec3(m * glm::dvec4(1, 0, 0, 1)), {-1, 0, 0});
    // So pbrt's +x (image left here) stays on the image's left.

    // A camera that mirrors already ("Scale -1 1 1" before LookAt, as exporters
    // write) leaves the world as it is.
    const json exported = document("Scale -1 1 1\n" + scene(kTriangle));
    expectNear(glm::dvec3(matrixOf(exported["shapes"][0]) * glm::dvec4(1, 0, 0, 1)), {1, 0, 0});
    const glm::dvec3 right2 = glm::cross(vec(exported["camera"]["up"]), vec(exported["camera"]["back"]));
    expectNear(glm::normalize(right2), {1, 0, 0});
}

TEST(PbrtImport, FovSpansTheShorterImageAxis) {
    const json wide = document(scene(kTriangle));  // 64 x 32: fov is vertical
    const json& w = wide["camera"]["window"];
    const double d = wide["camera"]["focal_distance"].get<double>();
    EXPECT_NEAR(w[3].get<double>() / d, std::tan(glm::radians(45.0) / 2), 1e-12);
    EXPECT_NEAR(w[1].get<double>() / d, 2 * std::tan(glm::radians(45.0) / 2), 1e-12);
    const json tall = document("Camera \"perspective\" \"float fov\" 45\n"
                               "Film \"rgb\" \"integer xresolution\" 32 \"integer yresolution\" 64\nWorldBegin\n" +
                               kTriangle);
    const json& t = tall["camera"]["window"];
    const double dt = tall["camera"]["focal_distance"].get<double>();
    EXPECT_NEAR(t[1].get<double>() / dt, std::tan(glm::radians(45.0) / 2), 1e-12);
    EXPECT_NEAR(t[3].get<double>() / dt, 2 * std::tan(glm::radians(45.0) / 2), 1e-12);
    // pbrt's defaults: 1280 x 720, fov 90, 16 samples, path tracing to depth 5.
    const json defaults = document("WorldBegin\n" + kTriangle);
    EXPECT_EQ(defaults["film"]["width"], 1280);
    EXPECT_EQ(defaults["film"]["height"], 720);
    EXPECT_EQ(defaults["render"]["spp"], 16);
    EXPECT_EQ(defaults["render"]["max_depth"], 5);
    EXPECT_EQ(defaults["render"]["integrator"], "path");
}

TEST(PbrtImport, TransformsPostMultiplyAndTransformIsColumnMajor) {
    const json doc = document(scene("AttributeBegin\nTranslate 1 0 0\nScale 2 2 2\n" + kTriangle +
                                    "AttributeEnd\n"
                                    "AttributeBegin\nRotate 90 0 0 1\n" + kTriangle + "AttributeEnd\n"
                                    "AttributeBegin\nTransform [1 0 0 0  0 1 0 0  0 0 1 0  3 4 5 1]\n" +
                                    kTriangle + "AttributeEnd\n" +
                                    "AttributeBegin\nCoordSysTransform \"camera\"\n" + kTriangle + "AttributeEnd\n"));
    const glm::dmat4 mirror = glm::scale(glm::dmat4(1.0), glm::dvec3(-1, 1, 1));
    auto world = [&](int shape, glm::dvec3 p) {
        return glm::dvec3(mirror * matrixOf(doc["shapes"][shape]) * glm::dvec4(p, 1.0));
    };
    expectNear(world(0, {1, 0, 0}), {3, 0, 0});  // translate(scale(p))
    expectNear(world(1, {1, 0, 0}), {0, 1, 0});  // Rotate 90 about z: +x to +y
    expectNear(world(2, {0, 0, 0}), {3, 4, 5});  // the translation is the 4th column
    expectNear(world(3, {0, 0, 0}), {0, 0, 5});  // the camera's origin
    expectNear(world(3, {0, 0, 1}), {0, 0, 4});  // looking down -z
}

TEST(PbrtImport, MaterialsMapOntoStrahlsModels) {
    const json doc = document(scene(
        "Material \"conductor\" \"float roughness\" 0.04\n" + kTriangle +
        "Material \"conductor\" \"float roughness\" 0.04 \"bool remaproughness\" false\n" + kTriangle +
        "Material \"dielectric\" \"spectrum eta\" \"glass-BK7\"\n" + kTriangle +
        "Material \"coateddiffuse\" \"rgb reflectance\" [0.5 0.2 0.1]\n" + kTriangle +
        "MakeNamedMaterial \"a\" \"string type\" \"diffuse\" \"rgb reflectance\" [1 0 0]\n"
        "MakeNamedMaterial \"b\" \"string type\" \"thindielectric\"\n"
        "Material \"mix\" \"string materials\" [\"a\" \"b\"] \"float amount\" 0.25\n" + kTriangle +
        "Material \"conductor\" \"rgb reflectance\" [0.5 0.5 0.5]\n" + kTriangle +
        "Material \"diffusetransmission\" \"rgb transmittance\" [0.5 0.5 0.5] \"float scale\" 0.5\n" + kTriangle));
    const json& m = doc["materials"];
    ASSERT_EQ(m.size(), 7u);
    // Copper by default; GGX alpha = sqrt(roughness) when remapped, strahl's
    // roughness = sqrt(alpha).
    EXPECT_EQ(m[0]["type"], "conductor");
    EXPECT_NEAR(m[0]["roughness"].get<double>(), std::sqrt(0.2), 1e-12);
    EXPECT_NEAR(vec(m[0]["eta"]).g, 0.923749, 1e-6);  // copper's green
    EXPECT_NEAR(m[1]["roughness"].get<double>(), 0.2, 1e-12);
    EXPECT_EQ(m[2]["type"], "dielectric");
    EXPECT_NEAR(m[2]["ior"].get<double>(), 1.5185, 1e-4);
    EXPECT_EQ(m[3]["type"], "plastic");
    EXPECT_EQ(m[3]["nonlinear"], true);
    EXPECT_EQ(m[4]["type"], "blend");
    EXPECT_EQ(m[4]["weight"], 0.25);  // pbrt picks the second with probability amount
    EXPECT_EQ(m[4]["materials"][0]["type"], "diffuse");
    EXPECT_EQ(m[4]["materials"][1]["type"], "thin_dielectric");
    // reflectance r: eta 1, k = 2 sqrt(r) / sqrt(1 - r) = 2 for r = 1/2.
    EXPECT_EQ(m[5]["eta"], 1.0);
    EXPECT_NEAR(m[5]["k"].get<double>(), 2.0, 1e-12);
    EXPECT_EQ(m[6]["type"], "diffuse_transmission");
    EXPECT_EQ(m[6]["color"], 0.125);
    EXPECT_EQ(m[6]["transmittance"], 0.25);
    // The whole document is a valid strahl scene.
    EXPECT_NO_THROW(SceneDocument::fromText(scene(kTriangle), "scene.pbrt").parse());
}

TEST(PbrtImport, CoatedConductorKeepsBothLayersAndTheLayersThickness) {
    const std::string text = scene(
        "Material \"coatedconductor\" \"float conductor.roughness\" 0.09 \"float interface.roughness\" 0.01\n"
        "  \"spectrum conductor.eta\" \"metal-Au-eta\" \"spectrum conductor.k\" \"metal-Au-k\"\n" + kTriangle +
        "Material \"coatedconductor\" \"float interface.eta\" 1.7 \"float thickness\" 0\n"
        "  \"rgb reflectance\" [0.5 0.5 0.5]\n" + kTriangle);
    const json doc = document(text);
    const json& m = doc["materials"];
    ASSERT_EQ(m.size(), 2u);
    EXPECT_EQ(m[0]["type"], "coated_conductor");
    // Remapped: alpha = sqrt(r), strahl's roughness = sqrt(alpha) = r^(1/4).
    EXPECT_NEAR(m[0]["roughness"].get<double>(), std::pow(0.09, 0.25), 1e-12);
    EXPECT_NEAR(m[0]["coat_roughness"].get<double>(), std::pow(0.01, 0.25), 1e-12);
    EXPECT_EQ(m[0]["ior"], 1.5);
    EXPECT_EQ(m[0]["thickness"], 0.01);  // pbrt's default
    EXPECT_GT(vec(m[0]["k"]).r, 3.0);  // gold's k in the red
    EXPECT_EQ(m[1]["ior"], 1.7);
    EXPECT_FALSE(m[1].contains("thickness"));
    EXPECT_EQ(m[1]["eta"], 1.0);
    EXPECT_NEAR(m[1]["k"].get<double>(), 2.0, 1e-12);
    EXPECT_NO_THROW(SceneDocument::fromText(text, "scene.pbrt").parse());

    EXPECT_THAT(errorOf(scene("Material \"coatedconductor\" \"float conductor.uroughness\" 0.1\n" + kTriangle)),
                HasSubstr("an anisotropic coated conductor is not supported"));
}

TEST(PbrtImport, BilinearMeshesAreTrianglesWhenFlatAndTheExactSurfaceWhenTwisted) {
    // pbrt's corner order per patch is p00, p10, p01, p11.
    const json flat = document(scene(
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0] \"point2 uv\" [0 0 1 0 0 1 1 1]\n"));
    const json& mesh = flat["shapes"][0];
    EXPECT_EQ(mesh["type"], "mesh");
    EXPECT_EQ(mesh["indices"], json({0, 1, 3, 0, 3, 2}));  // (p00, p10, p11), (p00, p11, p01)
    EXPECT_EQ(mesh["uvs"].size(), 4u);

    const std::string twistedText = scene("Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 1]\n");
    const json twisted = document(twistedText);
    const json& surface = twisted["shapes"][0];
    EXPECT_EQ(surface["type"], "parametric");
    EXPECT_EQ(surface["surface"]["type"], "bilinear");
    EXPECT_EQ(surface["surface"]["patches"], json({0, 1, 3, 2}));  // strahl's order around the patch
    EXPECT_EQ(surface["tessellation"]["segments"], 1);
    EXPECT_NO_THROW(buildWorld(SceneDocument::fromText(twistedText, "scene.pbrt").parse(), BuildOptions{}));

    EXPECT_THAT(errorOf(scene("Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 1] "
                              "\"point2 uv\" [0 0 1 0 0 1 1 1]\n")),
                HasSubstr("\"uv\" on twisted bilinear patches is not supported"));
    EXPECT_THAT(errorOf(scene("Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 1] "
                              "\"integer indices\" [0 1 2]\n")),
                HasSubstr("expected 4 indices per primitive"));
}

TEST(PbrtImport, TwistedAndFlatBilinearPatchesFaceTheSameWay) {
    // A flat patch (a mesh) and a slightly twisted one (a parametric surface)
    // with the same corners in the same order face the same side, with and
    // without ReverseOrientation, through the importer's mirror.
    for (const std::string reverse : {"", "ReverseOrientation\n"}) {
        const std::string text = scene(
            "AttributeBegin\n" + reverse +
            "Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0]\n"
            "Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0.05]\nAttributeEnd\n");
        const World world = buildWorld(SceneDocument::fromText(text, "scene.pbrt").parse(), BuildOptions{});
        ASSERT_EQ(world.shapes.size(), 2u);
        ASSERT_EQ(world.shapes[1].tessellated != nullptr, true);
        const Vec3 flatNormal = triangleInteraction(world.shapes[0].mesh, 0, 0.2f, 0.2f).Ng;
        const SurfaceInteraction twisted = world.shapes[1].tessellated->interaction(world.shapes[1].mesh, 0, 0.2f, 0.2f);
        EXPECT_GT(glm::dot(flatNormal, twisted.Ns), 0.9f) << reverse;
        EXPECT_GT(glm::dot(flatNormal, twisted.Ng), 0.9f) << reverse;
    }
}

TEST(PbrtImport, AReversedSphereIsAnInsideOutMesh) {
    // Regression: ReverseOrientation on a sphere made a parametric shape with
    // "flip_normals", which the scene format refused.
    const std::string text = scene("AttributeBegin\nReverseOrientation\nShape \"sphere\" \"float radius\" 1\nAttributeEnd\n");
    const json doc = document(text);
    EXPECT_EQ(doc["shapes"][0]["type"], "parametric");
    EXPECT_EQ(doc["shapes"][0]["flip_normals"], true);
    const World world = buildWorld(SceneDocument::fromText(text, "scene.pbrt").parse(), BuildOptions{});
    const SceneShape& sphere = world.shapes[0];
    const SurfaceInteraction si = sphere.tessellated->interaction(sphere.mesh, 0, 0.3f, 0.3f);
    EXPECT_LT(glm::dot(si.Ns, si.p), 0.0f);  // facing the centre
}

TEST(PbrtImport, TexturedQuadricsHavePbrtsUv) {
    // pbrt's (u, v): sphere (phi / 2 pi, (pi - theta) / pi), disk (phi / 2 pi,
    // (r_max - r) / (r_max - r_i)), cylinder (phi / 2 pi, (z - z_min) /
    // (z_max - z_min)), phi = atan2(y, x) in [0, 2 pi), in object space. The
    // importer mirrors the world in x: object (x, y, z) is world (-x, y, z).
    const std::string text = scene(
        "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"" + (test::sourceDir() / "tests/golden/parametric.exr").string() + "\"\n"
        "Material \"diffuse\" \"texture reflectance\" \"t\"\n"
        "AttributeBegin\nTranslate 0 0 -3\nShape \"sphere\" \"float radius\" 2\nAttributeEnd\n"
        "AttributeBegin\nTranslate 0 0 2\nShape \"disk\" \"float radius\" 1 \"float innerradius\" 0.25\nAttributeEnd\n"
        "AttributeBegin\nTranslate 4 0 0\nShape \"cylinder\" \"float radius\" 0.5 \"float zmin\" 0 \"float zmax\" 2\nAttributeEnd\n");
    const World world = buildWorld(SceneDocument::fromText(text, "scene.pbrt").parse(), BuildOptions{});
    ASSERT_EQ(world.shapes.size(), 3u);
    const auto phiOf = [](double x, double y) {
        const double phi = std::atan2(y, x);
        return phi < 0.0 ? phi + 2.0 * M_PI : phi;
    };
    const auto expectUv = [](const SurfaceInteraction& si, double u, double v, const char* what) {
        // Away from the seam at phi = 0, where u wraps.
        if (u < 0.01 || u > 0.99) return;
        EXPECT_NEAR(si.uv.x, u, 2e-3) << what;
        EXPECT_NEAR(si.uv.y, v, 2e-3) << what;
    };
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> spread(-1.0f, 1.0f);
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        // The sphere, centred at world (0, 0, -3), from the camera's side.
        Ray ray;
        ray.origin = Vec3(0.0f, 0.0f, 5.0f);
        ray.dir = glm::normalize(Vec3(1.6f * spread(rng), 1.6f * spread(rng), -8.0f));
        const Hit hit = nearestHit(*world.shapes[0].user, ray);
        if (!hit.valid()) continue;
        const SurfaceInteraction si = world.shapes[0].user->interaction(ray, hit);
        const glm::dvec3 o = glm::dvec3(-si.p.x, si.p.y, si.p.z + 3.0f) / 2.0;
        expectUv(si, phiOf(o.x, o.y) / (2.0 * M_PI), (M_PI - std::acos(std::clamp(o.z, -1.0, 1.0))) / M_PI, "sphere");
        ++checked;
    }
    const SceneShape& disk = world.shapes[1];
    for (uint32_t prim = 0; prim < disk.mesh.triangleCount(); prim += 7) {
        const SurfaceInteraction si = disk.tessellated->interaction(disk.mesh, prim, 0.3f, 0.3f);
        const double r = std::hypot(si.p.x, si.p.y);
        expectUv(si, phiOf(-si.p.x, si.p.y) / (2.0 * M_PI), (1.0 - r) / 0.75, "disk");
        ++checked;
    }
    for (int i = 0; i < 100; ++i) {
        // The open cylinder, its axis at world x = -4 (the mirror), seen from the axis.
        Ray ray;
        ray.origin = Vec3(-4.0f, 0.0f, 1.0f + 0.8f * spread(rng));
        ray.dir = glm::normalize(Vec3(spread(rng), spread(rng), 0.0f) + Vec3(1e-3f, 0.0f, 0.0f));
        const Hit hit = nearestHit(*world.shapes[2].user, ray);
        if (!hit.valid()) continue;
        const SurfaceInteraction si = world.shapes[2].user->interaction(ray, hit);
        expectUv(si, phiOf(-si.p.x - 4.0f, si.p.y) / (2.0 * M_PI), si.p.z / 2.0, "cylinder");
        ++checked;
    }
    EXPECT_GT(checked, 200);
}

TEST(PbrtImport, NamedMaterialsMayComeLaterAndObjectsAreGroups) {
    const json doc = document(scene(
        "NamedMaterial \"late\"\n"
        "ObjectBegin \"tri\"\nTranslate 0 1 0\n" + kTriangle + "ObjectEnd\n"
        "AttributeBegin\nTranslate 2 0 0\nObjectInstance \"tri\"\nAttributeEnd\n"
        "ObjectInstance \"tri\"\n"
        "MakeNamedMaterial \"late\" \"string type\" \"diffuse\" \"rgb reflectance\" [0.1 0.2 0.3]\n"));
    ASSERT_EQ(doc["groups"].size(), 1u);
    EXPECT_EQ(doc["groups"][0]["shapes"][0]["material"], "late");
    ASSERT_EQ(doc["shapes"].size(), 2u);
    EXPECT_EQ(doc["shapes"][0]["type"], "instance");
    // world = mirror . CTM at the instance . CTM at the definition
    const glm::dmat4 instance = matrixOf(doc["shapes"][0]);
    const glm::dmat4 inner = matrixOf(doc["groups"][0]["shapes"][0]);
    expectNear(glm::dvec3(instance * inner * glm::dvec4(0, 0, 0, 1)), {-2, 1, 0});
    EXPECT_THAT(errorOf(scene("NamedMaterial \"nowhere\"\n" + kTriangle)),
                HasSubstr("scene.pbrt:6: NamedMaterial: no material named \"nowhere\""));
    EXPECT_THAT(errorOf(scene("ObjectInstance \"nothing\"\n" + kTriangle)),
                HasSubstr("scene.pbrt:6: ObjectInstance: no object named \"nothing\""));
}

TEST(PbrtImport, LightsKeepRgbValuesAndNormaliseSpectraToLuminanceOne) {
    const json doc = document(scene(
        kTriangle + "LightSource \"point\" \"rgb I\" [1 2 3] \"float scale\" 2 \"point3 from\" [1 0 0]\n"
                    "LightSource \"point\" \"blackbody I\" 3000 \"float scale\" 4\n"
                    "LightSource \"point\" \"rgb I\" [1 1 1] \"float power\" 100\n"
                    "LightSource \"spot\" \"point3 from\" [0 0 0] \"point3 to\" [0 -1 0] \"float coneangle\" 20 "
                    "\"float conedeltaangle\" 5\n"
                    "LightSource \"distant\" \"point3 from\" [0 0 0] \"point3 to\" [1 0 0] \"rgb L\" [3 3 3]\n"
                    "LightSource \"infinite\" \"rgb L\" [0.5 0.5 0.5]\n"));
    const json& l = doc["lights"];
    ASSERT_EQ(l.size(), 6u);
    expectNear(vec(l[0]["intensity"]), {2, 4, 6});
    expectNear(vec(l[0]["position"]), {-1, 0, 0});  // mirrored
    const glm::dvec3 bb = vec(l[1]["intensity"]);
    EXPECT_NEAR(0.2126729 * bb.r + 0.7151522 * bb.g + 0.0721750 * bb.b, 4.0, 1e-9);
    EXPECT_GT(bb.r, bb.b);  // 3000 K is reddish
    EXPECT_NEAR(l[2]["intensity"].get<double>(), 100 / (4 * M_PI), 1e-9);
    EXPECT_EQ(l[3]["type"], "spot");
    EXPECT_EQ(l[3]["cone_angle"], 20.0);
    EXPECT_EQ(l[3]["falloff_start"], 15.0);
    expectNear(vec(l[3]["direction"]), {0, -1, 0});
    EXPECT_EQ(l[4]["type"], "directional");
    expectNear(vec(l[4]["direction"]), {-1, 0, 0});  // from -> to, mirrored
    EXPECT_EQ(l[4]["irradiance"], 3.0);
    EXPECT_EQ(l[5]["type"], "sky");
    EXPECT_EQ(l[5]["radiance"], 0.5);
}

TEST(PbrtImport, NamedIlluminantsAreTheirChromaticitiesAtLuminanceOne) {
    // Each named illuminant's RGB, converted back to chromaticity through
    // sRGB's primaries, is the CIE's (x, y), at luminance 1.
    const auto chromaticity = [](const glm::dvec3& rgb) {
        const glm::dvec3 xyz(0.4124564 * rgb.r + 0.3575761 * rgb.g + 0.1804375 * rgb.b,
                             0.2126729 * rgb.r + 0.7151522 * rgb.g + 0.0721750 * rgb.b,
                             0.0193339 * rgb.r + 0.1191920 * rgb.g + 0.9503041 * rgb.b);
        return glm::dvec3(xyz.x / (xyz.x + xyz.y + xyz.z), xyz.y / (xyz.x + xyz.y + xyz.z), xyz.y);
    };
    struct Case {
        const char* name;
        double x, y;
    };
    for (const Case& c : {Case{"stdillum-A", 0.44757, 0.40745}, Case{"stdillum-D50", 0.34567, 0.35850},
                          Case{"stdillum-F2", 0.37208, 0.37529}, Case{"stdillum-F11", 0.38052, 0.37713},
                          Case{"illum-acesD60", 0.32168, 0.33767}}) {
        const json doc = document(scene(kTriangle + "LightSource \"point\" \"spectrum I\" \"" +
                                        c.name + "\" \"float scale\" 3\n"));
        const glm::dvec3 xyY = chromaticity(vec(doc["lights"][0]["intensity"]));
        EXPECT_NEAR(xyY.x, c.x, 2e-4) << c.name;
        EXPECT_NEAR(xyY.y, c.y, 2e-4) << c.name;
        EXPECT_NEAR(xyY.z, 3.0, 2e-3) << c.name;
    }
    const glm::dvec3 a = vec(document(scene(kTriangle + "LightSource \"point\" \"spectrum I\" "
                                                        "\"stdillum-A\"\n"))["lights"][0]["intensity"]);
    EXPECT_GT(a.r, a.g);  // incandescent: warm
    EXPECT_GT(a.g, a.b);
    EXPECT_THAT(errorOf(scene("Material \"diffuse\" \"spectrum reflectance\" \"stdillum-F1\"\n" + kTriangle)),
                HasSubstr("an illuminant is only for lights"));
    EXPECT_THAT(errorOf(scene(kTriangle + "LightSource \"point\" \"spectrum I\" \"stdillum-F13\"\n")),
                HasSubstr("the named spectrum 'stdillum-F13' is not supported here"));
}

TEST(PbrtImport, AreaLightsAreTheEmissionOfTheShapesMaterial) {
    const json doc = document(scene("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [4 4 4] \"bool twosided\" true\n"
                                    "ReverseOrientation\n" + kTriangle + "AttributeEnd\n" + kTriangle));
    const json& m = doc["materials"];
    ASSERT_EQ(m.size(), 2u);  // pbrt's default material, with and without the light
    EXPECT_EQ(m[0]["emission"], 4.0);
    EXPECT_EQ(m[0]["two_sided"], true);
    EXPECT_EQ(m[0]["color"], 0.5);  // pbrt's default material: diffuse 0.5
    EXPECT_FALSE(m[1].contains("emission"));
    EXPECT_EQ(doc["shapes"][0]["flip_normals"], true);
    EXPECT_FALSE(doc["shapes"][1].contains("flip_normals"));
    EXPECT_EQ(doc["shapes"][1]["material"], "pbrt-default");
}

TEST(PbrtImport, AnAreaLightsPowerIsEveryTrianglesAsInPbrt) {
    // pbrt-v4 makes each triangle a light normalised by its own area: a unit
    // quad (two triangles of area 1/2) given power pi has radiance
    // pi / (pi x 1/2) = 2, not pi / (pi x 1) = 1.
    const std::string quad =
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0 0 1 0] \"integer indices\" [0 1 2 0 2 3]\n";
    const json doc = document(scene("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"float power\" " +
                                    std::to_string(M_PI) + "\n" + quad + "AttributeEnd\n"));
    EXPECT_NEAR(doc["materials"][0]["emission"].get<double>(), 2.0, 1e-5);
    // Triangles of different areas would each get their own radiance.
    EXPECT_THAT(errorOf(scene("AttributeBegin\nAreaLightSource \"diffuse\" \"float power\" 10\n"
                              "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0 0 3 0] "
                              "\"integer indices\" [0 1 2 0 2 3]\nAttributeEnd\n")),
                HasSubstr("power on triangles that differ in area is not supported"));
    // A sphere's area is pbrt's 4 pi r^2, in object space; a patch's is its
    // surface integral (a flat unit square: 1).
    const json sphere = document(scene("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"float power\" 8\n"
                                       "Scale 5 5 5\nShape \"sphere\" \"float radius\" 2\nAttributeEnd\n"));
    EXPECT_NEAR(sphere["materials"][0]["emission"].get<double>(), 8.0 / (M_PI * 4.0 * M_PI * 4.0), 1e-6);
    const json patch = document(scene("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"float power\" 3\n"
                                      "Shape \"bilinearmesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]\nAttributeEnd\n"));
    EXPECT_NEAR(patch["materials"][0]["emission"].get<double>(), 3.0 / M_PI, 1e-5);
}

// A w x h image of one value per channel: float EXR, or 8-bit PNG (sRGB-encoded).
void writeFlatImage(const fs::path& file, int w, int h, glm::vec3 value, bool eightBit = false) {
    std::vector<float> pixels;
    for (int i = 0; i < w * h; ++i) pixels.insert(pixels.end(), {value.r, value.g, value.b});
    auto out = OIIO::ImageOutput::create(file.string());
    const OIIO::TypeDesc type = eightBit ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    ASSERT_TRUE(out && out->open(file.string(), OIIO::ImageSpec(w, h, 3, type)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
}

TEST(PbrtImport, AnImageOnAnAreaLightIsTexturedEmission) {
    // pbrt-v4 emits scale x the image at (u, 1 - v), clamped at the borders;
    // with "power", k_e is pi x area x the image's mean luminance.
    const fs::path dir = test::scratchDir("pbrt-image-area-light");
    writeFlatImage(dir / "glow.exr", 4, 2, {1.0f, 2.0f, 3.0f});
    const std::string quad =
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0 0 1 0] \"point2 uv\" [0 0 1 0 1 1 0 1] "
        "\"integer indices\" [0 1 2 0 2 3]\n";
    const auto emissionOf = [&](const std::string& light) {
        return document(scene("AttributeBegin\nAreaLightSource \"diffuse\" " + light + "\n" + quad + "AttributeEnd\n"),
                        dir / "scene.pbrt")["materials"][0]["emission"];
    };
    const json plain = emissionOf("\"string filename\" \"glow.exr\" \"float scale\" 2");
    EXPECT_EQ(plain["texture"], "glow.exr");
    EXPECT_EQ(plain["wrap"], "clamp");
    EXPECT_EQ(plain["filter"], "bilinear");
    EXPECT_EQ(plain["scale"], 2.0);
    // Power pi on triangles of area 1/2: scale = pi / (pi x 1/2 x Y), Y the
    // image's luminance.
    const double Y = 0.2126729 * 1.0 + 0.7151522 * 2.0 + 0.0721750 * 3.0;
    const json powered = emissionOf("\"string filename\" \"glow.exr\" \"float power\" " + std::to_string(M_PI));
    EXPECT_NEAR(powered["scale"].get<double>(), 2.0 / Y, 1e-5);
    // An 8-bit PNG is decoded from sRGB, as the texture system reads it: 128
    // is 0.21586 in linear.
    writeFlatImage(dir / "glow.png", 2, 2, {128.0f / 255.0f, 128.0f / 255.0f, 128.0f / 255.0f}, true);
    const json png = emissionOf("\"string filename\" \"glow.png\" \"float power\" " + std::to_string(M_PI));
    EXPECT_NEAR(png["scale"].get<double>(), 2.0 / 0.2158605, 1e-4);
    // The scene builds, each triangle a light.
    const SceneDesc d =
        SceneDocument::fromText(scene("AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"glow.exr\"\n" +
                                      quad + "AttributeEnd\n"),
                                dir / "scene.pbrt")
            .parse();
    const BuiltScene built = buildScene(d, BuildOptions{});
    EXPECT_EQ(built.world.lightSet.lights().size(), 2u);

    EXPECT_THAT(errorOf(scene("AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"glow.exr\" "
                              "\"rgb L\" [1 1 1]\n" + quad + "AttributeEnd\n"),
                        dir / "scene.pbrt"),
                HasSubstr("give either L or filename"));
    writeFlatImage(dir / "black.exr", 2, 2, {0.0f, 0.0f, 0.0f});
    EXPECT_THAT(errorOf(scene("AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"black.exr\" "
                              "\"float power\" 1\n" + quad + "AttributeEnd\n"),
                        dir / "scene.pbrt"),
                HasSubstr("the image is black: no scale gives it a power"));
    EXPECT_THAT(errorOf(scene("AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"none.exr\"\n" +
                              quad + "AttributeEnd\n"),
                        dir / "scene.pbrt"),
                HasSubstr("no such file 'none.exr'"));
}

TEST(PbrtImport, PowerOnPlymeshAndLoopsubdivLights) {
    // A PLY of two triangles of area 1/2 each (a unit square cut in two),
    // scaled by 2: each triangle has area 2 in the world, so power 4 pi gives
    // radiance 4 pi / (pi x 2) = 2, as pbrt lights each triangle.
    const fs::path dir = test::scratchDir("pbrt-power-ply");
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                               "property float z\nelement face ";
    test::writeFile(dir / "tris.ply", header + "2\nproperty list uchar int vertex_indices\nend_header\n"
                                               "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
    test::writeFile(dir / "quad.ply", header + "1\nproperty list uchar int vertex_indices\nend_header\n"
                                               "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    const auto light = [](const std::string& shape) {
        return scene("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"float power\" " +
                     std::to_string(4.0 * M_PI) + "\nScale 2 2 2\n" + shape + "AttributeEnd\n");
    };
    const json doc = document(light("Shape \"plymesh\" \"string filename\" \"tris.ply\"\n"), dir / "scene.pbrt");
    EXPECT_NEAR(doc["materials"][0]["emission"].get<double>(), 2.0, 1e-5);
    // pbrt makes a PLY's quad one bilinear patch with that power, strahl two
    // triangles: refused rather than given twice the light.
    EXPECT_THAT(errorOf(light("Shape \"plymesh\" \"string filename\" \"quad.ply\"\n"), dir / "scene.pbrt"),
                HasSubstr("power on a plymesh with quads is not supported"));
    // loopsubdiv: the subdivided triangles are the lights; an octahedron's
    // differ in area after one level, which pbrt would light unevenly.
    const std::string octahedron =
        "Shape \"loopsubdiv\" \"integer levels\" 1 \"point3 P\" [1 0 0 -1 0 0 0 1 0 0 -1 0 0 0 1 0 0 -1] "
        "\"integer indices\" [0 2 4 2 1 4 1 3 4 3 0 4 2 0 5 1 2 5 3 1 5 0 3 5]\n";
    EXPECT_THAT(errorOf(light(octahedron), dir / "scene.pbrt"),
                HasSubstr("power on triangles that differ in area is not supported"));
}

TEST(PbrtImport, CheckerboardsKeepPbrtsParity) {
    // pbrt: tex1 where floor(8u) + floor(8v) is even; strahl counts rows from
    // the top (1 - v), which swaps the parity for an even vscale.
    json doc = document(scene("Texture \"c\" \"spectrum\" \"checkerboard\" \"float uscale\" 8 \"float vscale\" 8 "
                              "\"rgb tex1\" [1 1 1] \"rgb tex2\" [0 0 0]\nMaterial \"diffuse\" \"texture reflectance\" \"c\"\n" +
                              kTriangle));
    const json& c = doc["materials"][0]["color"]["checkerboard"];
    EXPECT_EQ(c["color0"], 0.0);
    EXPECT_EQ(c["color1"], 1.0);
    EXPECT_EQ(c["scale"][0], 4.0);
    doc = document(scene("Texture \"c\" \"spectrum\" \"checkerboard\" \"float uscale\" 3 \"float vscale\" 3 "
                         "\"rgb tex1\" [1 1 1] \"rgb tex2\" [0 0 0]\nMaterial \"diffuse\" \"texture reflectance\" \"c\"\n" +
                         kTriangle));
    EXPECT_EQ(doc["materials"][0]["color"]["checkerboard"]["color0"], 1.0);
}

TEST(PbrtImport, MixTexturesBecomeMixInputs) {
    // pbrt-v4: (1 - amount) tex1 + amount tex2; the amount may itself be a
    // texture, and tex1, tex2 values or textures (defaults 0, 1, 0.5).
    json doc = document(scene(
        "Texture \"c\" \"spectrum\" \"checkerboard\" \"rgb tex1\" [1 1 1] \"rgb tex2\" [0 0 0]\n"
        "Texture \"mask\" \"float\" \"mix\" \"float tex1\" 0.2 \"float tex2\" 0.6\n"
        "Texture \"m\" \"spectrum\" \"mix\" \"texture tex1\" \"c\" \"rgb tex2\" [0.1 0.2 0.3] "
        "\"texture amount\" \"mask\"\n"
        "Material \"diffuse\" \"texture reflectance\" \"m\"\n" + kTriangle));
    const json& mix = doc["materials"][0]["color"];
    ASSERT_TRUE(mix.contains("mix")) << mix.dump();
    EXPECT_TRUE(mix["mix"][0].contains("checkerboard"));
    EXPECT_EQ(mix["mix"][1], json::array({0.1, 0.2, 0.3}));
    // A float mix as the amount: tex1 0.2, tex2 0.6, amount 0.5 by default.
    EXPECT_EQ(mix["amount"]["mix"], json::array({0.2, 0.6}));
    EXPECT_EQ(mix["amount"]["amount"], 0.5);
    // The strahl scene parses and builds: the mix is an input like any other.
    const SceneDesc d = SceneDocument::fromText(scene(
        "Texture \"m\" \"spectrum\" \"mix\" \"rgb tex1\" [1 0 0] \"rgb tex2\" [0 0 1] \"float amount\" 0.25\n"
        "Material \"diffuse\" \"texture reflectance\" \"m\"\n" + kTriangle), "scene.pbrt").parse();
    bool found = false;
    for (const auto& m : d.materials)
        if (const auto* diffuse = std::get_if<DiffuseMaterial>(&m.material.kind); diffuse && diffuse->color.mix) {
            found = true;
            EXPECT_EQ(diffuse->color.mix->amount.value, 0.25f);
            EXPECT_EQ(diffuse->color.mix->b.value, Color(0.0f, 0.0f, 1.0f));
        }
    EXPECT_TRUE(found);
    EXPECT_THAT(errorOf(scene("Texture \"m\" \"spectrum\" \"mix\" \"float amount\" 2\n"
                              "Material \"diffuse\" \"texture reflectance\" \"m\"\n" + kTriangle)),
                HasSubstr("\"float amount\": an amount outside [0, 1] is not supported"));
    EXPECT_THAT(errorOf(scene("Texture \"d\" \"spectrum\" \"directionmix\"\n"
                              "Material \"diffuse\" \"texture reflectance\" \"d\"\n" + kTriangle)),
                HasSubstr("this texture is not supported (imagemap, constant, scale, mix, checkerboard)"));
}

TEST(PbrtImport, IncludesSpliceFilesInAndCyclesAreRefused) {
    const fs::path dir = test::scratchDir("pbrt-include");
    test::writeFile(dir / "geometry.pbrt", "# the geometry\n" + kTriangle);
    test::writeFile(dir / "scene.pbrt", scene("Include \"geometry.pbrt\"\nImport \"geometry.pbrt\"\n"));
    EXPECT_EQ(SceneDocument::read(dir / "scene.pbrt").parse().shapes.size(), 2u);
    test::writeFile(dir / "loop.pbrt", scene("Include \"loop.pbrt\"\n"));
    EXPECT_THAT(test::errorMessage([&] { SceneDocument::read(dir / "loop.pbrt"); }),
                HasSubstr("loop.pbrt:6: Include \"loop.pbrt\": the file includes itself (a cycle)"));
    test::writeFile(dir / "missing.pbrt", scene("Include \"nowhere.pbrt\"\n"));
    EXPECT_THAT(test::errorMessage([&] { SceneDocument::read(dir / "missing.pbrt"); }),
                HasSubstr("missing.pbrt:6: Include \"nowhere.pbrt\": cannot open"));
}

TEST(PbrtImport, MalformedOrUnsupportedInputIsOneErrorWithItsLine) {
    EXPECT_THAT(errorOf(scene("Frobnicate 1 2 3\n")), HasSubstr("scene.pbrt:6: unknown directive 'Frobnicate'"));
    EXPECT_THAT(errorOf(scene("AttributeBegin\n" + kTriangle)),
                HasSubstr("scene.pbrt:6: AttributeBegin without a matching AttributeEnd"));
    EXPECT_THAT(errorOf(scene("AttributeEnd\n")), HasSubstr("scene.pbrt:6: AttributeEnd without a matching AttributeBegin"));
    EXPECT_THAT(errorOf(scene("Shape \"sphere\" \"float radius\" \"big\"\n")),
                HasSubstr("scene.pbrt:6: \"float radius\": expected a number, got '\"big\"'"));
    EXPECT_THAT(errorOf(scene("Shape \"sphere\" \"integer radius\" 1.5\n")),
                HasSubstr("scene.pbrt:6: \"integer radius\": expected an integer"));
    EXPECT_THAT(errorOf(scene("Shape \"sphere\" \"quaternion q\" [1 2 3 4]\n")),
                HasSubstr("unknown parameter type 'quaternion'"));
    EXPECT_THAT(errorOf(scene("Shape \"sphere\" \"float radius\" [1 2")), HasSubstr("the file ends where ] should follow"));
    EXPECT_THAT(errorOf(scene("Shape \"sphere\" \"string name\" \"open")), HasSubstr("a string runs past the end of its line"));
    EXPECT_THAT(errorOf(scene("Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0] \"string type\" \"ribbon\"\n")),
                HasSubstr("scene.pbrt:6: Shape \"curve\": a ribbon needs \"normal N\" with two normals, at the curve's start and end"));
    EXPECT_THAT(errorOf(scene("Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0]\n")),
                HasSubstr("scene.pbrt:6: \"point3 P\": a Bezier curve of degree 3 needs 3k + 1 points (got 3)"));
    EXPECT_THAT(errorOf(scene("Shape \"sphere\" \"float radius\" 1 \"float wobble\" 2\n")),
                HasSubstr("scene.pbrt:6: Shape \"sphere\": parameter \"float wobble\" is not supported"));
    EXPECT_THAT(errorOf(scene("Material \"measured\" \"string filename\" \"x.bsdf\"\n" + kTriangle)),
                HasSubstr("scene.pbrt:6: Material \"measured\": this material is not supported"));
    EXPECT_THAT(errorOf(scene("MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\n")),
                HasSubstr("scene.pbrt:6: MakeNamedMedium: participating media are not supported"));
    EXPECT_THAT(errorOf(scene("LightSource \"goniometric\"\n" + kTriangle)),
                HasSubstr("scene.pbrt:6: LightSource \"goniometric\": this light is not supported"));
    EXPECT_THAT(errorOf(scene("ActiveTransform EndTime\nTranslate 1 0 0\nActiveTransform All\n"
                              "LightSource \"point\"\n" + kTriangle)),
                HasSubstr("scene.pbrt:9: LightSource: the start and end transforms differ (ActiveTransform): a light "
                          "cannot move in strahl (shapes and object instances can)"));
    EXPECT_THAT(errorOf(scene("ObjectBegin \"o\"\nActiveTransform EndTime\nTranslate 1 0 0\n" + kTriangle +
                              "ObjectEnd\n")),
                HasSubstr("scene.pbrt:9: Shape: the start and end transforms differ (ActiveTransform): a shape inside "
                          "ObjectBegin cannot move"));
    EXPECT_THAT(errorOf("ActiveTransform EndTime\nTranslate 1 0 0\nActiveTransform All\n" + scene(kTriangle)),
                HasSubstr("Camera: the start and end transforms differ (ActiveTransform): the camera cannot move"));
    EXPECT_THAT(errorOf(scene(kTriangle, "Camera \"realistic\"")),
                HasSubstr("Camera \"realistic\": only the perspective and orthographic cameras are supported"));
    EXPECT_THAT(errorOf("Camera \"perspective\"\n" + kTriangle), HasSubstr("Shape must come after WorldBegin"));
    EXPECT_THAT(errorOf("Camera \"perspective\"\n"), HasSubstr("scene.pbrt: the file has no WorldBegin"));
    EXPECT_THAT(errorOf(scene("Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 3]\n")),
                HasSubstr("index 3 is out of range (3 points)"));
    EXPECT_THAT(errorOf(scene(kTriangle, "ColorSpace \"aces2065-1\"")), HasSubstr("strahl renders in sRGB"));
    EXPECT_THAT(errorOf(scene("")), HasSubstr("the scene has no shapes"));
}

// An equal-area square that is 1 where the image's +z is up (z > 0) and 0 below.
void writeUpperHemisphereMap(const fs::path& file, int n, float value = 1.0f) {
    std::vector<float> pixels(size_t(n) * size_t(n) * 3);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const Vec3 d = equalAreaSquareToSphere(
                Vec2((static_cast<float>(x) + 0.5f) / static_cast<float>(n), (static_cast<float>(y) + 0.5f) / static_cast<float>(n)));
            for (int c = 0; c < 3; ++c) pixels[(size_t(y) * n + x) * 3 + c] = d.z > 0.0f ? value : 0.0f;
        }
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out && out->open(file.string(), OIIO::ImageSpec(n, n, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
}

// pbrt's animated transforms (ActiveTransform) become keyframes over strahl's
// frame time, which runs from TransformTimes' start to its end; pbrt turns a
// rotation as a rotation, so a quarter turn gets a keyframe per 10 degrees,
// each pbrt's interpolation at its time. The shutter maps into frame time.
TEST(PbrtImport, AnimatedTransformsBecomeKeyframesAndTheShutterFrameTime) {
    const std::string world =
        "AttributeBegin\nActiveTransform StartTime\nTranslate 0 0 1\nActiveTransform EndTime\n"
        "Translate 2 0 1\nRotate 90 0 0 1\nActiveTransform All\nShape \"sphere\" \"float radius\" 0.5\n"
        "AttributeEnd\nAttributeBegin\nActiveTransform EndTime\nTranslate 0 1 0\nActiveTransform All\n"
        "ObjectInstance \"thing\"\nAttributeEnd\n"
        "ObjectBegin \"thing\"\n" + kTriangle + "ObjectEnd\n";
    const json doc = document("LookAt 0 0 5  0 0 0  0 1 0\nTransformTimes 1 3\n"
                              "Camera \"perspective\" \"float shutteropen\" 1.5 \"float shutterclose\" 4\n"
                              "Film \"rgb\" \"integer xresolution\" 64 \"integer yresolution\" 32\nWorldBegin\n" +
                              world);
    const json& camera = doc["camera"];
    ASSERT_TRUE(camera.contains("shutter")) << camera.dump();
    EXPECT_DOUBLE_EQ(camera["shutter"][0].get<double>(), 0.25);  // (1.5 - 1) / (3 - 1)
    EXPECT_DOUBLE_EQ(camera["shutter"][1].get<double>(), 1.0);   // clamped, as pbrt clamps

    const json* sphere = nullptr;
    const json* instance = nullptr;
    for (const json& shape : doc["shapes"]) {
        if (shape["type"] == "instance") instance = &shape;
        else if (shape.contains("motion")) sphere = &shape;
    }
    ASSERT_TRUE(sphere && instance);
    EXPECT_FALSE(sphere->contains("transform"));
    const json& keys = (*sphere)["motion"];
    ASSERT_EQ(keys.size(), 10u) << "90 degrees in steps of 10";
    // Keyframe k is pbrt's interpolation at k/9: the centre moves on a line
    // (mirrored in x: pbrt_mapping.h), the sphere turns 10 degrees a step.
    for (size_t k = 0; k < keys.size(); ++k) {
        const glm::dmat4 m = matrixOf(json{{"transform", keys[k]}});
        const double f = double(k) / 9.0;
        expectNear(glm::dvec3(m[3]), {-2.0 * f, 0.0, 1.0}, 1e-6);
        const glm::dvec3 axis = glm::dmat3(m) * glm::dvec3(1, 0, 0);
        EXPECT_NEAR(glm::length(axis), 0.5, 1e-6) << "a rotation, not a chord";
        EXPECT_NEAR(std::atan2(axis.y, -axis.x), glm::radians(90.0 * f), 1e-6);
    }
    // A pure translation needs no more than its two ends.
    EXPECT_EQ((*instance)["motion"].size(), 2u);
}

TEST(PbrtImport, AnImageInfiniteLightIsAnEqualAreaMapInTheLightsFrame) {
    const fs::path dir = test::scratchDir("pbrt-envmap");
    writeUpperHemisphereMap(dir / "sky.exr", 64);
    const auto world = [&](const std::string& transform) {
        const SceneDesc d =
            SceneDocument::fromText(scene("AttributeBegin " + transform +
                                          "LightSource \"infinite\" \"string filename\" \"sky.exr\" "
                                          "\"float scale\" 2\nAttributeEnd\n" + kTriangle),
                                    dir / "scene.pbrt")
                .parse();
        return buildScene(d, BuildOptions{});
    };
    {
        // pbrt's +z is up in the map; strahl's world is pbrt's mirrored in x,
        // so +z stays +z.
        const BuiltScene s = world("");
        EXPECT_NEAR(s.world.escapedRadiance(Vec3(0.3f, 0.2f, 0.9f)).r, 2.0f, 1e-4f);
        EXPECT_NEAR(s.world.escapedRadiance(Vec3(-0.3f, 0.2f, -0.9f)).r, 0.0f, 1e-4f);
    }
    {
        // Rotate -90 about x turns the map's +z onto pbrt's (and strahl's) +y.
        const BuiltScene s = world("Rotate -90 1 0 0 ");
        EXPECT_NEAR(s.world.escapedRadiance(Vec3(0.2f, 0.9f, 0.3f)).r, 2.0f, 1e-4f);
        EXPECT_NEAR(s.world.escapedRadiance(Vec3(0.2f, -0.9f, 0.3f)).r, 0.0f, 1e-4f);
    }
    EXPECT_THAT(errorOf(scene("LightSource \"infinite\" \"string filename\" \"sky.exr\" \"rgb L\" [1 1 1]\n" +
                              kTriangle),
                        dir / "scene.pbrt"),
                HasSubstr("give either L or filename"));
}

TEST(PbrtImport, IlluminanceScalesAnImageInfiniteLight) {
    // An upper hemisphere of radiance 1 sends E = π to a surface facing up:
    // "illuminance" 2π makes it radiance 2 (to the map's sampling error),
    // times "scale" 3, as pbrt multiplies both.
    const fs::path dir = test::scratchDir("pbrt-illuminance");
    writeUpperHemisphereMap(dir / "sky.exr", 64);
    const SceneDesc d = SceneDocument::fromText(
                            scene("LightSource \"infinite\" \"string filename\" \"sky.exr\" \"float scale\" 3 "
                                  "\"float illuminance\" 6.2831853\n" +
                                  kTriangle),
                            dir / "scene.pbrt")
                            .parse();
    const BuiltScene s = buildScene(d, BuildOptions{});
    EXPECT_NEAR(s.world.escapedRadiance(Vec3(0.3f, 0.2f, 0.9f)).r, 6.0f, 0.03f);
    // An image dark above the horizon cannot be scaled to any illuminance.
    writeUpperHemisphereMap(dir / "dark.exr", 64, 0.0f);
    EXPECT_THAT(errorOf(scene("LightSource \"infinite\" \"string filename\" \"dark.exr\" \"float illuminance\" 1\n" +
                              kTriangle),
                        dir / "scene.pbrt"),
                HasSubstr("the image sends no light to a surface facing up (+z)"));
}

TEST(PbrtImport, LoopsubdivIsAControlMeshStrahlSubdivides) {
    const std::string octahedron =
        "\"point3 P\" [1 0 0 -1 0 0 0 1 0 0 -1 0 0 0 1 0 0 -1] "
        "\"integer indices\" [0 2 4 2 1 4 1 3 4 3 0 4 2 0 5 1 2 5 3 1 5 0 3 5]\n";
    const json doc = document(scene("Shape \"loopsubdiv\" " + octahedron));
    EXPECT_EQ(doc["shapes"][0]["subdivision"], (json{{"scheme", "loop"}, {"levels", 3}}));
    const SceneDesc d = SceneDocument::fromText(scene("Shape \"loopsubdiv\" \"integer levels\" 2 " + octahedron),
                                                "scene.pbrt")
                            .parse();
    ASSERT_EQ(d.shapes.size(), 1u);
    EXPECT_EQ(d.shapes[0].inlineMesh.triangleCount(), 8u * 16u);
    EXPECT_EQ(d.shapes[0].inlineMesh.normals.size(), d.shapes[0].inlineMesh.vertexCount());
    // The same key in a strahl scene, and its errors.
    const auto jsonError = [](const std::string& extra) {
        return test::errorMessage([&] {
            SceneDocument::fromText(R"({"shapes": [{"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]],
                "indices": [0, 1, 2], "subdivision": {"scheme": "loop")" + extra + "}]}",
                                    "scene.json")
                .parse();
        });
    };
    EXPECT_THAT(jsonError(R"(, "levels": 9})"), HasSubstr("/shapes/0/subdivision/levels: must be between 0 and 8"));
    EXPECT_THAT(jsonError(R"(}, "normals": [[0,0,1],[0,0,1],[0,0,1]])"),
                HasSubstr("/shapes/0/normals: not with 'subdivision'"));
    EXPECT_THAT(jsonError(R"(, "scheme2": 1})"), HasSubstr("unknown key 'scheme2'"));
}

TEST(PbrtImport, ParameterListsTakeBareOrBracketedValuesAndCommentsAnywhere) {
    const json doc = document(scene("# a comment\nShape \"sphere\" # another\n  \"float radius\" [ 2 ]\n"
                                    "Shape \"sphere\" \"float radius\" 3 \"float zmin\" -3\n"
                                    "AttributeBegin AreaLightSource \"diffuse\" \"bool twosided\" \"true\" "
                                    "\"rgb L\" [1 1 1] Shape \"disk\" AttributeEnd\n"));
    EXPECT_EQ(doc["shapes"][0]["type"], "implicit");
    EXPECT_NEAR(matrixOf(doc["shapes"][0])[1][1], 2.0, 0);
    EXPECT_NEAR(matrixOf(doc["shapes"][1])[1][1], 3.0, 0);
    EXPECT_EQ(doc["materials"][1]["two_sided"], true);  // a quoted bool, as pbrt-v3 wrote it
    EXPECT_EQ(doc["shapes"][2]["type"], "parametric");
}

}  // namespace
}  // namespace strahl

namespace strahl {
namespace {

TEST(PbrtImport, CurvesBecomeCubicBezierStrandsExactly) {
    // A cubic B-spline of 5 points (2 segments), width 0.2 -> 0.1, a tube.
    const json doc = document(scene(
        "Shape \"curve\" \"point3 P\" [0 0 0  1 1 0  2 -1 0  3 0 0  4 1 0] \"string basis\" \"bspline\"\n"
        "  \"float width0\" 0.2 \"float width1\" 0.1 \"string type\" \"cylinder\" \"integer splitdepth\" 5\n"
        "Shape \"curve\" \"point3 P\" [0 0 0  1 2 0  2 0 0] \"integer degree\" 2\n"));
    const json& tube = doc["shapes"][0];
    EXPECT_EQ(tube["type"], "curves");
    EXPECT_EQ(tube["basis"], "bezier");
    EXPECT_EQ(tube["profile"], "round");
    const json& p = tube["points"];
    ASSERT_EQ(p.size(), 7u);  // two Bézier segments sharing a point
    // The B-spline's Bézier points: (p0 + 4 p1 + p2) / 6 and (2 p1 + p2) / 3.
    expectNear(vec(p[0]), {1.0, 0.5, 0.0});
    expectNear(vec(p[1]), {4.0 / 3.0, 1.0 / 3.0, 0.0});
    // Radius = width / 2, linear in the curve's parameter: 0.1 at the root,
    // 0.075 half way, 0.05 at the tip.
    EXPECT_NEAR(p[0][3].get<double>(), 0.1, 1e-12);
    EXPECT_NEAR(p[3][3].get<double>(), 0.075, 1e-12);
    EXPECT_NEAR(p[6][3].get<double>(), 0.05, 1e-12);
    // A quadratic Bézier, degree elevated: q0 + 2/3 (q1 − q0), q2 + 2/3 (q1 − q2).
    const json& flat = doc["shapes"][1]["points"];
    EXPECT_EQ(doc["shapes"][1]["profile"], "flat");
    ASSERT_EQ(flat.size(), 4u);
    expectNear(vec(flat[1]), {2.0 / 3.0, 4.0 / 3.0, 0.0});
    expectNear(vec(flat[2]), {4.0 / 3.0, 4.0 / 3.0, 0.0});
    EXPECT_NEAR(flat[2][3].get<double>(), 0.5, 1e-12);  // width 1 by default
    // A ribbon: an oriented strand whose normals are pbrt's slerp from the
    // first N to the second along the whole curve.
    const json ribbon = document(scene("Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0] \"string type\" \"ribbon\"\n"
                                       "  \"normal N\" [0 0 1  0 1 0] \"float width\" 0.2\n"))["shapes"][0];
    EXPECT_EQ(ribbon["profile"], "oriented");
    ASSERT_EQ(ribbon["normals"].size(), 4u);
    expectNear(vec(ribbon["normals"][0]), {0.0, 0.0, 1.0}, 1e-12);
    expectNear(vec(ribbon["normals"][1]), {0.0, 0.5, std::sqrt(0.75)}, 1e-12);  // 30 of 90 degrees
    expectNear(vec(ribbon["normals"][3]), {0.0, 1.0, 0.0}, 1e-12);
    // And the document renders: the world has the two curve shapes.
    const World world = buildWorld(SceneDocument::fromText(scene(
        "Shape \"curve\" \"point3 P\" [0 0 0  1 1 0  2 -1 0  3 0 0] \"float width\" 0.1\n"), "scene.pbrt").parse(),
                                   BuildOptions{});
    ASSERT_EQ(world.shapes.size(), 1u);
    ASSERT_NE(world.shapes[0].user, nullptr);
    EXPECT_NE(world.shapes[0].user->asCurves(), nullptr);
}

}  // namespace
}  // namespace strahl

namespace strahl {
namespace {

TEST(PbrtImport, HairMaterialsKeepPbrtsPrecedence) {
    const json doc = document(scene(
        "Material \"hair\" \"rgb sigma_a\" [0.1 0.2 0.3] \"float eumelanin\" 4 \"float beta_m\" 0.2\n" + kTriangle +
        "Material \"hair\" \"rgb reflectance\" [0.5 0.4 0.3] \"float eta\" 1.6 \"float alpha\" 3\n" + kTriangle +
        "Material \"hair\" \"float pheomelanin\" 2\n" + kTriangle + "Material \"hair\"\n" + kTriangle));
    std::vector<json> hair;
    for (const json& m : doc["materials"])
        if (m["type"] == "hair") hair.push_back(m);
    ASSERT_EQ(hair.size(), 4u);
    EXPECT_EQ(hair[0]["sigma_a"], json({0.1, 0.2, 0.3}));
    EXPECT_FALSE(hair[0].contains("eumelanin"));
    EXPECT_EQ(hair[0]["beta_m"], 0.2);
    EXPECT_EQ(hair[1]["color"], json({0.5, 0.4, 0.3}));
    EXPECT_EQ(hair[1]["ior"], 1.6);
    EXPECT_EQ(hair[1]["alpha"], 3.0);
    EXPECT_EQ(hair[2]["pheomelanin"], 2.0);
    EXPECT_EQ(hair[2]["eumelanin"], 0.0);
    EXPECT_FALSE(hair[3].contains("sigma_a") || hair[3].contains("color") || hair[3].contains("eumelanin"));
}

}  // namespace
}  // namespace strahl
