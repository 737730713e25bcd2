// OBJ + MTL loader: index forms, triangulation, vertex unification, materials,
// and the "file:line: what" errors of malformed input.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "strahl/core/error.h"
#include "strahl/meshio/mesh_file.h"
#include "test_support.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

namespace strahl {
namespace {

using test::writeFile;

LoadedMesh loadObjText(const std::string& test, const std::string& text) {
    const fs::path file = test::scratchDir(test) / "mesh.obj";
    writeFile(file, text);
    return loadObj(file);
}

// Three corners with distinct positions, uvs and normals, so a mix-up shows.
const std::string kAttributes =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    "vt 0.25 0.5\nvt 0.75 0.5\nvt 0.5 1\n"
    "vn 1 0 0\nvn 0 1 0\nvn 0 0 1\n";

struct IndexForm {
    const char* name;
    const char* face;
    bool uvs;
    bool normals;
};

class ObjIndexForm : public ::testing::TestWithParam<IndexForm> {};

TEST_P(ObjIndexForm, GivesOneTriangleWithTheRightAttributes) {
    const IndexForm& form = GetParam();
    const LoadedMesh m = loadObjText(std::string("obj-form-") + form.name, kAttributes + form.face);
    ASSERT_EQ(m.mesh.triangleCount(), 1u);
    ASSERT_EQ(m.mesh.vertexCount(), 3u);
    EXPECT_EQ(m.mesh.uvs.empty(), !form.uvs);
    EXPECT_EQ(m.mesh.normals.empty(), !form.normals);
    const Vec3 positions[] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const Vec2 uvs[] = {{0.25f, 0.5f}, {0.75f, 0.5f}, {0.5f, 1.0f}};
    const Vec3 normals[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int k = 0; k < 3; ++k) {
        const uint32_t i = m.mesh.indices[size_t(k)];
        EXPECT_EQ(m.mesh.positions[i], positions[k]) << "corner " << k;
        if (form.uvs) {
            EXPECT_EQ(m.mesh.uvs[i], uvs[k]) << "corner " << k;
        }
        if (form.normals) {
            EXPECT_EQ(m.mesh.normals[i], normals[k]) << "corner " << k;
        }
    }
    EXPECT_TRUE(m.materials.empty());
    EXPECT_TRUE(m.mesh.faceMaterials.empty());
}

INSTANTIATE_TEST_SUITE_P(
    AllForms, ObjIndexForm,
    ::testing::Values(IndexForm{"v", "f 1 2 3\n", false, false},
                      IndexForm{"v_vt", "f 1/1 2/2 3/3\n", true, false},
                      IndexForm{"v__vn", "f 1//1 2//2 3//3\n", false, true},
                      IndexForm{"v_vt_vn", "f 1/1/1 2/2/2 3/3/3\n", true, true},
                      IndexForm{"negative", "f -3/-3/-3 -2/-2/-2 -1/-1/-1\n", true, true},
                      IndexForm{"negative_vn", "f -3//-3 -2//-2 -1//-1\n", false, true},
                      IndexForm{"blanks_crlf", "f\t1/1/1 \t2/2/2   3/3/3  \r\n", true, true},
                      IndexForm{"no_final_newline", "f 1/1 2/2 3/3", true, false}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(ObjLoader, NegativeIndicesCountFromTheVerticesDefinedSoFar) {
    const LoadedMesh m = loadObjText("obj-relative",
                                     "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                                     "v 0 0 5\nv 1 0 5\nv 0 1 5\nf -3 -2 -1\n");
    ASSERT_EQ(m.mesh.triangleCount(), 2u);
    for (size_t k = 3; k < 6; ++k) EXPECT_EQ(m.mesh.positions[m.mesh.indices[k]].z, 5.0f);
    for (size_t k = 0; k < 3; ++k) EXPECT_EQ(m.mesh.positions[m.mesh.indices[k]].z, 0.0f);
}

TEST(ObjLoader, PolygonsAreFanTriangulated) {
    const LoadedMesh m = loadObjText("obj-fan",
                                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\n"
                                     "f 1 2 3 4\nf 1 2 3 4 5\n");
    ASSERT_EQ(m.mesh.triangleCount(), 2u + 3u);
    EXPECT_EQ(m.mesh.vertexCount(), 5u);
    // Positions of the fan (0,i,i+1) of each polygon, in order.
    const int expected[][3] = {{0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
    const Vec3 input[] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 0.5f, 0}};
    for (size_t t = 0; t < 5; ++t) {
        for (size_t k = 0; k < 3; ++k)
            EXPECT_EQ(m.mesh.positions[m.mesh.indices[3 * t + k]], input[expected[t][k]])
                << "triangle " << t << " corner " << k;
    }
}

TEST(ObjLoader, CornersAreUnifiedPerDistinctIndexTriple) {
    const LoadedMesh m = loadObjText("obj-unify",
                                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 9 9 9\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                     "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"  // shares two corners
                                     "f 1/4 2/2 3/3\n");               // position 1 with a new uv
    ASSERT_EQ(m.mesh.triangleCount(), 3u);
    EXPECT_EQ(m.mesh.vertexCount(), 5u);  // the unused "v 9 9 9" is not output
    EXPECT_EQ(m.mesh.indices[0], m.mesh.indices[3]);
    EXPECT_EQ(m.mesh.indices[2], m.mesh.indices[4]);
    EXPECT_NE(m.mesh.indices[6], m.mesh.indices[0]);
    EXPECT_EQ(m.mesh.positions[m.mesh.indices[6]], m.mesh.positions[m.mesh.indices[0]]);
    EXPECT_EQ(m.mesh.uvs[m.mesh.indices[6]], Vec2(0, 1));
}

TEST(ObjLoader, AttributeOnOnlySomeCornersIsDroppedForTheWholeMesh) {
    ::testing::internal::CaptureStderr();
    const LoadedMesh m =
        loadObjText("obj-mixed",
                    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvn 0 1 0\nvt 0 0\n"
                    "f 1/1/1 2/1/1 3/1/1\n"
                    "f 1//2 3//1 4//1\n");
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_TRUE(m.mesh.uvs.empty());
    EXPECT_FALSE(m.mesh.normals.empty());
    // Corner 1 came as 1/1/1 and 1//2: different normals keep them apart; the
    // corners that differed only in their uv are merged again.
    EXPECT_EQ(m.mesh.vertexCount(), 5u);
    EXPECT_EQ(m.mesh.indices[2], m.mesh.indices[4]);
    EXPECT_THAT(warnings, HasSubstr("strahl: warning: "));
    EXPECT_THAT(warnings, HasSubstr("mesh.obj: only some face corners have texture coordinates"));
    EXPECT_THAT(warnings, Not(HasSubstr("normals")));
}

TEST(ObjLoader, IgnoresGroupingAndNonSurfaceStatementsSilently) {
    ::testing::internal::CaptureStderr();
    const LoadedMesh m = loadObjText("obj-ignored",
                                     "# comment\n\n   \no thing\ng a b\ns 1\ns off\n"
                                     "v 0 0 0 1\nv 1 0 0 0.5 0.5 0.5   # w, then a vertex colour\n"
                                     "v 0 1 0\nvp 0.5\nvt 0.5\n"
                                     "l 1 2\np 3\nf 1 2 3 # trailing comment\n");
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    EXPECT_EQ(m.mesh.triangleCount(), 1u);
    EXPECT_EQ(m.mesh.positions[m.mesh.indices[1]], Vec3(1, 0, 0));
}

TEST(ObjLoader, UnsupportedStatementWarnsOncePerKeyword) {
    ::testing::internal::CaptureStderr();
    const LoadedMesh m = loadObjText(
        "obj-unsupported", "v 0 0 0\nv 1 0 0\nv 0 1 0\ncstype bspline\ncstype bezier\nf 1 2 3\n");
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(m.mesh.triangleCount(), 1u);
    EXPECT_THAT(warnings, HasSubstr("mesh.obj:4: ignoring unsupported statement 'cstype'"));
    EXPECT_EQ(warnings.find("cstype"), warnings.rfind("cstype"));
}

TEST(ObjLoader, MaterialsFromSeveralLibrariesWithCaseInsensitiveTextures) {
    const fs::path dir = test::scratchDir("obj-materials");
    writeFile(dir / "lib" / "a.mtl",
              "# library a\nKd 0.1 0.1 0.1\n"  // before any newmtl: ignored
              "newmtl red\n\tKd 1 0 0\n\tNs 10\n\tillum 2\n"
              "newmtl textured\n  Kd 0.5\n  map_Kd -bm 0.5 -o 0.1 0.2 Tex\\Wood.PNG\n"
              "newmtl two words\nKd 0 0 1\n");
    writeFile(dir / "lib" / "tex" / "wood.png", "not really a png");
    writeFile(dir / "b.mtl",
              "newmtl glow\r\nKd 0 0 0\r\nKe 1 2 3\r\n"
              "newmtl red\r\nKd 0 1 0\r\n");  // a second "red": the first one wins
    writeFile(dir / "scene.obj",
              "mtllib lib/a.mtl B.MTL\n"
              "mtllib Missing.mtl\n"
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
              "f 1 2 3\n"              // no material yet: default slot 0
              "usemtl red\nf 1 2 3\n"  // slot 1
              "usemtl unused\n"        // no face: takes no slot
              "usemtl glow\nf 1 2 4 3\n"
              "usemtl textured\nf 1 2 3\n"
              "usemtl nosuch\nf 1 2 3\n"
              "usemtl red\nf 1 2 3\n"
              "usemtl two words\nf 1 2 3\n");
    ::testing::internal::CaptureStderr();
    const LoadedMesh m = loadObj(dir / "scene.obj");
    const std::string warnings = ::testing::internal::GetCapturedStderr();

    ASSERT_EQ(m.materials.size(), 6u);
    const std::vector<uint32_t> slots = {0, 1, 2, 2, 3, 4, 1, 5};
    EXPECT_EQ(m.mesh.faceMaterials, slots);
    EXPECT_EQ(m.materials[0].name, "");
    EXPECT_EQ(m.materials[0].diffuse, Color(0.8f));
    EXPECT_EQ(m.materials[1].name, "red");
    EXPECT_EQ(m.materials[1].diffuse, Color(1, 0, 0));
    EXPECT_EQ(m.materials[2].name, "glow");
    EXPECT_EQ(m.materials[2].emission, Color(1, 2, 3));
    EXPECT_EQ(m.materials[2].diffuse, Color(0));
    EXPECT_EQ(m.materials[3].diffuse, Color(0.5f));
    EXPECT_TRUE(fs::equivalent(m.materials[3].diffuseTexture, dir / "lib" / "tex" / "wood.png"));
    EXPECT_EQ(m.materials[4].name, "nosuch");
    EXPECT_EQ(m.materials[4].diffuse, Color(0.8f));
    EXPECT_EQ(m.materials[5].name, "two words");
    EXPECT_EQ(m.materials[5].diffuse, Color(0, 0, 1));
    for (size_t i : {0, 1, 2, 4, 5}) EXPECT_TRUE(m.materials[i].diffuseTexture.empty());

    EXPECT_THAT(warnings, HasSubstr("strahl: warning: " + (dir / "scene.obj").string() +
                                    ":2: material library 'Missing.mtl' not found"));
    EXPECT_THAT(warnings, HasSubstr("scene.obj:15: unknown material 'nosuch'"));
    EXPECT_THAT(warnings, Not(HasSubstr("unused")));
}

TEST(ObjLoader, MaterialLibraryMayComeAfterTheFacesUsingIt) {
    const fs::path dir = test::scratchDir("obj-late-mtllib");
    writeFile(dir / "m.mtl", "newmtl late\nKd 0.25 0.5 0.75\nKe 2\n");
    writeFile(dir / "late.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl late\nf 1 2 3\nmtllib m.mtl\n");
    const LoadedMesh m = loadObj(dir / "late.obj");
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.materials[0].diffuse, Color(0.25f, 0.5f, 0.75f));
    EXPECT_EQ(m.materials[0].emission, Color(2.0f));
    EXPECT_EQ(m.mesh.faceMaterials, std::vector<uint32_t>{0});
}

TEST(ObjLoader, MissingTextureWarnsAndLeavesTheMaterialUntextured) {
    const fs::path dir = test::scratchDir("obj-missing-texture");
    writeFile(dir / "m.mtl", "newmtl wood\nKd 1 1 1\nmap_Kd -clamp on nowhere.png\n");
    writeFile(dir / "t.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wood\nf 1 2 3\n");
    ::testing::internal::CaptureStderr();
    const LoadedMesh m = loadObj(dir / "t.obj");
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_TRUE(m.materials[0].diffuseTexture.empty());
    EXPECT_THAT(warnings, HasSubstr("m.mtl:3: texture 'nowhere.png' not found"));
}

struct BadObj {
    const char* name;
    const char* obj;
    const char* expected;  // after "<file>:"
    const char* mtl = nullptr;
};

class ObjErrors : public ::testing::TestWithParam<BadObj> {};

TEST_P(ObjErrors, ThrowWithFileAndLine) {
    const BadObj& bad = GetParam();
    const fs::path dir = test::scratchDir(std::string("obj-error-") + bad.name);
    writeFile(dir / "bad.obj", bad.obj);
    if (bad.mtl) writeFile(dir / "bad.mtl", bad.mtl);
    const std::string place = bad.mtl ? (dir / "bad.mtl").string() : (dir / "bad.obj").string();
    try {
        loadObj(dir / "bad.obj");
        FAIL() << "no error for " << bad.name;
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr(place + ":" + bad.expected));
    }
}

const std::string kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";  // lines 1-3

INSTANTIATE_TEST_SUITE_P(
    Malformed, ObjErrors,
    ::testing::Values(
        BadObj{"letter", "v 1 x 3\n", "1: cannot parse coordinate 'x' as a number"},
        BadObj{"short_v", "v 1 2\n", "1: missing coordinate"},
        BadObj{"suffix", "v 1 2 3q\n", "1: cannot parse coordinate '3q' as a number"},
        BadObj{"nan", "v nan 0 0\n", "1: coordinate 'nan' is not a finite float"},
        BadObj{"inf", "v 0 -inf 0\n", "1: coordinate '-inf' is not a finite float"},
        BadObj{"overflow", "v 0 0 1e39\n", "1: coordinate '1e39' is not a finite float"},
        BadObj{"huge", "v 0 0 1e999\n", "1: coordinate '1e999' is out of range"},
        BadObj{"short_vn", "vn 0 0\n", "1: missing normal coordinate"},
        BadObj{"crlf_line", "v 0 0 0\r\nv 1 0 0\r\nv a 0 0\r\n", "3: cannot parse coordinate 'a'"},
        BadObj{"index0", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
               "4: vertex index 0 is invalid (OBJ indices start at 1)"},
        BadObj{"past_end", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
               "4: vertex index 4 is out of range (3 defined so far)"},
        BadObj{"before_start", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n",
               "4: vertex index -4 is out of range (3 defined so far)"},
        BadObj{"no_vt", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n",
               "4: texture index 1 is out of range (0 defined so far)"},
        BadObj{"vn_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n",
               "5: normal index 2 is out of range (1 defined so far)"},
        BadObj{"two_corners", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",
               "4: face with 2 vertices (needs at least 3)"},
        BadObj{"empty_face", "f\n", "1: face with 0 vertices"},
        BadObj{"corner_suffix", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3x\n",
               "4: malformed face corner '3x'"},
        BadObj{"four_parts", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1/1 2/1/1 3/1/1\n",
               "6: malformed face corner '1/1/1/1'"},
        BadObj{"dangling_slash", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2/ 3/\n",
               "4: cannot parse texture index in face corner '1/'"},
        BadObj{"word", "v 0 0 0\nf a b c\n", "2: cannot parse vertex index in face corner 'a'"},
        BadObj{"usemtl", "usemtl\n", "1: usemtl without a material name"},
        BadObj{"mtl_number", "mtllib bad.mtl\n", "2: cannot parse Kd 'zz' as a number",
               "newmtl m\nKd 1 zz 0\n"},
        BadObj{"vn_extra", "vn 0 0 1 1\n", "1: unexpected '1' at the end of the vn statement"},
        BadObj{"huge_then_more", "v 1e999 0 0\n", "1: coordinate '1e999' is out of range"},
        BadObj{"mtl_extra", "mtllib bad.mtl\n", "3: unexpected 'spectral' at the end of the Ke",
               "newmtl m\nKd 1 1 1\nKe 1 1 1 spectral\n"},
        BadObj{"mtl_no_texture", "mtllib bad.mtl\n", "2: map_Kd without a file name",
               "newmtl m\nmap_Kd -bm 0.5\n"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(ObjLoader, NonFiniteCoordinateOfAnUnusedVertexIsStillAnError) {
    EXPECT_THROW(loadObjText("obj-unused-nan", kTri + "v 0 0 inf\nf 1 2 3\n"), Error);
}

TEST(ObjLoader, MissingFileNamesTheFileAndTheReason) {
    const fs::path file = test::scratchDir("obj-missing") / "nope.obj";
    try {
        loadObj(file);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(),
                    HasSubstr(file.string() + ": cannot open: No such file or directory"));
    }
}

}  // namespace
}  // namespace strahl
