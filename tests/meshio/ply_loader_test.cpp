// PLY loader: the three encodings, every scalar type name, skipped properties
// and elements, and the errors of malformed, truncated or lying files.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "../../src/meshio/loader_tuning.h"  // internal to meshio: the sequential reader
#include "strahl/core/error.h"
#include "strahl/meshio/mesh_file.h"
#include "test_support.h"
#include "warning_capture.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace strahl {
namespace {

// ---------------------------------------------------------------------------
// A small PLY writer: every value carries its type, so one description can be
// written in all three encodings.

struct Cell {
    std::string type;
    double value;
};

struct ElementSpec {
    std::string name;
    std::vector<std::string> properties;  // "float x", "list uchar int vertex_indices"
    std::vector<std::vector<Cell>> rows;  // lists: the count cell, then the items
};

void appendBinary(std::string& out, const Cell& c, bool bigEndian) {
    char bytes[8];
    size_t size = 0;
    const auto put = [&](auto v) {
        size = sizeof v;
        std::memcpy(bytes, &v, size);
    };
    if (c.type == "char" || c.type == "int8") put(static_cast<int8_t>(c.value));
    if (c.type == "uchar" || c.type == "uint8") put(static_cast<uint8_t>(c.value));
    if (c.type == "short" || c.type == "int16") put(static_cast<int16_t>(c.value));
    if (c.type == "ushort" || c.type == "uint16") put(static_cast<uint16_t>(c.value));
    if (c.type == "int" || c.type == "int32") put(static_cast<int32_t>(c.value));
    if (c.type == "uint" || c.type == "uint32") put(static_cast<uint32_t>(c.value));
    if (c.type == "float" || c.type == "float32") put(static_cast<float>(c.value));
    if (c.type == "double" || c.type == "float64") put(c.value);
    ASSERT_NE(size, 0u) << "unknown type " << c.type;
    if (bigEndian == (std::endian::native == std::endian::little))
        std::reverse(bytes, bytes + size);
    out.append(bytes, size);
}

std::string plyText(const std::string& format, const std::vector<ElementSpec>& elements) {
    std::string out = "ply\nformat " + format + " 1.0\ncomment written by ply_loader_test\n";
    for (const ElementSpec& e : elements) {
        out += "element " + e.name + " " + std::to_string(e.rows.size()) + "\n";
        for (const std::string& p : e.properties) out += "property " + p + "\n";
    }
    out += "obj_info headers may end with obj_info too\nend_header\n";
    for (const ElementSpec& e : elements) {
        for (const auto& row : e.rows) {
            for (const Cell& c : row) {
                if (format == "ascii") {
                    char text[32];
                    out.append(text, std::to_chars(text, text + sizeof text, c.value).ptr);
                    out += ' ';
                } else {
                    appendBinary(out, c, format == "binary_big_endian");
                }
            }
            if (format == "ascii") out += "\n";
        }
    }
    return out;
}

fs::path writePly(const std::string& test, const std::string& text) {
    const fs::path file = test::scratchDir(test) / "bad.ply";
    std::ofstream(file, std::ios::binary) << text;
    return file;
}

const char* const kFormats[] = {"ascii", "binary_little_endian", "binary_big_endian"};

// Five vertices with normals, uvs and three properties to skip (one a list),
// an unknown element before the faces, faces with extra properties around the
// index list (a quad and a triangle), and an unknown element at the end.
std::vector<ElementSpec> richMesh() {
    ElementSpec vertex{
        "vertex",
        {"float x", "float y", "float z", "uchar flags", "list uchar short extra", "float nx",
         "float ny", "float nz", "double confidence", "float u", "float v"},
        {}};
    const float p[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0.5f, -1.25f}};
    for (int i = 0; i < 5; ++i) {
        std::vector<Cell> row = {{"float", p[i][0]},
                                 {"float", p[i][1]},
                                 {"float", p[i][2]},
                                 {"uchar", 200},
                                 {"uchar", double(i % 3)}};
        for (int k = 0; k < i % 3; ++k) row.push_back({"short", -300.0 + k});
        row.insert(row.end(), {{"float", 0},
                               {"float", 0},
                               {"float", 1},
                               {"double", 0.125 * i},
                               {"float", 0.25 * i},
                               {"float", 1 - 0.25 * i}});
        vertex.rows.push_back(row);
    }
    const ElementSpec rangeGrid{"range_grid",
                                {"list uchar int vertex_indices"},
                                {{{"uchar", 0}},
                                 {{"uchar", 1}, {"int", 7}},
                                 {{"uchar", 3}, {"int", 9}, {"int", 9}, {"int", 9}}}};
    const ElementSpec face{"face",
                           {"uchar intensity", "list uchar int vertex_indices",
                            "list ushort float weights", "int8 tag"},
                           {{{"uchar", 9},
                             {"uchar", 4},
                             {"int", 0},
                             {"int", 1},
                             {"int", 2},
                             {"int", 3},
                             {"ushort", 2},
                             {"float", 0.5},
                             {"float", 0.5},
                             {"int8", -1}},
                            {{"uchar", 9},
                             {"uchar", 3},
                             {"int", 1},
                             {"int", 4},
                             {"int", 2},
                             {"ushort", 0},
                             {"int8", -2}}}};
    const ElementSpec edge{"edge",
                           {"int vertex1", "int vertex2"},
                           {{{"int", 0}, {"int", 1}}, {{"int", 1}, {"int", 2}}}};
    return {vertex, rangeGrid, face, edge};
}

TEST(PlyLoader, SameMeshInAllThreeEncodingsGivesIdenticalData) {
    std::vector<LoadedMesh> loaded;
    for (const char* format : kFormats) {
        SCOPED_TRACE(format);
        const fs::path file =
            writePly(std::string("ply-rich-") + format, plyText(format, richMesh()));
        loaded.push_back(loadPly(file));
        const TriangleMesh& m = loaded.back().mesh;
        ASSERT_EQ(m.vertexCount(), 5u);
        ASSERT_EQ(m.triangleCount(), 3u);
        EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 1, 4, 2}));
        EXPECT_EQ(m.positions[4], Vec3(2, 0.5f, -1.25f));
        ASSERT_EQ(m.normals.size(), 5u);
        EXPECT_EQ(m.normals[3], Vec3(0, 0, 1));
        ASSERT_EQ(m.uvs.size(), 5u);
        EXPECT_EQ(m.uvs[3], Vec2(0.75f, 0.25f));
        EXPECT_TRUE(m.faceMaterials.empty());
        EXPECT_TRUE(loaded.back().materials.empty());
        EXPECT_TRUE(m.isPadded());
    }
    for (size_t i = 1; i < loaded.size(); ++i) {
        EXPECT_EQ(loaded[i].mesh.positions, loaded[0].mesh.positions);
        EXPECT_EQ(loaded[i].mesh.normals, loaded[0].mesh.normals);
        EXPECT_EQ(loaded[i].mesh.uvs, loaded[0].mesh.uvs);
        EXPECT_EQ(loaded[i].mesh.indices, loaded[0].mesh.indices);
    }
}

// The values of the attribute called `name` (and its scope and channels).
const MeshAttribute& attribute(const TriangleMesh& m, const std::string& name) {
    for (const MeshAttribute& a : m.attributes)
        if (a.name == name) return a;
    ADD_FAILURE() << "no attribute " << name;
    static const MeshAttribute none;
    return none;
}

TEST(PlyLoader, AttributesAreGroupedByMitsubasNamesInEveryEncodingAndBothReaders) {
    // Vertex: red green blue (8-bit, sRGB-decoded), dir_x dir_y dir_z, heat_0
    // (one channel), pair_0 pair_1 (two channels: skipped with a warning) and
    // confidence (no suffix: skipped). Face: color_0..2 and weight_0 around
    // the index list; the quad's values go to both of its triangles.
    ElementSpec vertex{"vertex",
                       {"float x", "float y", "float z", "uchar red", "uchar green", "uchar blue",
                        "float dir_x", "float dir_y", "float dir_z", "float heat_0",
                        "float pair_0", "float pair_1", "float confidence"},
                       {}};
    const float p[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; ++i)
        vertex.rows.push_back({{"float", p[i][0]}, {"float", p[i][1]}, {"float", 0},
                               {"uchar", 255}, {"uchar", 0}, {"uchar", double(10 * i)},
                               {"float", 1}, {"float", 2}, {"float", 3}, {"float", 0.5 * i},
                               {"float", 7}, {"float", 8}, {"float", 9}});
    const ElementSpec face{"face",
                           {"float color_0", "float color_1", "list uchar int vertex_indices",
                            "float color_2", "float weight_0"},
                           {{{"float", 0.25}, {"float", 0.5}, {"uchar", 4}, {"int", 0}, {"int", 1},
                             {"int", 2}, {"int", 3}, {"float", 0.75}, {"float", 0.125}},
                            {{"float", 1}, {"float", 0}, {"uchar", 3}, {"int", 0}, {"int", 2},
                             {"int", 1}, {"float", 0}, {"float", 1}}}};
    for (const char* format : kFormats) {
        SCOPED_TRACE(format);
        const std::string text = plyText(format, {vertex, face});
        test::WarningCapture warnings;
        const LoadedMesh loaded = loadPly(writePly("ply-attributes", text));
        EXPECT_THAT(warnings.text(), HasSubstr("properties pair_* are not an attribute (2 channels, not 1 or 3): skipped"));
        const TriangleMesh& m = loaded.mesh;
        ASSERT_EQ(m.attributes.size(), 5u);
        const MeshAttribute& color = attribute(m, "vertex_color");
        EXPECT_EQ(color.scope, MeshAttribute::Scope::Vertex);
        ASSERT_EQ(color.channels, 3);
        ASSERT_EQ(color.values.size(), 12u);
        EXPECT_EQ(color.values[0], 1.0f);
        EXPECT_EQ(color.values[1], 0.0f);
        EXPECT_NEAR(color.values[3 * 3 + 2], std::pow((30.0 / 255 + 0.055) / 1.055, 2.4), 1e-6);
        EXPECT_EQ(attribute(m, "vertex_dir").values,
                  (std::vector<float>{1, 2, 3, 1, 2, 3, 1, 2, 3, 1, 2, 3}));
        EXPECT_EQ(attribute(m, "vertex_heat").values, (std::vector<float>{0, 0.5f, 1, 1.5f}));
        const MeshAttribute& faceColor = attribute(m, "face_color");
        EXPECT_EQ(faceColor.scope, MeshAttribute::Scope::Face);
        EXPECT_EQ(faceColor.values, (std::vector<float>{0.25f, 0.5f, 0.75f, 0.25f, 0.5f, 0.75f, 1, 0, 0}));
        EXPECT_EQ(attribute(m, "face_weight").values, (std::vector<float>{0.125f, 0.125f, 1}));
        EXPECT_NO_THROW(m.validate("ply-attributes"));
        // The generic reader (which reads every ascii body) gives the same.
        const LoadedMesh sequential = meshio::decodePly(text, "ply-attributes.ply", false);
        ASSERT_EQ(sequential.mesh.attributes.size(), m.attributes.size());
        for (size_t a = 0; a < m.attributes.size(); ++a) {
            EXPECT_EQ(sequential.mesh.attributes[a].name, m.attributes[a].name);
            EXPECT_EQ(sequential.mesh.attributes[a].values, m.attributes[a].values);
        }
    }
}

TEST(PlyLoader, EveryScalarTypeNameInEveryEncoding) {
    const char* const types[] = {"char",  "uchar",  "short",   "ushort", "int",   "uint",
                                 "float", "double", "int8",    "uint8",  "int16", "uint16",
                                 "int32", "uint32", "float32", "float64"};
    for (const std::string type : types) {
        const bool isFloat = type.starts_with("float") || type == "double";
        for (const char* format : kFormats) {
            SCOPED_TRACE(type + " " + format);
            // Coordinates of this type; indices of this type when it is an integer.
            const std::string index = isFloat ? "int" : type;
            const ElementSpec vertex{"vertex",
                                     {type + " x", type + " y", type + " z"},
                                     {{{type, 1}, {type, 2}, {type, 100}},
                                      {{type, 3}, {type, 4}, {type, 5}},
                                      {{type, 6}, {type, 7}, {type, 8}}}};
            const ElementSpec face{"face",
                                   {"list " + index + " " + index + " vertex_indices"},
                                   {{{index, 3}, {index, 2}, {index, 0}, {index, 1}}}};
            const fs::path file = writePly("ply-types", plyText(format, {vertex, face}));
            const LoadedMesh m = loadPly(file);
            ASSERT_EQ(m.mesh.vertexCount(), 3u);
            EXPECT_EQ(m.mesh.positions[0], Vec3(1, 2, 100));
            EXPECT_EQ(m.mesh.positions[2], Vec3(6, 7, 8));
            EXPECT_EQ(m.mesh.indices, (std::vector<uint32_t>{2, 0, 1}));
        }
    }
}

TEST(PlyLoader, AlternativeTextureCoordinateNamesAndIncompleteNormals) {
    for (const auto& [u, v] : {std::pair{"s", "t"}, std::pair{"texture_u", "texture_v"}}) {
        SCOPED_TRACE(u);
        const ElementSpec vertex{"vertex",
                                 {"float x", "float y", "float z", "float nx", "float ny",
                                  std::string("float ") + u, std::string("float ") + v},
                                 {{{"float", 0},
                                   {"float", 0},
                                   {"float", 0},
                                   {"float", 1},
                                   {"float", 0},
                                   {"float", 0.5},
                                   {"float", 0.75}}}};
        const LoadedMesh m = loadPly(writePly("ply-uv-names", plyText("ascii", {vertex})));
        ASSERT_EQ(m.mesh.uvs.size(), 1u);
        EXPECT_EQ(m.mesh.uvs[0], Vec2(0.5f, 0.75f));
        EXPECT_TRUE(m.mesh.normals.empty());    // nz is missing
        EXPECT_EQ(m.mesh.triangleCount(), 0u);  // a point cloud: no face element
    }
}

TEST(PlyLoader, VertexIndexNameAndPropertylessElementsWithHugeCounts) {
    const std::string text =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement nothing 18446744073709551615\n"
        "element face 1\nproperty list uchar uint vertex_index\nend_header\n";
    std::string body;
    for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f})
        appendBinary(body, {"float", f}, false);
    appendBinary(body, {"uchar", 3}, false);
    for (int i : {0, 1, 2}) appendBinary(body, {"uint", double(i)}, false);
    const LoadedMesh m = loadPly(writePly("ply-vertex-index", text + body));
    EXPECT_EQ(m.mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

// ---------------------------------------------------------------------------
// Errors

std::string plyErrorOf(const fs::path& file) {
    return test::errorMessage([&] { loadPly(file); });
}

struct BadHeader {
    const char* name;
    const char* text;
    const char* expected;  // after "<file>: "
};

class PlyHeaderErrors : public ::testing::TestWithParam<BadHeader> {};

TEST_P(PlyHeaderErrors, NameTheHeaderLine) {
    const fs::path file = writePly(std::string("ply-header-") + GetParam().name, GetParam().text);
    EXPECT_THAT(plyErrorOf(file), HasSubstr(file.string() + ": " + GetParam().expected));
}

#define PLY_ASCII_START "ply\nformat ascii 1.0\n"
#define PLY_XYZ "property float x\nproperty float y\nproperty float z\n"

INSTANTIATE_TEST_SUITE_P(
    Malformed, PlyHeaderErrors,
    ::testing::Values(
        BadHeader{"magic", "plx\nformat ascii 1.0\n", "header line 1: not a PLY file"},
        BadHeader{"empty", "", "header line 1: end of file before end_header"},
        BadHeader{"format", "ply\nformat utf8 1.0\n", "header line 2: unknown format 'utf8'"},
        BadHeader{"version", "ply\nformat ascii 2.0\n", "header line 2: unsupported PLY version"},
        BadHeader{"no_format", "ply\nelement vertex 0\n" PLY_XYZ "end_header\n",
                  "header line 6: end_header before any format line"},
        BadHeader{"orphan_property", PLY_ASCII_START "property float x\n",
                  "header line 3: property before the first element"},
        BadHeader{"type", PLY_ASCII_START "element vertex 1\nproperty float3 x\n",
                  "header line 4: unknown type 'float3'"},
        BadHeader{"list_count",
                  PLY_ASCII_START "element face 1\nproperty list float int vertex_indices\n",
                  "header line 4: list count type 'float' is not an integer"},
        BadHeader{"count", PLY_ASCII_START "element vertex -5\n",
                  "header line 3: element count '-5' is not a non-negative integer"},
        BadHeader{"keyword", PLY_ASCII_START "elemnt vertex 1\n",
                  "header line 3: unknown header keyword"},
        BadHeader{"unterminated", PLY_ASCII_START "element vertex 1\n" PLY_XYZ,
                  "header line 7: end of file before end_header"},
        BadHeader{"no_z",
                  PLY_ASCII_START
                  "element vertex 1\nproperty float x\nproperty float y\nend_header\n",
                  "header line 3: element vertex has no property 'z'"},
        BadHeader{"no_vertex", PLY_ASCII_START "element face 0\nend_header\n",
                  "header line 4: no 'vertex' element"},
        BadHeader{"list_x",
                  PLY_ASCII_START "element vertex 1\nproperty list uchar float x\n"
                                  "property float y\nproperty float z\nend_header\n",
                  "header line 4: vertex property 'x' is a list"},
        BadHeader{"too_many", PLY_ASCII_START "element vertex 4294967296\n" PLY_XYZ "end_header\n",
                  "header line 3: element vertex has 4294967296 vertices, more than 2^32-1"},
        BadHeader{"no_indices",
                  PLY_ASCII_START "element vertex 0\n" PLY_XYZ "element face 0\n"
                                  "property uchar flags\nend_header\n",
                  "header line 7: element face has no 'vertex_indices' property"},
        BadHeader{"float_indices",
                  PLY_ASCII_START "element vertex 0\n" PLY_XYZ "element face 0\n"
                                  "property list uchar float vertex_indices\nend_header\n",
                  "header line 8: face property 'vertex_indices' is not a list of integers"},
        BadHeader{"tristrips", PLY_ASCII_START "element tristrips 1\n",
                  "header line 3: element 'tristrips' (triangle strips) is not supported"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

// A triangle in the given binary encoding: 3 float vertices, one face.
std::string binaryTriangle(const char* format, const char* countType = "uchar",
                           double faceCount = 1, double listCount = 3) {
    const std::string header = std::string("ply\nformat ") + format +
                               " 1.0\nelement vertex 3\n" PLY_XYZ "element face " +
                               std::to_string(uint64_t(faceCount)) + "\nproperty list " +
                               countType + " int vertex_indices\nend_header\n";
    const bool big = std::string(format) == "binary_big_endian";
    std::string body;
    for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f})
        appendBinary(body, {"float", f}, big);
    appendBinary(body, {countType, listCount}, big);
    for (int i : {0, 1, 2}) appendBinary(body, {"int", double(i)}, big);
    return header + body;
}

TEST(PlyLoader, TruncatedBinaryBodyNamesTheByteOffset) {
    for (const char* format : {"binary_little_endian", "binary_big_endian"}) {
        SCOPED_TRACE(format);
        const std::string whole = binaryTriangle(format);
        const size_t header = whole.find("end_header\n") + 11;
        ASSERT_EQ(loadPly(writePly("ply-whole", whole)).mesh.triangleCount(), 1u);
        // Cut in the middle of the second index: it starts after 36 bytes of
        // vertices, the count byte and the first index.
        const size_t secondIndex = header + 36 + 1 + 4;
        const fs::path file = writePly("ply-truncated", whole.substr(0, secondIndex + 2));
        EXPECT_THAT(plyErrorOf(file),
                    HasSubstr(file.string() + ": byte offset " + std::to_string(secondIndex) +
                              ": unexpected end of file (truncated?)"));
        // Cut inside the vertices.
        const fs::path early = writePly("ply-truncated-early", whole.substr(0, header + 13));
        EXPECT_THAT(plyErrorOf(early), HasSubstr(": byte offset " + std::to_string(header + 12) +
                                                 ": unexpected end of file (truncated?)"));
    }
}

TEST(PlyLoader, AbsurdCountsFailCleanlyAtTheEndOfTheFile) {
    // A face count far beyond what the file holds, and a polygon of 4 billion
    // corners: both must run into the end of the data, not into the allocator.
    const fs::path faces =
        writePly("ply-absurd-faces", binaryTriangle("binary_little_endian", "uchar", 1e15));
    EXPECT_THAT(plyErrorOf(faces), HasSubstr("unexpected end of file (truncated?)"));
    const fs::path corners =
        writePly("ply-absurd-list", binaryTriangle("binary_big_endian", "uint", 1, 4e9));
    EXPECT_THAT(plyErrorOf(corners), HasSubstr("unexpected end of file (truncated?)"));
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n" PLY_XYZ "end_header\n";
    std::string text = header;
    text.append(14, '\1');  // one vertex and a half
    const fs::path vertices = writePly("ply-absurd-vertices", text);
    const std::string offset = std::to_string(header.size() + 12);  // the second vertex
    EXPECT_THAT(plyErrorOf(vertices),
                HasSubstr("bad.ply: byte offset " + offset + ": unexpected end"));
}

TEST(PlyLoader, BinaryBodyErrorsNameTheByteOffset) {
    const std::string tri = binaryTriangle("binary_little_endian", "uchar", 1, 2);
    const fs::path file = writePly("ply-binary-two", tri);
    const size_t count = tri.find("end_header\n") + 11 + 36;
    EXPECT_THAT(plyErrorOf(file), HasSubstr("bad.ply: byte offset " + std::to_string(count) +
                                            ": face 0 has 2 vertices (needs at least 3)"));
    std::string outOfRange = binaryTriangle("binary_big_endian");
    outOfRange.back() = 3;  // the last index, big-endian: its low byte comes last
    const fs::path bad = writePly("ply-binary-range", outOfRange);
    EXPECT_THAT(plyErrorOf(bad),
                HasSubstr("bad.ply: byte offset " + std::to_string(outOfRange.size() - 4) +
                          ": face 0 refers to vertex 3 but there are only 3 vertices"));
}

struct BadAscii {
    const char* name;
    const char* body;      // after a header of 3 vertices (x y z) and 1 face, 9 lines long
    const char* expected;  // after "<file>:"
};

class PlyAsciiErrors : public ::testing::TestWithParam<BadAscii> {};

TEST_P(PlyAsciiErrors, NameTheLine) {
    const std::string header =
        PLY_ASCII_START "element vertex 3\n" PLY_XYZ
                        "element face 1\nproperty list uchar int vertex_indices\n"
                        "end_header\n";
    const fs::path file =
        writePly(std::string("ply-ascii-") + GetParam().name, header + GetParam().body);
    EXPECT_THAT(plyErrorOf(file), HasSubstr(file.string() + ":" + GetParam().expected));
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, PlyAsciiErrors,
    ::testing::Values(BadAscii{"number", "0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n",
                               "line 11: cannot parse 'abc' as a number"},
                      BadAscii{"nan", "0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n",
                               "line 12: vertex 2 has a non-finite y"},
                      BadAscii{"truncated", "0 0 0\n1 0 0\n0 1 0\n3 0 1\n",
                               "line 13: unexpected end of file (truncated?)"},
                      BadAscii{"range", "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
                               "line 13: face 0 refers to vertex 7 but there are only 3 vertices"},
                      BadAscii{"negative", "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
                               "line 13: face 0 refers to vertex -1"},
                      BadAscii{"float_index", "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n",
                               "line 13: cannot parse '1.5' as an integer"},
                      BadAscii{"two_corners", "0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                               "line 13: face 0 has 2 vertices (needs at least 3)"},
                      BadAscii{"count_type", "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n",
                               "line 13: value 300 does not fit its type"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(PlyLoader, NegativeLengthOfASkippedList) {
    const fs::path file =
        writePly("ply-negative-list", PLY_ASCII_START "element vertex 1\n" PLY_XYZ
                                                      "property list char int junk\n"
                                                      "end_header\n0 0 0 -1\n");
    EXPECT_THAT(plyErrorOf(file), HasSubstr("bad.ply:line 9: negative list length -1"));
}

}  // namespace
}  // namespace strahl
