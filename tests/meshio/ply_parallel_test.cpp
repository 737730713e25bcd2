// The parallel binary PLY decoder against the generic sequential reader
// (src/meshio/loader_tuning.h): the same mesh bit for bit and the same first
// error, for fixed-size and mixed faces, both byte orders, extra properties,
// truncation at every offset, and lying element counts.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "same_bits.h"
#include "../../src/meshio/loader_tuning.h"  // internal to meshio
#include "strahl/core/error.h"
#include "strahl/meshio/mesh_file.h"
#include "test_support.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace strahl {
namespace {

// ---------------------------------------------------------------------------
// A binary PLY writer for generated meshes.

struct Options {
    bool bigEndian = false;
    bool normals = false;     // float nx ny nz after x y z
    bool doubles = false;     // double x y z instead of float
    bool extras = false;      // uchar before and float after the vertex and face records
    const char* indexType = "int";
    size_t quadEvery = 0;     // every n-th face is a quad (0: triangles only)
};

template <typename T>
void put(std::string& out, T value, bool bigEndian) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (bigEndian == (std::endian::native == std::endian::little))
        std::reverse(bytes, bytes + sizeof(T));
    out.append(bytes, sizeof(T));
}

void putIndex(std::string& out, uint32_t v, const Options& o) {
    if (std::string(o.indexType) == "ushort")
        put(out, static_cast<uint16_t>(v), o.bigEndian);
    else if (std::string(o.indexType) == "uint")
        put(out, v, o.bigEndian);
    else
        put(out, static_cast<int32_t>(v), o.bigEndian);
}

// An n x n grid of quads over a wavy sheet: (n + 1)^2 vertices, 2 n^2
// triangles (fewer faces where quads are kept whole).
std::string gridPly(uint32_t n, const Options& o) {
    const uint32_t side = n + 1;
    std::vector<std::vector<uint32_t>> faces;
    size_t faceNo = 0;
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t a = i * side + j, b = a + 1, c = a + side + 1, d = a + side;
            if (o.quadEvery && faceNo++ % o.quadEvery == 0) {
                faces.push_back({a, b, c, d});
            } else {
                faces.push_back({a, b, c});
                faces.push_back({a, c, d});
            }
        }
    }
    const char* coord = o.doubles ? "double" : "float";
    std::string out = std::string("ply\nformat ") +
                      (o.bigEndian ? "binary_big_endian" : "binary_little_endian") + " 1.0\n";
    out += "element vertex " + std::to_string(side * side) + "\n";
    if (o.extras) out += "property uchar flags\n";
    out += std::string("property ") + coord + " x\nproperty " + coord + " y\nproperty " + coord +
           " z\n";
    if (o.normals) out += "property float nx\nproperty float ny\nproperty float nz\n";
    if (o.extras) out += "property float confidence\n";
    out += "element face " + std::to_string(faces.size()) + "\n";
    if (o.extras) out += "property uchar intensity\n";
    out += std::string("property list uchar ") + o.indexType + " vertex_indices\n";
    if (o.extras) out += "property float quality\n";
    out += "end_header\n";
    for (uint32_t i = 0; i < side; ++i) {
        for (uint32_t j = 0; j < side; ++j) {
            const double x = j / double(n), y = i / double(n);
            const double z = 0.1 * std::sin(7 * x) * std::cos(5 * y);
            if (o.extras) put(out, uint8_t(i + j), o.bigEndian);
            if (o.doubles) {
                put(out, x, o.bigEndian), put(out, y, o.bigEndian), put(out, z, o.bigEndian);
            } else {
                put(out, float(x), o.bigEndian), put(out, float(y), o.bigEndian),
                    put(out, float(z), o.bigEndian);
            }
            if (o.normals)
                put(out, float(-z), o.bigEndian), put(out, 0.5f, o.bigEndian),
                    put(out, 1.0f, o.bigEndian);
            if (o.extras) put(out, float(i) * 0.5f, o.bigEndian);
        }
    }
    for (const auto& f : faces) {
        if (o.extras) put(out, uint8_t(f.size()), o.bigEndian);
        put(out, uint8_t(f.size()), o.bigEndian);
        for (uint32_t v : f) putIndex(out, v, o);
        if (o.extras) put(out, 0.25f, o.bigEndian);
    }
    return out;
}

using test::sameBits;

void expectSameMesh(const TriangleMesh& a, const TriangleMesh& b) {
    EXPECT_TRUE(sameBits(a.positions, b.positions));
    EXPECT_TRUE(sameBits(a.normals, b.normals));
    EXPECT_TRUE(sameBits(a.uvs, b.uvs));
    EXPECT_TRUE(sameBits(a.indices, b.indices));
    ASSERT_EQ(a.attributes.size(), b.attributes.size());
    for (size_t i = 0; i < a.attributes.size(); ++i)
        EXPECT_TRUE(sameBits(a.attributes[i].values, b.attributes[i].values)) << a.attributes[i].name;
    EXPECT_TRUE(a.faceMaterials.empty() && b.faceMaterials.empty());
    EXPECT_TRUE(a.isPadded() && b.isPadded());
}

// The error message of decoding `data`, or "" if it loads.
std::string errorOfDecode(const std::string& data, bool parallel) {
    try {
        meshio::decodePly(data, "grid.ply", parallel);
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}

// Parallel and sequential decoding agree: both load the same mesh, or both
// fail with the same message. Returns that message.
std::string expectAgreement(const std::string& data) {
    const std::string parallelError = errorOfDecode(data, true);
    const std::string sequentialError = errorOfDecode(data, false);
    EXPECT_EQ(parallelError, sequentialError);
    if (parallelError.empty() && sequentialError.empty())
        expectSameMesh(meshio::decodePly(data, "grid.ply", true).mesh,
                       meshio::decodePly(data, "grid.ply", false).mesh);
    return parallelError;
}

size_t bodyOffset(const std::string& data) {
    return data.find("end_header\n") + 11;
}

// ---------------------------------------------------------------------------

TEST(PlyParallel, LargeMeshEqualsTheSequentialReader) {
    // 224^2 quads: 50,625 vertices, 100,352 triangles, many chunks of work.
    const std::string data = gridPly(224, {});
    const LoadedMesh parallel = meshio::decodePly(data, "grid.ply", true);
    ASSERT_EQ(parallel.mesh.triangleCount(), 100352u);
    expectSameMesh(parallel.mesh, meshio::decodePly(data, "grid.ply", false).mesh);
}

TEST(PlyParallel, LayoutsEqualTheSequentialReader) {
    const Options layouts[] = {
        {.bigEndian = true},
        {.normals = true},
        {.bigEndian = true, .normals = true, .doubles = true},
        {.extras = true},
        {.bigEndian = true, .extras = true, .indexType = "ushort"},
        {.indexType = "uint", .quadEvery = 3},             // quads among triangles
        {.bigEndian = true, .extras = true, .quadEvery = 1000},  // one late quad
        {.normals = true, .quadEvery = 1},                 // quads only
    };
    for (const Options& o : layouts) {
        SCOPED_TRACE(std::string(o.bigEndian ? "big" : "little") + (o.normals ? " normals" : "") +
                     (o.doubles ? " doubles" : "") + (o.extras ? " extras" : "") + " " +
                     o.indexType + " quadEvery " + std::to_string(o.quadEvery));
        const std::string data = gridPly(120, o);
        EXPECT_EQ(expectAgreement(data), "");
    }
}

TEST(PlyParallel, BigEndianEqualsLittleEndian) {
    const TriangleMesh little = meshio::decodePly(gridPly(60, {.normals = true}), "g.ply", true).mesh;
    const TriangleMesh big =
        meshio::decodePly(gridPly(60, {.bigEndian = true, .normals = true}), "g.ply", true).mesh;
    expectSameMesh(little, big);
    EXPECT_EQ(little.normals.size(), little.positions.size());
}

TEST(PlyParallel, TruncatedAnywhereGivesTheSequentialError) {
    // Cut a small mesh at every byte of its body (fixed faces), and a mixed
    // one at a spread of offsets: the same message as the sequential reader.
    for (const Options& o : {Options{}, Options{.extras = true, .quadEvery = 2}}) {
        const std::string whole = gridPly(4, o);
        for (size_t cut = bodyOffset(whole); cut < whole.size(); ++cut) {
            SCOPED_TRACE(cut);
            const std::string message = expectAgreement(whole.substr(0, cut));
            EXPECT_THAT(message, HasSubstr("unexpected end of file (truncated?)"));
        }
    }
}

TEST(PlyParallel, TruncationNamesTheElementThatDoesNotFit) {
    const std::string whole = gridPly(4, {});  // 25 vertices of 12 bytes, 32 faces of 13
    const size_t body = bodyOffset(whole);
    const std::string inVertices = expectAgreement(whole.substr(0, body + 100));
    // 8 whole vertices and the x of the 9th: its y is the first value not there.
    EXPECT_THAT(inVertices, HasSubstr("grid.ply: byte offset " + std::to_string(body + 100) +
                                      ": unexpected end of file (truncated?): element vertex: 25 "
                                      "vertices of 12 bytes need 300 bytes but only 100 remain "
                                      "after the header"));
    const std::string inFaces = expectAgreement(whole.substr(0, body + 300 + 20));
    EXPECT_THAT(inFaces, HasSubstr(": element face: 32 faces of at least 13 bytes need 416 bytes "
                                   "but only 20 remain from byte offset " +
                                   std::to_string(body + 300)));
}

TEST(PlyParallel, LyingCountsFailBeforeAllocating) {
    // A billion vertices (12 GB) and a trillion faces behind a 3-vertex body:
    // the counts are checked against the file before anything is reserved.
    const std::string vertices =
        "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n"
        "property float x\nproperty float y\nproperty float z\nend_header\n" +
        std::string(36, '\0');
    EXPECT_THAT(expectAgreement(vertices),
                HasSubstr("element vertex: 1000000000 vertices of 12 bytes need 12000000000 "
                          "bytes but only 36 remain after the header"));

    std::string faces = gridPly(1, {});  // 4 vertices, 2 triangles
    const std::string claim = "element face 2\n";
    faces.replace(faces.find(claim), claim.size(), "element face 1000000000000\n");
    EXPECT_THAT(expectAgreement(faces),
                HasSubstr("element face: 1000000000000 faces of at least 13 bytes need "
                          "13000000000000 bytes but only 26 remain from byte offset "));
    // Through loadPly too (the mapped file).
    const fs::path file = test::scratchDir("ply-lying") / "lying.ply";
    std::ofstream(file, std::ios::binary) << vertices;
    try {
        loadPly(file);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr(file.string() + ": byte offset "));
        EXPECT_THAT(e.what(), HasSubstr("element vertex: 1000000000 vertices"));
    }
}

TEST(PlyParallel, FirstBadValueInFileOrderIsReported) {
    // Two bad indices far apart, in different chunks of work: the first wins,
    // with its byte offset, as in the sequential reader.
    std::string data = gridPly(200, {.indexType = "uint"});
    const size_t faces = bodyOffset(data) + 201 * 201 * 12;
    const auto poke = [&](size_t face, size_t corner, uint32_t value) {
        std::memcpy(&data[faces + face * 13 + 1 + 4 * corner], &value, 4);
    };
    poke(70000, 2, 999999);
    poke(30000, 1, 888888);
    EXPECT_THAT(expectAgreement(data),
                HasSubstr("grid.ply: byte offset " + std::to_string(faces + 30000 * 13 + 5) +
                          ": face 30000 refers to vertex 888888 but there are only 40401 vertices"));

    // A non-finite coordinate, likewise.
    std::string nan = gridPly(200, {});
    const float inf = std::numeric_limits<float>::infinity();
    std::memcpy(&nan[bodyOffset(nan) + 35000 * 12 + 8], &inf, 4);
    std::memcpy(&nan[bodyOffset(nan) + 12000 * 12 + 4], &inf, 4);
    EXPECT_THAT(expectAgreement(nan), HasSubstr(": vertex 12000 has a non-finite y"));
}

TEST(PlyParallel, BadFaceAmongFixedOnesFallsBackToTheSequentialError) {
    // Fixed-size triangles until face 5000, which claims 2 corners: the
    // generic reader's message, after the earlier faces' index checks.
    std::string data = gridPly(100, {});
    const size_t faces = bodyOffset(data) + 101 * 101 * 12;
    data[faces + 5000 * 13] = 2;
    EXPECT_THAT(expectAgreement(data), HasSubstr("face 5000 has 2 vertices (needs at least 3)"));
    // A bad index before it is reported first.
    const uint32_t bad = 1u << 30;
    std::memcpy(&data[faces + 4000 * 13 + 1], &bad, 4);
    EXPECT_THAT(expectAgreement(data), HasSubstr("face 4000 refers to vertex 1073741824"));
}

}  // namespace
}  // namespace strahl
