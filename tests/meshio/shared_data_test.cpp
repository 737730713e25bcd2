// The loaders against the real files of ../shared/data: every OBJ and PLY of
// MANIFEST.tsv with its exact counts, and the texture names of the .mtl files
// (Sponza's differ in case from the files on disk).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "strahl/meshio/mesh_file.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace strahl {
namespace {

struct ManifestMesh {
    std::string path;
    std::string format;
    size_t vertices = 0;
    size_t triangles = 0;
};

// Rows of MANIFEST.tsv (path bytes sha256 format vertices triangles) whose
// format is OBJ or PLY.
std::vector<ManifestMesh> manifestMeshes() {
    std::ifstream in(test::sharedData() / "MANIFEST.tsv");
    std::vector<ManifestMesh> meshes;
    std::string line;
    std::getline(in, line);  // column names
    while (std::getline(in, line)) {
        std::vector<std::string> fields;
        std::stringstream row(line);
        for (std::string field; std::getline(row, field, '\t');) fields.push_back(field);
        if (fields.size() < 6) continue;
        if (!fields[3].starts_with("OBJ") && !fields[3].starts_with("PLY")) continue;
        meshes.push_back({fields[0], fields[3], std::stoul(fields[4]), std::stoul(fields[5])});
    }
    return meshes;
}

TEST(SharedData, EveryManifestMeshLoadsWithItsExactCounts) {
    STRAHL_REQUIRE_SHARED_DATA();
    const std::vector<ManifestMesh> meshes = manifestMeshes();
    ASSERT_GE(meshes.size(), 20u) << "MANIFEST.tsv lists fewer meshes than expected";
    for (const ManifestMesh& entry : meshes) {
        SCOPED_TRACE(entry.path);
        ::testing::internal::CaptureStderr();
        const LoadedMesh m = loadMeshFile(test::sharedData() / entry.path);
        const std::string warnings = ::testing::internal::GetCapturedStderr();
        EXPECT_EQ(m.mesh.triangleCount(), entry.triangles);
        // The manifest counts an OBJ's "v" lines; the loader outputs one vertex
        // per distinct corner, so only PLY vertex counts are comparable.
        if (entry.format.starts_with("PLY")) {
            EXPECT_EQ(m.mesh.vertexCount(), entry.vertices);
        }
        // Some files mix corners with and without uvs, or name a material their
        // .mtl lacks (warned about); but every library and texture must resolve.
        EXPECT_THAT(warnings, ::testing::Not(::testing::HasSubstr("not found")));
        if (!m.mesh.faceMaterials.empty()) {
            ASSERT_EQ(m.mesh.faceMaterials.size(), m.mesh.triangleCount());
            for (uint32_t slot : m.mesh.faceMaterials) ASSERT_LT(slot, m.materials.size());
        }
    }
}

// Material name -> map_Kd file name, as written in an .mtl.
std::map<std::string, std::string> diffuseMapsOf(const fs::path& mtl) {
    std::ifstream in(mtl);
    std::map<std::string, std::string> maps;
    std::string current;
    for (std::string line; std::getline(in, line);) {
        std::stringstream words(line);
        std::string keyword, value;
        words >> keyword >> value;
        if (keyword == "newmtl") current = value;
        if (keyword == "map_Kd") maps[current] = value;
    }
    return maps;
}

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

class SharedTextures : public ::testing::TestWithParam<const char*> {};

TEST_P(SharedTextures, EveryDiffuseMapResolvesToItsFile) {
    STRAHL_REQUIRE_SHARED_DATA();
    const fs::path obj = test::sharedData() / GetParam();
    fs::path mtl = obj;
    const std::map<std::string, std::string> maps = diffuseMapsOf(mtl.replace_extension(".mtl"));
    ASSERT_FALSE(maps.empty());
    const LoadedMesh m = loadObj(obj);
    size_t textured = 0;
    for (const MeshMaterial& material : m.materials) {
        const auto it = maps.find(material.name);
        if (it == maps.end()) {
            EXPECT_TRUE(material.diffuseTexture.empty()) << material.name;
            continue;
        }
        SCOPED_TRACE(material.name + " -> " + it->second);
        ASSERT_FALSE(material.diffuseTexture.empty());
        EXPECT_TRUE(fs::is_regular_file(material.diffuseTexture));
        EXPECT_EQ(lower(material.diffuseTexture.filename().string()), lower(it->second));
        EXPECT_EQ(material.diffuseTexture.parent_path(), obj.parent_path());
        ++textured;
    }
    EXPECT_GT(textured, 0u);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SharedTextures,
                         ::testing::Values("sponza-dabrovic/sponza.obj", "sibenik/sibenik.obj"),
                         [](const auto& testInfo) {
                             const std::string path = testInfo.param;
                             return path.substr(0, path.find_first_of("-/"));
                         });

}  // namespace
}  // namespace strahl
