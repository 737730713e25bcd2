// .mtl material libraries: every MeshMaterial field an OBJ can fill (Kd Ks Ns Ni
// d/Tr illum Tf Ke map_Kd map_Ke norm), texture options, bump maps that are not
// normal maps, the warnings for missing textures and odd values, and the
// materials of the Cornell box, Sponza and Sibenik in ../shared/data.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/meshio/mesh_file.h"
#include "warning_capture.h"
#include "test_support.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace strahl {
namespace {

using test::WarningCapture;
using test::writeFile;

// One triangle per material name, in that order, with `mtl` as m.mtl.
LoadedMesh loadWithMaterials(const fs::path& dir, const std::string& mtl,
                             const std::vector<std::string>& names) {
    writeFile(dir / "m.mtl", mtl);
    std::string obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (const std::string& name : names) obj += "usemtl " + name + "\nf 1 2 3\n";
    writeFile(dir / "t.obj", obj);
    return loadObj(dir / "t.obj");
}

std::map<std::string, MeshMaterial> byName(const LoadedMesh& m) {
    std::map<std::string, MeshMaterial> result;
    for (const MeshMaterial& material : m.materials) result[material.name] = material;
    return result;
}

TEST(ObjMaterial, EveryKeyFillsItsField) {
    const fs::path dir = test::scratchDir("mtl-all-keys");
    writeFile(dir / "tex" / "wood.png", "x");
    writeFile(dir / "glow.png", "x");
    writeFile(dir / "normals.png", "x");
    WarningCapture warnings;
    const LoadedMesh m = loadWithMaterials(
        dir,
        "newmtl all\n"
        "  Kd 0.1 0.2 0.3\n  Ks 0.4 0.5 0.6\n  Ns 250\n  Ni 1.33\n  d 0.25\n  illum 7\n"
        "  Tf 0.7 0.8 0.9\n  Ke 17 12 4\n"
        "  map_Kd -bm 1.0 -o 0.5 0.5 tex/wood.png\n"
        "  map_Ke -clamp on -s 2 2 1 glow.png\n"
        "  norm -bm 1.0 normals.png\n",
        {"all"});
    EXPECT_EQ(warnings.text(), "");
    ASSERT_EQ(m.materials.size(), 1u);
    const MeshMaterial& g = m.materials[0];
    EXPECT_EQ(g.source, MeshMaterial::Source::Obj);
    EXPECT_EQ(g.diffuse, Color(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(g.specular, Color(0.4f, 0.5f, 0.6f));
    EXPECT_FLOAT_EQ(g.shininess, 250.0f);
    EXPECT_FLOAT_EQ(g.ior, 1.33f);
    EXPECT_FLOAT_EQ(g.dissolve, 0.25f);
    EXPECT_EQ(g.illum, 7);
    EXPECT_EQ(g.transmission, Color(0.7f, 0.8f, 0.9f));
    EXPECT_EQ(g.emission, Color(17.0f, 12.0f, 4.0f));
    EXPECT_EQ(g.diffuseTexture, dir / "tex" / "wood.png");
    EXPECT_EQ(g.emissionTexture, dir / "glow.png");
    EXPECT_EQ(g.normalTexture, dir / "normals.png");
    EXPECT_TRUE(g.metallicRoughnessTexture.empty());
}

TEST(ObjMaterial, DefaultsWithoutStatements) {
    const LoadedMesh m =
        loadWithMaterials(test::scratchDir("mtl-defaults"), "newmtl bare\n", {"bare"});
    ASSERT_EQ(m.materials.size(), 1u);
    const MeshMaterial& g = m.materials[0];
    EXPECT_EQ(g.diffuse, Color(0.8f));
    EXPECT_EQ(g.specular, Color(0.0f));
    EXPECT_FLOAT_EQ(g.shininess, 0.0f);
    EXPECT_FLOAT_EQ(g.ior, 1.5f);
    EXPECT_FLOAT_EQ(g.dissolve, 1.0f);
    EXPECT_EQ(g.illum, 2);
    EXPECT_EQ(g.transmission, Color(0.0f));
    EXPECT_EQ(g.emission, Color(0.0f));
}

TEST(ObjMaterial, TrIsOneMinusDissolveAndDWinsOverTr) {
    const LoadedMesh m = loadWithMaterials(test::scratchDir("mtl-tr"),
                                           "newmtl tr\nTr 0.2\n"
                                           "newmtl dFirst\nd 0.9\nTr 0.5\n"
                                           "newmtl trFirst\nTr 0.5\nd 0.9\n"
                                           "newmtl halo\nd -halo 0.4\n"
                                           "newmtl grey\nKs 0.5\nTf 0.25\n",
                                           {"tr", "dFirst", "trFirst", "halo", "grey"});
    const auto materials = byName(m);
    EXPECT_FLOAT_EQ(materials.at("tr").dissolve, 0.8f);
    EXPECT_FLOAT_EQ(materials.at("dFirst").dissolve, 0.9f);
    EXPECT_FLOAT_EQ(materials.at("trFirst").dissolve, 0.9f);
    EXPECT_FLOAT_EQ(materials.at("halo").dissolve, 0.4f);
    EXPECT_EQ(materials.at("grey").specular, Color(0.5f));
    EXPECT_EQ(materials.at("grey").transmission, Color(0.25f));
}

TEST(ObjMaterial, BumpMapsAreHeightMapsNotNormalMapsAndAreIgnoredSilently) {
    const fs::path dir = test::scratchDir("mtl-bump");
    writeFile(dir / "height.png", "x");
    WarningCapture warnings;
    const LoadedMesh m = loadWithMaterials(dir,
                                           "newmtl a\nmap_Bump -bm 1.0 height.png\n"
                                           "newmtl b\nbump height.png\n"
                                           "newmtl c\nmap_bump missing.png\n",
                                           {"a", "b", "c"});
    EXPECT_EQ(warnings.text(), "");
    ASSERT_EQ(m.materials.size(), 3u);
    for (const MeshMaterial& g : m.materials) EXPECT_TRUE(g.normalTexture.empty()) << g.name;
}

TEST(ObjMaterial, MissingTexturesWarnWithTheMtlLineAndStayEmpty) {
    const fs::path dir = test::scratchDir("mtl-missing-textures");
    WarningCapture warnings;
    const LoadedMesh m = loadWithMaterials(dir,
                                           "newmtl lamp\n"
                                           "map_Kd -bm 0.5 gone.png\n"
                                           "map_Ke -o 1 1 1 glow.png\n"
                                           "norm -bm 1.0 flat.png\n",
                                           {"lamp"});
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_TRUE(m.materials[0].diffuseTexture.empty());
    EXPECT_TRUE(m.materials[0].emissionTexture.empty());
    EXPECT_TRUE(m.materials[0].normalTexture.empty());
    const std::string mtl = (dir / "m.mtl").string();
    EXPECT_THAT(warnings.text(), HasSubstr(mtl + ":2: texture 'gone.png' not found; material "
                                                 "'lamp' gets no diffuse texture"));
    EXPECT_THAT(warnings.text(), HasSubstr(mtl + ":3: texture 'glow.png' not found; material "
                                                 "'lamp' gets no emission texture"));
    EXPECT_THAT(warnings.text(), HasSubstr(mtl + ":4: texture 'flat.png' not found; material "
                                                 "'lamp' gets no normal texture"));
}

TEST(ObjMaterial, OutOfRangeValuesWarnAndFallBack) {
    const fs::path dir = test::scratchDir("mtl-ranges");
    WarningCapture warnings;
    const LoadedMesh m = loadWithMaterials(dir,
                                           "newmtl odd\nd 1.5\nNi 0\nNs -3\nillum 12\n"
                                           "newmtl clear\nTr -1\n",
                                           {"odd", "clear"});
    const auto materials = byName(m);
    const MeshMaterial& odd = materials.at("odd");
    EXPECT_FLOAT_EQ(odd.dissolve, 1.0f);
    EXPECT_FLOAT_EQ(odd.ior, 1.5f);
    EXPECT_FLOAT_EQ(odd.shininess, 0.0f);
    EXPECT_EQ(odd.illum, 2);
    EXPECT_FLOAT_EQ(materials.at("clear").dissolve, 1.0f);
    const std::string mtl = (dir / "m.mtl").string();
    EXPECT_THAT(warnings.text(), HasSubstr(mtl + ":2: d 1.5 is outside [0, 1]; using 1"));
    EXPECT_THAT(warnings.text(), HasSubstr(mtl + ":3: Ni 0 is not positive; using 1.5"));
    EXPECT_THAT(warnings.text(), HasSubstr(mtl + ":4: Ns -3 is negative; using 0"));
    EXPECT_THAT(warnings.text(), HasSubstr(mtl + ":5: illum 12 is not a model 0..10; using 2"));
    EXPECT_THAT(warnings.text(), HasSubstr(mtl + ":7: Tr -1 is outside [0, 1]; using 0"));
}

struct BadMtl {
    const char* name;
    const char* mtl;
    const char* error;  // expected after "m.mtl:"
};

// Test names print the case's name (not its bytes, padding included).
void PrintTo(const BadMtl& bad, std::ostream* out) {
    *out << bad.name;
}

class ObjMaterialErrors : public ::testing::TestWithParam<BadMtl> {};

TEST_P(ObjMaterialErrors, NameTheMtlLine) {
    const BadMtl& bad = GetParam();
    const fs::path dir = test::scratchDir(std::string("mtl-bad-") + bad.name);
    const std::string message = test::errorMessage([&] { loadWithMaterials(dir, bad.mtl, {"m"}); });
    EXPECT_THAT(message, HasSubstr((dir / "m.mtl").string() + ":" + bad.error));
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, ObjMaterialErrors,
    ::testing::Values(BadMtl{"ks", "newmtl m\nKs 1 x 0\n", "2: cannot parse Ks 'x' as a number"},
                      BadMtl{"tf", "newmtl m\nTf spectral file.rfl\n",
                             "2: cannot parse Tf 'spectral' as a number"},
                      BadMtl{"ns", "newmtl m\nNs\n", "2: missing Ns"},
                      BadMtl{"ni_extra", "newmtl m\nNi 1.5 2\n",
                             "2: unexpected '2' at the end of the Ni statement"},
                      BadMtl{"d_halo", "newmtl m\nd -halo\n", "2: missing d"},
                      BadMtl{"illum", "newmtl m\nillum two\n",
                             "2: cannot parse illum 'two' as a number"},
                      BadMtl{"norm", "newmtl m\nnorm -bm 1.0\n", "2: norm without a file name"},
                      BadMtl{"map_ke", "newmtl m\nmap_Ke\n", "2: map_Ke without a file name"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

// ------------------------------------------------------------------ shared data

TEST(ObjMaterialSharedData, CornellBoxOriginalLightHasKe) {
    STRAHL_REQUIRE_SHARED_DATA();
    WarningCapture warnings;
    const LoadedMesh m =
        loadObj(test::sharedData() / "cornell-box-mcguire" / "CornellBox-Original.obj");
    EXPECT_EQ(warnings.text(), "");
    const auto materials = byName(m);
    ASSERT_EQ(materials.count("light"), 1u);
    const MeshMaterial& light = materials.at("light");
    EXPECT_EQ(light.emission, Color(17.0f, 12.0f, 4.0f));
    EXPECT_EQ(light.diffuse, Color(0.78f));
    const MeshMaterial& left = materials.at("leftWall");
    EXPECT_EQ(left.diffuse, Color(0.63f, 0.065f, 0.05f));
    EXPECT_EQ(left.specular, Color(0.0f));
    EXPECT_EQ(left.emission, Color(0.0f));
    EXPECT_FLOAT_EQ(left.shininess, 10.0f);
    EXPECT_FLOAT_EQ(left.ior, 1.5f);
    EXPECT_EQ(left.illum, 2);
    // Only the light emits.
    for (const auto& [name, material] : materials) {
        if (name != "light") {
            EXPECT_EQ(material.emission, Color(0.0f)) << name;
        }
    }
}

TEST(ObjMaterialSharedData, CornellBoxSphereHasAMirrorAndAGlass) {
    STRAHL_REQUIRE_SHARED_DATA();
    WarningCapture warnings;  // the file mixes corners with and without uvs
    const LoadedMesh m =
        loadObj(test::sharedData() / "cornell-box-mcguire" / "CornellBox-Sphere.obj");
    EXPECT_THAT(warnings.text(), ::testing::Not(HasSubstr("mtl")));
    const auto materials = byName(m);
    const MeshMaterial& mirror = materials.at("leftSphere");
    EXPECT_EQ(mirror.illum, 5);
    EXPECT_EQ(mirror.specular, Color(0.95f));
    EXPECT_FLOAT_EQ(mirror.shininess, 1000.0f);
    const MeshMaterial& glass = materials.at("rightSphere");
    EXPECT_EQ(glass.illum, 7);
    EXPECT_FLOAT_EQ(glass.ior, 2.5f);
    EXPECT_EQ(glass.transmission, Color(0.1f));
}

class SharedBumpScenes : public ::testing::TestWithParam<const char*> {};

// Sponza and Sibenik name grey height maps with bump / map_bump: none may turn
// into a normal map, and every map_Kd resolves without a warning.
TEST_P(SharedBumpScenes, BumpMapsAreNotNormalMapsAndDissolveIsRead) {
    STRAHL_REQUIRE_SHARED_DATA();
    const fs::path obj = test::sharedData() / GetParam();
    fs::path mtl = obj;
    mtl.replace_extension(".mtl");
    ASSERT_THAT(test::readFile(mtl), HasSubstr("bump"));
    WarningCapture warnings;
    const LoadedMesh m = loadObj(obj);
    EXPECT_THAT(warnings.text(), ::testing::Not(HasSubstr("not found")));
    ASSERT_FALSE(m.materials.empty());
    size_t textured = 0;
    for (const MeshMaterial& g : m.materials) {
        EXPECT_TRUE(g.normalTexture.empty()) << g.name;
        EXPECT_TRUE(g.emissionTexture.empty()) << g.name;
        EXPECT_GE(g.dissolve, 0.0f);
        EXPECT_LE(g.dissolve, 1.0f);
        if (!g.diffuseTexture.empty()) {
            EXPECT_TRUE(fs::is_regular_file(g.diffuseTexture)) << g.name;
            ++textured;
        }
    }
    EXPECT_GT(textured, 0u);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SharedBumpScenes,
                         ::testing::Values("sponza-dabrovic/sponza.obj", "sibenik/sibenik.obj"),
                         [](const auto& testInfo) {
                             const std::string path = testInfo.param;
                             return path.substr(0, path.find_first_of("-/"));
                         });

}  // namespace
}  // namespace strahl
