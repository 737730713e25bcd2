// The chunked OBJ parser (src/meshio/loader_tuning.h, decodeObj): the mesh, the
// materials, the warnings and the first error must not depend on where the
// chunk boundaries fall. Chunk sizes from 1 byte (a chunk per line) up to the
// whole file put boundaries between every pair of statements.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "same_bits.h"
#include "../../src/meshio/loader_tuning.h"  // internal to meshio
#include "strahl/core/error.h"
#include "strahl/meshio/mesh_file.h"
#include "test_support.h"
#include "warning_capture.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace strahl {
namespace {

constexpr size_t kChunkSizes[] = {1, 2, 3, 5, 8, 13, 21, 40, 100, 333, 4096};
constexpr size_t kWhole = size_t(1) << 40;  // one chunk: the line-by-line order

using test::sameBits;

struct Outcome {
    LoadedMesh mesh;
    std::string error;
    std::string warnings;
};

Outcome decode(const std::string& text, size_t chunkBytes) {
    Outcome out;
    test::WarningCapture warnings;
    try {
        out.mesh = meshio::decodeObj(text, "mesh.obj", chunkBytes);
    } catch (const Error& e) {
        out.error = e.what();
    }
    out.warnings = warnings.text();
    return out;
}

// Every chunk size gives what one chunk gives; returns that.
Outcome expectChunkInvariance(const std::string& text) {
    Outcome whole = decode(text, kWhole);
    for (const size_t chunkBytes : kChunkSizes) {
        SCOPED_TRACE("chunk bytes " + std::to_string(chunkBytes));
        const Outcome chunked = decode(text, chunkBytes);
        EXPECT_EQ(chunked.error, whole.error);
        EXPECT_EQ(chunked.warnings, whole.warnings);
        const TriangleMesh &a = chunked.mesh.mesh, &b = whole.mesh.mesh;
        EXPECT_TRUE(sameBits(a.positions, b.positions));
        EXPECT_TRUE(sameBits(a.normals, b.normals));
        EXPECT_TRUE(sameBits(a.uvs, b.uvs));
        EXPECT_TRUE(sameBits(a.indices, b.indices));
        EXPECT_TRUE(sameBits(a.faceMaterials, b.faceMaterials));
        EXPECT_EQ(chunked.mesh.materials.size(), whole.mesh.materials.size());
        for (size_t i = 0; i < std::min(chunked.mesh.materials.size(), whole.mesh.materials.size()); ++i)
            EXPECT_EQ(chunked.mesh.materials[i].name, whole.mesh.materials[i].name);
    }
    return whole;
}

// A strip of quads written with relative indices, under changing materials,
// with comments, groups, CRLF lines and statements strahl ignores.
std::string stripObj(int quads) {
    std::string text = "# strip\r\nmtllib missing.mtl\n";
    for (int i = 0; i <= quads; ++i) {
        text += "v " + std::to_string(i) + " 0 0\nv " + std::to_string(i) + " 1 0.5\r\n";
        text += "vt " + std::to_string(i * 0.125) + " 0\nvt " + std::to_string(i * 0.125) + " 1\n";
        text += "vn 0 0 1\n";
        if (i == 0) continue;
        if (i % 3 == 1) text += "usemtl m" + std::to_string(i % 2) + "\n";
        if (i % 4 == 0) text += "g group" + std::to_string(i) + "\ncstype bezier\n";
        if (i % 5 == 0) text += "usemtl unused\n";  // no face before the next usemtl
        // Relative indices reach back across the v/vt/vn lines above.
        text += "f -4/-4/-2 -2/-2/-1 -1/-1/-1 -3/-3/-2\n";
        text += "f " + std::to_string(2 * i - 1) + "/" + std::to_string(2 * i - 1) + "/" +
                std::to_string(i) + " -2/-2/-1 -1/-1/-1\n";
    }
    text += "usemtl trailing\n";  // after the last face: no slot
    return text;
}

TEST(ObjChunks, MeshAndMaterialsDoNotDependOnChunkBoundaries) {
    const Outcome whole = expectChunkInvariance(stripObj(12));
    EXPECT_EQ(whole.error, "");
    EXPECT_EQ(whole.mesh.mesh.triangleCount(), 12u * 3);
    ASSERT_EQ(whole.mesh.materials.size(), 3u);  // m1 m0 unused... in order of first face
    EXPECT_EQ(whole.mesh.materials[0].name, "m1");
    EXPECT_EQ(whole.mesh.materials[1].name, "m0");
    EXPECT_EQ(whole.mesh.materials[2].name, "unused");
    EXPECT_THAT(whole.warnings, HasSubstr("mesh.obj:2: material library 'missing.mtl' not found"));
    EXPECT_THAT(whole.warnings, HasSubstr("ignoring unsupported statement 'cstype'"));
}

TEST(ObjChunks, FacesBeforeAnyUsemtlAcrossChunks) {
    // The default slot (no usemtl yet) spans many chunks, then a usemtl.
    std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (int i = 0; i < 10; ++i) text += "f 1 2 3\n";
    text += "usemtl red\n";
    for (int i = 0; i < 10; ++i) text += "f -1 -2 -3\n";
    const Outcome whole = expectChunkInvariance(text);
    ASSERT_EQ(whole.mesh.materials.size(), 2u);
    EXPECT_EQ(whole.mesh.materials[0].name, "");
    EXPECT_EQ(whole.mesh.mesh.faceMaterials.front(), 0u);
    EXPECT_EQ(whole.mesh.mesh.faceMaterials.back(), 1u);
}

struct BadChunkedObj {
    const char* name;
    std::string text;
    const char* expected;
};

class ObjChunkErrors : public ::testing::TestWithParam<BadChunkedObj> {};

TEST_P(ObjChunkErrors, NameTheSameLineForEveryChunkSize) {
    const Outcome whole = expectChunkInvariance(GetParam().text);
    EXPECT_EQ(whole.error, std::string("mesh.obj:") + GetParam().expected);
}

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

INSTANTIATE_TEST_SUITE_P(
    Malformed, ObjChunkErrors,
    ::testing::Values(
        // -4 reaches one vertex before the first, three chunks back at 1 byte.
        BadChunkedObj{"negative_before_start", kTriangle + "f -1 -2 -3\nf -1 -2 -4\n",
                      "5: vertex index -4 is out of range (3 defined so far)"},
        // A forward reference: vertex 4 comes on the next line (the next chunk).
        BadChunkedObj{"forward", kTriangle + "f 1 2 4\nv 1 1 0\n",
                      "4: vertex index 4 is out of range (3 defined so far)"},
        // Two errors: the first line's wins, whatever chunk the second is in.
        BadChunkedObj{"first_of_two", kTriangle + "f 1 2 3\nv 1 x 0\nf 1 2 9\n",
                      "5: cannot parse coordinate 'x' as a number"},
        BadChunkedObj{"later_chunk_only", kTriangle + "g a\n# c\nf 1 2\n",
                      "6: face with 2 vertices (needs at least 3)"},
        BadChunkedObj{"normal_range", kTriangle + "vn 0 0 1\nf 1//1 2//1 3//2\n",
                      "5: normal index 2 is out of range (1 defined so far)"},
        BadChunkedObj{"usemtl_empty", kTriangle + "f 1 2 3\nusemtl\n",
                      "5: usemtl without a material name"},
        BadChunkedObj{"mtllib_empty", kTriangle + "mtllib \nf 1 2 3 x\n",
                      "4: mtllib without a file name"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(ObjChunks, WarningsBeforeAnErrorOnly) {
    // The unsupported statement after the error is not reported, as when the
    // file is read line by line.
    const Outcome whole = expectChunkInvariance(kTriangle + "curv 1\nf 1 2 0\nsurf 1\n");
    EXPECT_EQ(whole.error, "mesh.obj:5: vertex index 0 is invalid (OBJ indices start at 1)");
    EXPECT_THAT(whole.warnings, HasSubstr("mesh.obj:4: ignoring unsupported statement 'curv'"));
    EXPECT_THAT(whole.warnings, ::testing::Not(HasSubstr("surf")));
}

TEST(ObjChunks, LargeFileThroughLoadObjMatchesOneChunk) {
    // Above the default chunk size (1 MiB), through the mapped file.
    const std::string text = stripObj(20000);
    ASSERT_GT(text.size(), size_t(2) << 20);
    const fs::path file = test::scratchDir("obj-chunks-large") / "mesh.obj";
    test::writeFile(file, text);
    test::WarningCapture quiet;
    const LoadedMesh loaded = loadObj(file);
    const LoadedMesh one = meshio::decodeObj(text, file, kWhole);
    EXPECT_TRUE(sameBits(loaded.mesh.positions, one.mesh.positions));
    EXPECT_TRUE(sameBits(loaded.mesh.uvs, one.mesh.uvs));
    EXPECT_TRUE(sameBits(loaded.mesh.indices, one.mesh.indices));
    EXPECT_TRUE(sameBits(loaded.mesh.faceMaterials, one.mesh.faceMaterials));
    EXPECT_EQ(loaded.mesh.triangleCount(), 60000u);
}

}  // namespace
}  // namespace strahl
