// Mitsuba's .serialized meshes: files written here by the format's definition
// (zlib streams, both versions, floats and doubles, several meshes with the
// end-of-file dictionary) read back exactly, and corrupt files give one clear
// error.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <string>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/meshio/mesh_file.h"
#include "test_support.h"

namespace strahl {
namespace {

using testing::HasSubstr;

template <typename T>
void put(std::string& out, T value) {
    out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

std::string deflated(const std::string& data) {
    uLongf size = compressBound(uLong(data.size()));
    std::string out(size, '\0');
    EXPECT_EQ(compress(reinterpret_cast<Bytef*>(out.data()), &size,
                       reinterpret_cast<const Bytef*>(data.data()), uLong(data.size())),
              Z_OK);
    out.resize(size);
    return out;
}

// One mesh: header, then the zlib stream of flags, name (v4), counts, data.
template <typename Real>
std::string mesh(uint16_t version, const std::vector<Real>& positions, const std::vector<Real>& normals,
                 const std::vector<Real>& uvs, const std::vector<uint32_t>& indices) {
    std::string body;
    uint32_t flags = sizeof(Real) == 8 ? 0x2000 : 0x1000;
    if (!normals.empty()) flags |= 0x0001;
    if (!uvs.empty()) flags |= 0x0002;
    put(body, flags);
    if (version == 4) body += std::string("part") + '\0';
    put<uint64_t>(body, positions.size() / 3);
    put<uint64_t>(body, indices.size() / 3);
    for (const auto* array : {&positions, &normals, &uvs})
        for (Real r : *array) put(body, r);
    for (uint32_t i : indices) put(body, i);
    std::string out;
    put<uint16_t>(out, 0x041C);
    put<uint16_t>(out, version);
    return out + deflated(body);
}

// Meshes one after the other, then the dictionary of their offsets.
std::string file(uint16_t version, const std::vector<std::string>& meshes) {
    std::string out;
    std::vector<uint64_t> offsets;
    for (const std::string& m : meshes) {
        offsets.push_back(out.size());
        out += m;
    }
    for (uint64_t o : offsets) version == 4 ? put<uint64_t>(out, o) : put<uint32_t>(out, uint32_t(o));
    put<uint32_t>(out, uint32_t(meshes.size()));
    return out;
}

const std::vector<float> kTrianglePositions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
const std::vector<float> kNormals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
const std::vector<float> kUvs = {0, 0, 1, 0, 0, 0.25f};
const std::vector<double> kQuad = {0, 0, 2, 1, 0, 2, 1, 1, 2, 0, 1, 2};

TEST(SerializedLoader, ReadsEveryMeshOfAVersion4File) {
    const std::string bytes =
        file(4, {mesh<float>(4, kTrianglePositions, kNormals, kUvs, {0, 1, 2}),
                 mesh<double>(4, kQuad, {}, {}, {0, 1, 2, 0, 2, 3})});
    const LoadedMesh first = loadSerializedFromMemory(bytes, "scene.serialized");
    ASSERT_EQ(first.mesh.triangleCount(), 1u);
    EXPECT_EQ(first.mesh.positions[1], Vec3(1, 0, 0));
    EXPECT_EQ(first.mesh.normals[2], Vec3(0, 0, 1));
    // Mitsuba's v runs down the image, strahl's up.
    EXPECT_EQ(first.mesh.uvs[2], Vec2(0.0f, 0.75f));
    const LoadedMesh second = loadSerializedFromMemory(bytes, "scene.serialized", 1);
    ASSERT_EQ(second.mesh.triangleCount(), 2u);
    EXPECT_EQ(second.mesh.positions[2], Vec3(1, 1, 2));  // from doubles
    EXPECT_TRUE(second.mesh.normals.empty());
    EXPECT_EQ(second.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST(SerializedLoader, ReadsVersion3FilesAndThroughTheFormatList) {
    const std::string bytes = file(3, {mesh<float>(3, kTrianglePositions, {}, {}, {0, 1, 2}),
                                       mesh<float>(3, kTrianglePositions, {}, {}, {0, 2, 1})});
    EXPECT_EQ(loadSerializedFromMemory(bytes, "old.serialized", 1).mesh.indices,
              (std::vector<uint32_t>{0, 2, 1}));
    const std::filesystem::path path = test::scratchDir("serialized") / "old.serialized";
    test::writeFile(path, bytes);
    EXPECT_EQ(loadMeshFile(path).mesh.triangleCount(), 1u);  // by its extension, mesh 0
}

TEST(SerializedLoader, CorruptFilesAreOneClearError) {
    const std::string good = file(4, {mesh<float>(4, kTrianglePositions, {}, {}, {0, 1, 2})});
    const auto error = [](const std::string& bytes, uint32_t index = 0) {
        return test::errorMessage([&] { loadSerializedFromMemory(bytes, "m.serialized", index); });
    };
    EXPECT_THAT(error("PLY"), HasSubstr("m.serialized: not a Mitsuba serialized mesh"));
    std::string version5 = good;
    version5[2] = 5;
    EXPECT_THAT(error(version5), HasSubstr("serialized format version 5 is not supported"));
    EXPECT_THAT(error(good, 3), HasSubstr("shape_index 3 is out of range (the file holds 1 meshes)"));
    // Cut inside the compressed stream: the indices are missing.
    EXPECT_THAT(error(good.substr(0, good.size() - 30)), HasSubstr("m.serialized: truncated"));
    // An index past the vertices.
    EXPECT_THAT(error(file(4, {mesh<float>(4, kTrianglePositions, {}, {}, {0, 1, 7})})),
                HasSubstr("m.serialized"));
}

}  // namespace
}  // namespace strahl
