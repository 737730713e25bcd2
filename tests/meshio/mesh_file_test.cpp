// loadMeshFile dispatch and open errors, and findFileCaseInsensitive.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <string>

#include "strahl/core/error.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/meshio/mesh_format.h"
#include "test_support.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace strahl {
namespace {

using test::writeFile;

std::string meshFileErrorOf(const fs::path& file) {
    return test::errorMessage([&] { loadMeshFile(file); });
}

TEST(LoadMeshFile, DispatchesOnTheExtensionIgnoringCase) {
    const fs::path dir = test::scratchDir("meshfile-dispatch");
    writeFile(dir / "quad.OBJ", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    writeFile(dir / "tri.Ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_EQ(loadMeshFile(dir / "quad.OBJ").mesh.triangleCount(), 2u);
    EXPECT_EQ(loadMeshFile(dir / "tri.Ply").mesh.triangleCount(), 1u);
}

TEST(MeshFormats, EachExtensionBelongsToOneFormatAndTheListsSayThemAll) {
    size_t extensions = 0;
    for (const MeshFormat* format : meshFormats()) {
        EXPECT_FALSE(format->name.empty());
        EXPECT_NE(format->load, nullptr);
        EXPECT_NE(format->loadFromMemory, nullptr);
        for (std::string_view extension : format->extensions) {
            ++extensions;
            EXPECT_EQ(findMeshFormat("model" + std::string(extension)), format) << extension;
            std::string upper(extension);
            for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
            EXPECT_EQ(findMeshFormat("model" + upper), format) << upper;
        }
    }
    EXPECT_EQ(extensions, 6u);
    EXPECT_EQ(findMeshFormat("model.stl"), nullptr);
    EXPECT_EQ(meshExtensionList(", ", " or "), ".obj, .ply, .ply.gz, .gltf, .glb or .serialized");
    EXPECT_EQ(meshExtensionList(", ", ", "), ".obj, .ply, .ply.gz, .gltf, .glb, .serialized");
}

TEST(LoadMeshFile, UnknownExtensionNamesTheFile) {
    const fs::path dir = test::scratchDir("meshfile-unknown");
    EXPECT_THAT(meshFileErrorOf(dir / "model.stl"),
                HasSubstr((dir / "model.stl").string() + ": unknown mesh file extension '.stl'"));
    EXPECT_THAT(meshFileErrorOf(dir / "model"), HasSubstr("model: unknown mesh file extension ''"));
    EXPECT_THAT(meshFileErrorOf(dir / "model.stl"), HasSubstr("(expected .obj, .ply, .ply.gz, .gltf, .glb or .serialized)"));
}

TEST(LoadMeshFile, MissingOrUnreadableFileGivesTheSystemReason) {
    const fs::path dir = test::scratchDir("meshfile-missing");
    EXPECT_THAT(
        meshFileErrorOf(dir / "gone.ply"),
        HasSubstr((dir / "gone.ply").string() + ": cannot open: No such file or directory"));
    fs::create_directories(dir / "folder.obj");
    EXPECT_THAT(meshFileErrorOf(dir / "folder.obj"),
                HasSubstr((dir / "folder.obj").string() + ": cannot open: Is a directory"));
}

class FindFile : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::scratchDir("meshfile-find");
        writeFile(dir_ / "Textures" / "Sub" / "Wood.JPG", "x");
        writeFile(dir_ / "exact.png", "x");
        writeFile(dir_ / "twice.jpg", "x");
        writeFile(dir_ / "TWICE.JPG", "x");
        fs::create_directories(dir_ / "folder.png");
    }
    fs::path dir_;
};

TEST_F(FindFile, ExactSpellingIsUsedAsIs) {
    EXPECT_EQ(findFileCaseInsensitive(dir_, "exact.png"), dir_ / "exact.png");
    EXPECT_EQ(findFileCaseInsensitive(dir_, "./exact.png"), dir_ / "exact.png");
}

TEST_F(FindFile, EveryComponentMatchesIgnoringCase) {
    const fs::path wood = dir_ / "Textures" / "Sub" / "Wood.JPG";
    EXPECT_EQ(findFileCaseInsensitive(dir_, "textures/sub/wood.jpg"), wood);
    EXPECT_EQ(findFileCaseInsensitive(dir_, "TEXTURES/SUB/WOOD.JPG"), wood);
    EXPECT_EQ(findFileCaseInsensitive(dir_, "EXACT.PNG"), dir_ / "exact.png");
}

TEST_F(FindFile, BackslashesSeparateComponentsToo) {
    EXPECT_EQ(findFileCaseInsensitive(dir_, "textures\\SUB\\wood.jpg"),
              dir_ / "Textures" / "Sub" / "Wood.JPG");
    EXPECT_EQ(findFileCaseInsensitive(dir_ / "Textures" / "Sub", "..\\..\\exact.png"),
              dir_ / "Textures" / "Sub" / ".." / ".." / "exact.png");
}

TEST_F(FindFile, SeveralCaseMatchesPickTheSmallestNameDeterministically) {
    EXPECT_EQ(findFileCaseInsensitive(dir_, "Twice.jpg"), dir_ / "TWICE.JPG");
    EXPECT_EQ(findFileCaseInsensitive(dir_, "twice.jpg"), dir_ / "twice.jpg");  // exact wins
}

TEST_F(FindFile, EmptyFolderMeansTheWorkingDirectory) {
    const fs::path previous = fs::current_path();
    fs::current_path(dir_);
    const fs::path found = findFileCaseInsensitive({}, "EXACT.PNG");
    fs::current_path(previous);
    EXPECT_EQ(found, fs::path(".") / "exact.png");
}

TEST_F(FindFile, MissingFilesAndFoldersGiveAnEmptyPath) {
    EXPECT_TRUE(findFileCaseInsensitive(dir_, "nowhere.png").empty());
    EXPECT_TRUE(findFileCaseInsensitive(dir_, "textures/none/wood.jpg").empty());
    EXPECT_TRUE(findFileCaseInsensitive(dir_, "Folder.PNG").empty());  // a folder, not a file
    EXPECT_TRUE(findFileCaseInsensitive(dir_, "exact.png/more").empty());
    EXPECT_TRUE(findFileCaseInsensitive(dir_, "").empty());
    EXPECT_TRUE(findFileCaseInsensitive(dir_ / "no-such-dir", "exact.png").empty());
}

}  // namespace
}  // namespace strahl

namespace strahl {
namespace {

TEST(MeshWarnings, GoToTheInstalledHandler) {
    const fs::path dir = test::scratchDir("meshfile-warnings");
    test::writeFile(dir / "t.obj", "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    std::vector<std::string> seen;
    setMeshWarningHandler([&](const std::string& message) { seen.push_back(message); });
    const LoadedMesh mesh = loadMeshFile(dir / "t.obj");
    setMeshWarningHandler({});  // back to stderr for the other tests
    EXPECT_EQ(mesh.mesh.triangleCount(), 1u);
    ASSERT_EQ(seen.size(), 1u);
    EXPECT_TRUE(test::contains(seen[0], "t.obj:1")) << seen[0];
    EXPECT_TRUE(test::contains(seen[0], "nowhere.mtl")) << seen[0];
}

}  // namespace
}  // namespace strahl
