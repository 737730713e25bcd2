// gzip-compressed PLY files (.ply.gz, src/meshio/ply_loader.cpp and
// inflate.cpp): read as the PLY they hold, and a damaged one is one error.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <zlib.h>

#include <filesystem>
#include <string>

#include "strahl/meshio/mesh_file.h"
#include "strahl/meshio/mesh_format.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

const std::string kPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "property float nx\nproperty float ny\nproperty float nz\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1\n0 1 0 0 0 1\n4 0 1 2 3\n";

void writeGzip(const fs::path& file, const std::string& text) {
    gzFile out = gzopen(file.string().c_str(), "wb");
    ASSERT_NE(out, nullptr);
    ASSERT_EQ(gzwrite(out, text.data(), static_cast<unsigned>(text.size())), static_cast<int>(text.size()));
    gzclose(out);
}

TEST(GzipPly, ReadsAsThePlyItHolds) {
    const fs::path dir = test::scratchDir("gzip-ply");
    test::writeFile(dir / "quad.ply", kPly);
    writeGzip(dir / "quad.ply.gz", kPly);
    EXPECT_STREQ(findMeshFormat(dir / "quad.PLY.GZ")->name.data(), "gzip-compressed PLY");
    const LoadedMesh plain = loadMeshFile(dir / "quad.ply");
    const LoadedMesh packed = loadMeshFile(dir / "quad.ply.gz");
    EXPECT_EQ(packed.mesh.positions, plain.mesh.positions);
    EXPECT_EQ(packed.mesh.indices, plain.mesh.indices);
    EXPECT_EQ(packed.mesh.normals, plain.mesh.normals);
    EXPECT_TRUE(plyFileHasVertexNormals(dir / "quad.ply.gz"));
    EXPECT_TRUE(plyFileHasVertexNormals(dir / "quad.ply"));
    test::writeFile(dir / "bare.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nend_header\n");
    EXPECT_FALSE(plyFileHasVertexNormals(dir / "bare.ply"));
    EXPECT_FALSE(plyFileHasVertexNormals(dir / "missing.ply"));
}

TEST(GzipPly, ATruncatedOrCorruptFileIsOneError) {
    const fs::path dir = test::scratchDir("gzip-ply-bad");
    writeGzip(dir / "quad.ply.gz", kPly);
    const std::string bytes = test::readFile(dir / "quad.ply.gz");
    test::writeFile(dir / "cut.ply.gz", bytes.substr(0, bytes.size() / 2));
    EXPECT_THAT(test::errorMessage([&] { loadMeshFile(dir / "cut.ply.gz"); }),
                testing::HasSubstr("cut.ply.gz: the compressed data ends early (truncated)"));
    std::string corrupt = bytes;
    for (size_t i = 12; i < corrupt.size() - 8; ++i) corrupt[i] = static_cast<char>(corrupt[i] ^ 0x5a);
    test::writeFile(dir / "bad.ply.gz", corrupt);
    EXPECT_THAT(test::errorMessage([&] { loadMeshFile(dir / "bad.ply.gz"); }),
                testing::HasSubstr("bad.ply.gz: the compressed data is corrupt"));
}

}  // namespace
}  // namespace strahl
