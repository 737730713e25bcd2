// glTF 2.0 loader: tiny .gltf/.glb files written by the tests (data-URI and
// external buffers, a node hierarchy with a mirror, a byte-by-byte .glb, sparse
// and interleaved accessors, embedded images), the errors of bad input,
// loadGltfContents against loadGltf and loadGltfCameras, and the DamagedHelmet
// of ../shared/data.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "same_bits.h"
#include "strahl/core/error.h"
#include "strahl/meshio/gltf_camera.h"
#include "strahl/meshio/mesh_file.h"
#include "warning_capture.h"
#include "test_support.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

namespace strahl {
namespace {

using test::WarningCapture;
using test::writeFile;

// ------------------------------------------------------------------ helpers

// A little-endian binary buffer assembled value by value; every add() starts
// at a 4-byte boundary, as glTF accessors of floats need.
struct Bytes {
    std::string data;

    template <typename T>
    size_t add(std::initializer_list<T> values) {
        while (data.size() % 4 != 0) data += '\0';
        const size_t offset = data.size();
        for (const T& v : values) {
            char raw[sizeof(T)];
            std::memcpy(raw, &v, sizeof(T));
            data.append(raw, sizeof(T));
        }
        return offset;
    }
    void pad() {
        while (data.size() % 4 != 0) data += '\0';
    }
};

std::string base64(const std::string& bytes) {
    static const char* kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t n = uint32_t(uint8_t(bytes[i])) << 16 |
                           uint32_t(uint8_t(bytes[i + 1])) << 8 | uint32_t(uint8_t(bytes[i + 2]));
        for (int k = 3; k >= 0; --k) out += kAlphabet[(n >> (6 * k)) & 63];
    }
    if (i < bytes.size()) {
        uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        out += kAlphabet[(n >> 18) & 63];
        out += kAlphabet[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(n >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

std::string dataUri(const std::string& bytes) {
    return "data:application/octet-stream;base64," + base64(bytes);
}

// The triangle (0,0,0) (1,0,0) (0,1,0), normals +z, uvs (0,0) (1,0) (0,1) in
// glTF's convention, u16 indices 0 1 2: accessors 0 POSITION, 1 NORMAL,
// 2 TEXCOORD_0, 3 indices, all in buffer view 0..3 of buffer 0.
struct Triangle {
    Bytes bytes;
    size_t positions, normals, uvs, indices;

    Triangle() {
        positions = bytes.add<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});
        normals = bytes.add<float>({0, 0, 1, 0, 0, 1, 0, 0, 1});
        uvs = bytes.add<float>({0, 0, 1, 0, 0, 1});
        indices = bytes.add<uint16_t>({0, 1, 2});
        bytes.pad();
    }

    // "bufferViews" and "accessors" members of the JSON (no braces around).
    std::string viewsAndAccessors() const {
        return concat(
            R"("bufferViews": [
              {"buffer": 0, "byteOffset": )",
            positions, R"(, "byteLength": 36},
              {"buffer": 0, "byteOffset": )",
            normals, R"(, "byteLength": 36},
              {"buffer": 0, "byteOffset": )",
            uvs, R"(, "byteLength": 24},
              {"buffer": 0, "byteOffset": )",
            indices, R"(, "byteLength": 6}],
            "accessors": [
              {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
              {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
              {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
              {"bufferView": 3, "componentType": 5123, "count": 3, "type": "SCALAR"}])");
    }

    std::string buffers() const {
        return concat(R"("buffers": [{"byteLength": )", bytes.data.size(), R"(, "uri": ")",
                      dataUri(bytes.data), R"("}])");
    }
};

const char* kTrianglePrimitive =
    R"({"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3)";

// A whole .gltf: one mesh of the triangle under one node, plus `extra` members.
std::string triangleGltf(const std::string& extra = "", const std::string& primitiveExtra = "") {
    const Triangle t;
    return concat(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
                    "nodes": [{"mesh": 0}],
                    "meshes": [{"primitives": [)",
                  kTrianglePrimitive, primitiveExtra, R"(}]}],
                    )",
                  t.viewsAndAccessors(), ",\n", t.buffers(), extra, "}");
}

LoadedMesh loadGltfText(const std::string& test, const std::string& json,
                        const std::string& name = "model.gltf") {
    const fs::path file = test::scratchDir(test) / name;
    writeFile(file, json);
    return loadGltf(file);
}

void expectNear(const Vec3& actual, const Vec3& expected, const char* what, size_t i) {
    EXPECT_NEAR(actual.x, expected.x, 1e-5f) << what << ' ' << i;
    EXPECT_NEAR(actual.y, expected.y, 1e-5f) << what << ' ' << i;
    EXPECT_NEAR(actual.z, expected.z, 1e-5f) << what << ' ' << i;
}

// The normal of triangle t from its winding (counter-clockwise = front).
Vec3 windingNormal(const TriangleMesh& m, size_t t) {
    const Vec3 a = m.positions[m.indices[3 * t]];
    const Vec3 b = m.positions[m.indices[3 * t + 1]];
    const Vec3 c = m.positions[m.indices[3 * t + 2]];
    return glm::normalize(glm::cross(b - a, c - a));
}

// ------------------------------------------------------------------ .gltf

// The triangle with a material using every extension the loader reads.
std::string pbrTriangleGltf() {
    return triangleGltf(R"(,
        "extensionsUsed": ["KHR_materials_emissive_strength", "KHR_materials_ior",
                           "KHR_materials_transmission"],
        "materials": [{"name": "glass",
          "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1.0, 1.0],
                                   "metallicFactor": 0.3, "roughnessFactor": 0.6},
          "emissiveFactor": [1.0, 0.5, 0.0],
          "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4.0},
                         "KHR_materials_ior": {"ior": 1.33},
                         "KHR_materials_transmission": {"transmissionFactor": 0.75}}}])",
                        R"(, "material": 0)");
}

TEST(GltfLoader, SingleTriangleWithDataUriBufferAndPbrMaterial) {
    const LoadedMesh m = loadGltfText("gltf-triangle", pbrTriangleGltf());
    const TriangleMesh& mesh = m.mesh;
    ASSERT_EQ(mesh.triangleCount(), 1u);
    ASSERT_EQ(mesh.vertexCount(), 3u);
    EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(mesh.positions[1], Vec3(1, 0, 0));
    EXPECT_EQ(mesh.positions[2], Vec3(0, 1, 0));
    for (const Vec3& n : mesh.normals) EXPECT_EQ(n, Vec3(0, 0, 1));
    // glTF (u, v) is stored as (u, 1 - v).
    EXPECT_EQ(mesh.uvs, (std::vector<Vec2>{{0, 1}, {1, 1}, {0, 0}}));
    EXPECT_TRUE(mesh.isPadded());
    EXPECT_EQ(mesh.faceMaterials, std::vector<uint32_t>{0});

    ASSERT_EQ(m.materials.size(), 1u);
    const MeshMaterial& g = m.materials[0];
    EXPECT_EQ(g.name, "glass");
    EXPECT_EQ(g.source, MeshMaterial::Source::Gltf);
    EXPECT_EQ(g.diffuse, Color(0.5f, 0.25f, 1.0f));
    EXPECT_FLOAT_EQ(g.metallic, 0.3f);
    EXPECT_FLOAT_EQ(g.roughness, 0.6f);
    EXPECT_EQ(g.emission, Color(4.0f, 2.0f, 0.0f));
    EXPECT_FLOAT_EQ(g.ior, 1.33f);
    EXPECT_EQ(g.transmission, Color(0.75f));
    EXPECT_FLOAT_EQ(g.dissolve, 1.0f);
    EXPECT_TRUE(g.diffuseTexture.empty());
    EXPECT_TRUE(g.normalTexture.empty());
}

// The triangle with one material of alphaMode `mode` (and `extra` material keys).
MeshMaterial alphaMaterial(const std::string& mode, const std::string& extra = "") {
    const LoadedMesh m = loadGltfText("gltf-alpha", triangleGltf(R"(,
        "materials": [{"alphaMode": ")" + mode + R"(", "pbrMetallicRoughness":
                       {"baseColorFactor": [1, 1, 1, 0.4]})" + extra + "}]",
                                                             R"(, "material": 0)"));
    return m.materials.at(0);
}

TEST(GltfLoader, AlphaModesBecomeAnOpacityOrACutoff) {
    const MeshMaterial opaque = alphaMaterial("OPAQUE");
    EXPECT_EQ(opaque.dissolve, 1.0f);  // OPAQUE ignores alpha
    EXPECT_LT(opaque.opacityCutoff, 0.0f);
    const MeshMaterial blend = alphaMaterial("BLEND");
    EXPECT_FLOAT_EQ(blend.dissolve, 0.4f);  // a stochastic opacity
    EXPECT_LT(blend.opacityCutoff, 0.0f);
    const MeshMaterial mask = alphaMaterial("MASK", R"(, "alphaCutoff": 0.3)");
    EXPECT_FLOAT_EQ(mask.dissolve, 0.4f);
    EXPECT_FLOAT_EQ(mask.opacityCutoff, 0.3f);
    EXPECT_FLOAT_EQ(alphaMaterial("MASK").opacityCutoff, 0.5f);  // glTF's default cutoff
    // Emitters keep no alpha (cut-out emitters are not supported), with a warning.
    WarningCapture warnings;
    const MeshMaterial lamp = alphaMaterial("BLEND", R"(, "emissiveFactor": [1, 1, 1])");
    EXPECT_EQ(lamp.dissolve, 1.0f);
    EXPECT_THAT(warnings.text(), HasSubstr("the alpha of emitting materials is ignored"));
}

TEST(GltfLoader, PrimitiveWithoutMaterialGetsTheGltfDefaultMaterial) {
    WarningCapture warnings;
    const LoadedMesh m = loadGltfText("gltf-default-material", triangleGltf());
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.materials[0].name, "default");
    EXPECT_EQ(m.materials[0].source, MeshMaterial::Source::Gltf);
    EXPECT_EQ(m.materials[0].diffuse, Color(1.0f));
    EXPECT_FLOAT_EQ(m.materials[0].metallic, 1.0f);
    EXPECT_FLOAT_EQ(m.materials[0].roughness, 1.0f);
    EXPECT_EQ(m.mesh.faceMaterials, std::vector<uint32_t>{0});
    EXPECT_EQ(warnings.text(), "");
}

// The triangle with its buffer in the file "tri data.bin" next to the glTF.
std::string externalBufferGltf() {
    const Triangle t;
    return concat(R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
                         "nodes": [{"mesh": 0}], "meshes": [{"primitives": [)",
                  kTrianglePrimitive, R"(}]}],)", t.viewsAndAccessors(),
                  R"(, "buffers": [{"byteLength": )", t.bytes.data.size(),
                  R"(, "uri": "tri%20data.bin"}]})");
}

TEST(GltfLoader, ExternalBufferAndDispatchByExtensionIgnoringCase) {
    const fs::path dir = test::scratchDir("gltf-external");
    writeFile(dir / "tri data.bin", Triangle().bytes.data);
    writeFile(dir / "Tri.GLTF", externalBufferGltf());
    const LoadedMesh m = loadMeshFile(dir / "Tri.GLTF");
    EXPECT_EQ(m.mesh.triangleCount(), 1u);
    EXPECT_EQ(m.mesh.positions[1], Vec3(1, 0, 0));
}

// Root node 0 (translation 10 0 0) with children 1 (rotation 90 degrees about z,
// scale 2) and 2 (matrix mirroring x); node 3 is outside the default scene.
const char* kHierarchyNodes = R"(
    "scene": 1,
    "scenes": [{"nodes": [3]}, {"nodes": [0]}],
    "nodes": [
      {"translation": [10, 0, 0], "children": [1, 2]},
      {"mesh": 0, "rotation": [0, 0, 0.7071067811865476, 0.7071067811865476],
       "scale": [2, 2, 2]},
      {"mesh": 0, "matrix": [-1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]},
      {"mesh": 0, "translation": [0, 0, 100]}],)";

// The triangle under kHierarchyNodes (or another node list).
std::string hierarchyGltf(const char* nodes = kHierarchyNodes) {
    const Triangle t;
    return concat(R"({"asset": {"version": "2.0"},)", nodes, R"("meshes": [{"primitives": [)",
                  kTrianglePrimitive, R"(}]}],)", t.viewsAndAccessors(), ",", t.buffers(), "}");
}

TEST(GltfLoader, NodeHierarchyAppliesTrsAndMatricesAndMirrorsFlipTheWinding) {
    const LoadedMesh m = loadGltfText("gltf-hierarchy", hierarchyGltf());
    const TriangleMesh& mesh = m.mesh;
    ASSERT_EQ(mesh.triangleCount(), 2u);  // node 3 is not in scene 1
    ASSERT_EQ(mesh.vertexCount(), 6u);
    // Node 1: p -> T(10,0,0) R_z(90) S(2) p.
    expectNear(mesh.positions[0], {10, 0, 0}, "position", 0);
    expectNear(mesh.positions[1], {10, 2, 0}, "position", 1);
    expectNear(mesh.positions[2], {8, 0, 0}, "position", 2);
    // Node 2: x mirrored, then translated.
    expectNear(mesh.positions[3], {10, 0, 0}, "position", 3);
    expectNear(mesh.positions[4], {9, 0, 0}, "position", 4);
    expectNear(mesh.positions[5], {10, 1, 0}, "position", 5);
    EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 3, 5, 4}));
    for (size_t i = 0; i < 6; ++i) expectNear(mesh.normals[i], {0, 0, 1}, "normal", i);
    // The winding agrees with the normals in both instances.
    for (size_t tri = 0; tri < 2; ++tri)
        expectNear(windingNormal(mesh, tri), {0, 0, 1}, "winding", tri);
}

// A slanted triangle with normals under a non-uniform scale, not indexed.
std::string slantedTriangleGltf() {
    Bytes b;
    b.add<float>({0, 0, 0, 1, 0, 1, 0, 1, 0});
    const float s = 1.0f / std::sqrt(2.0f);
    b.add<float>({-s, 0, s, -s, 0, s, -s, 0, s});
    return concat(R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
               "nodes": [{"mesh": 0, "scale": [3, 1, 0.5]}],
               "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}],
               "bufferViews": [{"buffer": 0, "byteLength": 36},
                               {"buffer": 0, "byteOffset": 36, "byteLength": 36}],
               "accessors": [
                 {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                 {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}],
               "buffers": [{"byteLength": 72, "uri": ")",
                  dataUri(b.data), R"("}]})");
}

TEST(GltfLoader, NormalsUseTheInverseTransposeAndStayUnitLength) {
    // The normal must stay perpendicular to the transformed triangle.
    const LoadedMesh m = loadGltfText("gltf-normals", slantedTriangleGltf());
    ASSERT_EQ(m.mesh.triangleCount(), 1u);
    EXPECT_EQ(m.mesh.indices, (std::vector<uint32_t>{0, 1, 2}));  // non-indexed: 0..n-1
    const Vec3 face = windingNormal(m.mesh, 0);
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(glm::length(m.mesh.normals[i]), 1.0f, 1e-6f);
        expectNear(m.mesh.normals[i], face, "normal", i);
    }
}

// Two primitives: one buffer view with byteStride 16 (position, 12 bytes, and
// a u16 normalized uv), u8 normalized uvs, a sparse position and u8 indices.
std::string interleavedGltf() {
    Bytes b;
    const uint16_t half = 32768;  // 32768 / 65535, a little above 0.5
    b.add<float>({0, 0, 0});
    b.add<uint16_t>({0, 0});
    b.add<float>({1, 0, 0});
    b.add<uint16_t>({65535, 0});
    b.add<float>({0, 1, 0});
    b.add<uint16_t>({0, half});
    const size_t u8uvs = b.add<uint8_t>({0, 255, 255, 255, 51, 0});  // 51 / 255 = 0.2
    const size_t sparseIndices = b.add<uint8_t>({2});
    const size_t sparseValues = b.add<float>({5, 6, 7});
    const size_t u8indices = b.add<uint8_t>({0, 1, 2});
    b.pad();
    return concat(R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
               "nodes": [{"mesh": 0}],
               "meshes": [{"primitives": [
                 {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}},
                 {"attributes": {"POSITION": 2, "TEXCOORD_0": 3}, "indices": 4}]}],
               "bufferViews": [{"buffer": 0, "byteLength": 48, "byteStride": 16},
                               {"buffer": 0, "byteOffset": )",
                  u8uvs, R"(, "byteLength": 6},
                               {"buffer": 0, "byteOffset": )",
                  sparseIndices, R"(, "byteLength": 1},
                               {"buffer": 0, "byteOffset": )",
                  sparseValues, R"(, "byteLength": 12},
                               {"buffer": 0, "byteOffset": )",
                  u8indices, R"(, "byteLength": 3}],
               "accessors": [
                 {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                 {"bufferView": 0, "byteOffset": 12, "componentType": 5123,
                  "normalized": true, "count": 3, "type": "VEC2"},
                 {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                  "sparse": {"count": 1,
                             "indices": {"bufferView": 2, "componentType": 5121},
                             "values": {"bufferView": 3}}},
                 {"bufferView": 1, "componentType": 5121, "normalized": true,
                  "count": 3, "type": "VEC2"},
                 {"bufferView": 4, "componentType": 5121, "count": 3, "type": "SCALAR"}],
               "buffers": [{"byteLength": )",
                  b.data.size(), R"(, "uri": ")", dataUri(b.data), R"("}]})");
}

TEST(GltfLoader, InterleavedStrideNormalizedTexcoordsSparseAccessorsAndByteIndices) {
    const LoadedMesh m = loadGltfText("gltf-interleaved", interleavedGltf());
    const TriangleMesh& mesh = m.mesh;
    ASSERT_EQ(mesh.vertexCount(), 6u);
    EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));  // u8 in primitive 1
    EXPECT_EQ(mesh.positions[1], Vec3(1, 0, 0));
    EXPECT_EQ(mesh.positions[2], Vec3(0, 1, 0));
    EXPECT_EQ(mesh.positions[4], Vec3(1, 0, 0));
    EXPECT_EQ(mesh.positions[5], Vec3(5, 6, 7));  // the sparse substitution
    EXPECT_NEAR(mesh.uvs[1].x, 1.0f, 1e-6f);
    EXPECT_NEAR(mesh.uvs[1].y, 1.0f, 1e-6f);
    EXPECT_NEAR(mesh.uvs[2].y, 1.0f - 32768.0f / 65535.0f, 1e-6f);
    EXPECT_NEAR(mesh.uvs[3].x, 0.0f, 1e-6f);
    EXPECT_NEAR(mesh.uvs[3].y, 0.0f, 1e-6f);  // u8 255 = 1: stored 1 - 1
    EXPECT_NEAR(mesh.uvs[5].x, 0.2f, 1e-6f);
    EXPECT_NEAR(mesh.uvs[5].y, 1.0f, 1e-6f);
}

// The triangle twice under a mirror, the second time without normals and uvs.
std::string flatNormalsGltf() {
    const Triangle t;
    return concat(R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
               "nodes": [{"mesh": 0, "scale": [-1, 1, 1]}],
               "meshes": [{"primitives": [)",
                  kTrianglePrimitive, R"(},
                 {"attributes": {"POSITION": 0}, "indices": 3, "mode": 4}]}],)",
                  t.viewsAndAccessors(), ",", t.buffers(), "}");
}

TEST(GltfLoader, PrimitivesWithoutNormalsGetFlatNormalsNextToOthers) {
    const LoadedMesh m = loadGltfText("gltf-flat", flatNormalsGltf());
    ASSERT_EQ(m.mesh.triangleCount(), 2u);
    ASSERT_EQ(m.mesh.vertexCount(), 6u);  // the flat primitive: one vertex per corner
    ASSERT_EQ(m.mesh.normals.size(), 6u);
    for (size_t i = 0; i < 6; ++i) expectNear(m.mesh.normals[i], {0, 0, 1}, "normal", i);
    for (size_t tri = 0; tri < 2; ++tri)
        expectNear(windingNormal(m.mesh, tri), {0, 0, 1}, "winding", tri);
    // No uvs in the second primitive: (0, 0).
    EXPECT_EQ(m.mesh.uvs[5], Vec2(0.0f));
}

// The triangle, then the same primitive as lines (mode 1); `extra` as in triangleGltf.
std::string linesGltf(const std::string& extra = "") {
    return triangleGltf(extra, R"(}, )" + std::string(kTrianglePrimitive) + R"(, "mode": 1)");
}

TEST(GltfLoader, ModesOtherThanTrianglesAreSkippedWithAWarning) {
    WarningCapture warnings;
    const LoadedMesh m = loadGltfText("gltf-lines", linesGltf());
    EXPECT_EQ(m.mesh.triangleCount(), 1u);
    EXPECT_THAT(warnings.text(),
                HasSubstr("model.gltf: meshes[0].primitives[1]: mode 1 is not TRIANGLES (4); "
                          "primitive skipped"));
}

// A PNG signature and some bytes: what the loader takes for a PNG image.
const std::string kPng = std::string("\x89PNG\r\n\x1a\n", 8) + "fake image bytes";

// The triangle with textures from "tex dir/base color.png" (percent-encoded),
// from kPng in a data URI and from the missing "nowhere.png".
std::string texturedGltf() {
    return triangleGltf(concat(R"(,
        "images": [{"uri": "tex%20dir/base%20color.png"},
                   {"uri": "data:image/png;base64,)",
                               base64(kPng), R"("},
                   {"uri": "nowhere.png"}],
        "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                "metallicRoughnessTexture": {"index": 2}},
                       "normalTexture": {"index": 1}, "emissiveTexture": {"index": 1}}])"),
                        R"(, "material": 0)");
}

TEST(GltfLoader, TexturePathsResolvePercentDecodedAndEmbeddedImagesAreCached) {
    const fs::path dir = test::scratchDir("gltf-textures");
    writeFile(dir / "tex dir" / "base color.png", "png");
    WarningCapture warnings;
    writeFile(dir / "t.gltf", texturedGltf());
    const LoadedMesh m = loadGltf(dir / "t.gltf");
    ASSERT_EQ(m.materials.size(), 1u);
    const MeshMaterial& g = m.materials[0];
    EXPECT_TRUE(fs::equivalent(g.diffuseTexture, dir / "tex dir" / "base color.png"));
    ASSERT_FALSE(g.normalTexture.empty());
    EXPECT_EQ(g.normalTexture, g.emissionTexture);  // one image, extracted once
    EXPECT_EQ(g.normalTexture.extension(), ".png");
    EXPECT_THAT(g.normalTexture.parent_path().filename().string(), HasSubstr("strahl-gltf-"));
    EXPECT_EQ(g.normalTexture.parent_path().parent_path(), fs::temp_directory_path());
    EXPECT_EQ(test::readFile(g.normalTexture), kPng);
    EXPECT_TRUE(g.metallicRoughnessTexture.empty());
    EXPECT_THAT(warnings.text(), HasSubstr("t.gltf: images[2]: texture 'nowhere.png' not found"));

    // A second load finds the extracted file in place.
    const auto written = fs::last_write_time(g.normalTexture);
    EXPECT_EQ(loadGltf(dir / "t.gltf").materials[0].normalTexture, g.normalTexture);
    EXPECT_EQ(fs::last_write_time(g.normalTexture), written);
    fs::remove_all(g.normalTexture.parent_path());  // the cache folder of this test's file
}

// extensionsUsed, with one extension the loader reads and one it does not.
const char* kExtensionsUsed = R"(, "extensionsUsed": ["KHR_texture_transform",
                                                      "KHR_materials_ior"])";

TEST(GltfLoader, UnsupportedOptionalExtensionsAreNamedInAWarning) {
    WarningCapture warnings;
    const LoadedMesh m = loadGltfText("gltf-extensions", triangleGltf(kExtensionsUsed));
    EXPECT_EQ(m.mesh.triangleCount(), 1u);
    EXPECT_THAT(warnings.text(), HasSubstr("ignoring the glTF extensions KHR_texture_transform"));
    EXPECT_THAT(warnings.text(), Not(HasSubstr("KHR_materials_ior")));
}

// ------------------------------------------------------------------ .glb

// A .glb: 12-byte header, JSON chunk padded with spaces, BIN chunk padded with zeros.
std::string glb(std::string json, std::string bin) {
    while (json.size() % 4 != 0) json += ' ';
    while (bin.size() % 4 != 0) bin += '\0';
    Bytes out;
    out.add<uint32_t>({0x46546C67, 2, uint32_t(12 + 8 + json.size() + 8 + bin.size())});
    out.add<uint32_t>({uint32_t(json.size()), 0x4E4F534A});
    out.data += json;
    out.add<uint32_t>({uint32_t(bin.size()), 0x004E4942});
    out.data += bin;
    return out.data;
}

// Two triangles sharing an edge, u32 indices, and a JPEG image in a buffer view.
std::string quadGlb() {
    Bytes b;
    b.add<float>({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    const size_t indices = b.add<uint32_t>({0, 1, 2, 0, 2, 3});
    const size_t image = b.add<uint8_t>({0xFF, 0xD8, 0xFF, 0xE0, 'j', 'p', 'g'});
    b.pad();
    const std::string json = concat(
        R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
                                        "material": 0}]}],
            "materials": [{"name": "tiles", "pbrMetallicRoughness": {
                             "baseColorTexture": {"index": 0}}}],
            "textures": [{"source": 0}],
            "images": [{"bufferView": 2, "mimeType": "image/jpeg"}],
            "bufferViews": [{"buffer": 0, "byteLength": 48},
                            {"buffer": 0, "byteOffset": )",
        indices, R"(, "byteLength": 24},
                            {"buffer": 0, "byteOffset": )",
        image, R"(, "byteLength": 7}],
            "accessors": [
              {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
              {"bufferView": 1, "componentType": 5125, "count": 6, "type": "SCALAR"}],
            "buffers": [{"byteLength": )",
        b.data.size(), "}]}");
    return glb(json, b.data);
}

TEST(GltfLoader, BinaryGlbWithEmbeddedImage) {
    const fs::path dir = test::scratchDir("gltf-glb");
    writeFile(dir / "quad.glb", quadGlb());
    const LoadedMesh m = loadMeshFile(dir / "quad.glb");
    ASSERT_EQ(m.mesh.triangleCount(), 2u);
    EXPECT_EQ(m.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(m.mesh.positions[2], Vec3(1, 1, 0));
    EXPECT_TRUE(m.mesh.normals.empty());
    EXPECT_TRUE(m.mesh.uvs.empty());
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.materials[0].name, "tiles");
    const fs::path image = m.materials[0].diffuseTexture;
    EXPECT_EQ(image.extension(), ".jpg");
    EXPECT_EQ(test::readFile(image), std::string("\xFF\xD8\xFF\xE0jpg", 7));
    fs::remove_all(image.parent_path());  // the cache folder of this test's file
}

// Every byte of the header and JSON chunk replaced in turn by values that change
// numbers, break strings and break UTF-8 / structure: each load succeeds or throws
// strahl::Error, never anything else (or crashes).
TEST(GltfLoader, MutatedGlbEitherLoadsOrFailsWithAStrahlError) {
    const fs::path dir = test::scratchDir("gltf-mutated");
    const std::string whole = quadGlb();
    uint32_t jsonLength = 0;
    std::memcpy(&jsonLength, whole.data() + 12, 4);
    const size_t end = 20 + jsonLength;  // header and JSON chunk
    size_t loaded = 0, failed = 0;
    WarningCapture warnings;  // mutations make tinygltf warn
    for (size_t i = 0; i < end; ++i) {
        for (const char c : {'9', '"', '\xFF'}) {
            if (whole[i] == c) continue;
            std::string mutated = whole;
            mutated[i] = c;
            writeFile(dir / "m.glb", mutated);
            try {
                const LoadedMesh m = loadGltf(dir / "m.glb");
                m.mesh.validate("mutated");
                ++loaded;
            } catch (const Error&) {
                ++failed;
            }
        }
    }
    EXPECT_GT(failed, 0u);
    EXPECT_GT(loaded, 0u);            // e.g. a changed material name
    writeFile(dir / "m.glb", whole);  // its cache folder, shared by all mutations
    fs::remove_all(loadGltf(dir / "m.glb").materials.at(0).diffuseTexture.parent_path());
}

// One of those mutations: the image's view starts past the end of the buffer.
// tinygltf 2.7 would index the buffer there before checking anything
// (undefined behaviour, caught by the sanitizer build); the loader refuses the
// file before tinygltf reads it.
// tinygltf 2.7 throws std::out_of_range for a zero-length buffer next to a
// BIN chunk instead of failing: the loader turns that into its own error,
// naming the file, like every other malformed file.
TEST(GltfLoader, AnExceptionFromTinygltfBecomesAnErrorNamingTheFile) {
    const fs::path dir = test::scratchDir("gltf-tinygltf-throws");
    writeFile(dir / "m.glb", glb(R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 0}]})",
                                 std::string(8, 'x')));
    const std::string message = test::errorMessage([&] { loadGltf(dir / "m.glb"); });
    EXPECT_THAT(message, HasSubstr("m.glb: "));
}

TEST(GltfLoader, ImageViewStartingPastItsBufferIsAnError) {
    const fs::path dir = test::scratchDir("gltf-image-view");
    std::string glb = quadGlb();
    const size_t at = glb.find(R"("byteOffset": 72, "byteLength": 7})");
    ASSERT_NE(at, std::string::npos);
    glb[at + 14] = '9';  // byte offset 92 of the 80-byte buffer, the file's length unchanged
    writeFile(dir / "m.glb", glb);
    EXPECT_THAT(test::errorMessage([&] { loadGltf(dir / "m.glb"); }),
                HasSubstr("m.glb: images[0]: buffer view 2 (7 bytes from offset 92) reads past "
                          "the end of buffer 0 (80 bytes)"));
}

// ------------------------------------------------------------------ errors

struct BadGltf {
    const char* name;
    std::string json;   // the whole file
    const char* error;  // expected part of the message, which starts with the file
};

// Test names print the case's name (not its bytes, padding included).
void PrintTo(const BadGltf& bad, std::ostream* out) {
    *out << bad.name;
}

class GltfErrors : public ::testing::TestWithParam<BadGltf> {};

TEST_P(GltfErrors, NameTheFileAndThePlace) {
    const BadGltf& bad = GetParam();
    const fs::path file = test::scratchDir(std::string("gltf-bad-") + bad.name) / "bad.gltf";
    writeFile(file, bad.json);
    const std::string message = test::errorMessage([&] { loadGltf(file); });
    EXPECT_THAT(message, ::testing::StartsWith(file.string() + ": "));
    EXPECT_THAT(message, HasSubstr(bad.error));
}

// The triangle with `accessors`, `primitive` or `nodes` replaced.
std::string triangleWith(const std::string& accessors, const std::string& primitive = "",
                         const std::string& nodes = R"("scenes": [{"nodes": [0]}],
                                                       "nodes": [{"mesh": 0}])",
                         const std::string& extra = "") {
    const Triangle t;
    const std::string views = t.viewsAndAccessors();
    const std::string viewsOnly = views.substr(0, views.find("\"accessors\""));
    return concat(R"({"asset": {"version": "2.0"},)", nodes, R"(,
                   "meshes": [{"primitives": [)",
                  primitive.empty() ? std::string(kTrianglePrimitive) + "}" : primitive, "]}],",
                  viewsOnly,
                  accessors.empty() ? views.substr(views.find("\"accessors\"")) : accessors, ",",
                  t.buffers(), extra, "}");
}

// Accessors 0..3 of the triangle with one of them replaced.
std::string accessorsWith(int which, const std::string& replacement) {
    std::string list[4] = {
        R"({"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"})",
        R"({"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"})",
        R"({"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"})",
        R"({"bufferView": 3, "componentType": 5123, "count": 3, "type": "SCALAR"})"};
    list[which] = replacement;
    return concat(R"("accessors": [)", list[0], ",", list[1], ",", list[2], ",", list[3], "]");
}

std::string withIndices(std::initializer_list<uint16_t> indices) {
    Triangle t;
    Bytes b = t.bytes;
    b.data.resize(t.indices);
    b.add<uint16_t>(indices);
    b.pad();
    std::string json = triangleWith("");
    const size_t start = json.find("\"buffers\"");
    return json.substr(0, start) + concat(R"("buffers": [{"byteLength": )", b.data.size(),
                                          R"(, "uri": ")", dataUri(b.data), R"("}]})");
}

std::string withNonFinitePosition() {
    Triangle t;
    const float inf = std::numeric_limits<float>::infinity();
    std::memcpy(t.bytes.data.data() + t.positions + 12, &inf, sizeof inf);  // vertex 1, x
    std::string json = triangleWith("");
    const size_t start = json.find("\"buffers\"");
    return json.substr(0, start) + t.buffers() + "}";
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, GltfErrors,
    ::testing::Values(
        BadGltf{"json", "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [", "parse error"},
        BadGltf{"past_view",
                triangleWith(accessorsWith(
                    0, R"({"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"})")),
                "bad.gltf: meshes[0].primitives[0]: POSITION accessor 0 reads past the end of "
                "buffer view 0 (4 elements of 12 bytes, stride 12, from offset 0; the view has "
                "36 bytes)"},
        BadGltf{
            "offset_past_view", triangleWith(accessorsWith(2, R"({"bufferView": 2, "byteOffset": 4,
                    "componentType": 5126, "count": 3, "type": "VEC2"})")),
            "meshes[0].primitives[0]: TEXCOORD_0 accessor 2 reads past the end of buffer view 2"},
        BadGltf{"lying_count",
                triangleWith(accessorsWith(0, R"({"bufferView": 0, "componentType": 5126,
                    "count": 4000000000000, "type": "VEC3"})")),
                "POSITION accessor 0 reads past the end of buffer view 0 (4000000000000 elements"},
        BadGltf{"lying_count_no_view", triangleWith(accessorsWith(0, R"({"componentType": 5126,
                    "count": 4000000000000, "type": "VEC3"})")),
                "POSITION accessor 0 has no buffer view and claims 4000000000000 elements"},
        BadGltf{"missing_accessor",
                triangleWith("", R"({"attributes": {"POSITION": 0}, "indices": 9})"),
                "primitive indices accessor out of bounds"},
        BadGltf{"missing_normal_accessor",
                triangleWith("", R"({"attributes": {"POSITION": 0, "NORMAL": 7}})"),
                "meshes[0].primitives[0]: NORMAL accessor 7 does not exist (4 accessors)"},
        BadGltf{"wrong_type",
                triangleWith(accessorsWith(
                    0, R"({"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC2"})")),
                "POSITION accessor 0 is VEC2, expected VEC3"},
        BadGltf{"wrong_component",
                triangleWith(accessorsWith(
                    0, R"({"bufferView": 0, "componentType": 5123, "count": 3, "type": "VEC3"})")),
                "POSITION accessor 0 holds unsigned short values, expected float"},
        BadGltf{
            "float_indices",
            triangleWith(accessorsWith(
                3, R"({"bufferView": 2, "componentType": 5126, "count": 3, "type": "SCALAR"})")),
            "indices accessor 3 holds float values, expected unsigned byte"},
        BadGltf{"count_mismatch",
                triangleWith(accessorsWith(
                    1, R"({"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC3"})")),
                "NORMAL accessor 1 has 2 elements, POSITION has 3"},
        BadGltf{"partial_triangle",
                triangleWith(accessorsWith(3, R"({"bufferView": 3, "componentType": 5123,
                    "count": 2, "type": "SCALAR"})")),
                "meshes[0].primitives[0]: 2 indices are not a whole number of triangles"},
        BadGltf{"index_range", withIndices({0, 1, 7}),
                "indices accessor 3: index 7 (element 2) is out of range: the primitive has 3"},
        BadGltf{"infinite_position", withNonFinitePosition(),
                "POSITION accessor 0: element 1 is not finite"},
        BadGltf{"cycle", triangleWith("", "", R"("scenes": [{"nodes": [0]}],
                    "nodes": [{"mesh": 0, "children": [1]}, {"children": [2]},
                              {"children": [0]}])"),
                "nodes[0]: node 0 is its own ancestor (cyclic node hierarchy)"},
        BadGltf{"self_child", triangleWith("", "", R"("scenes": [{"nodes": [0]}],
                    "nodes": [{"mesh": 0, "children": [0]}])"),
                "nodes[0].children[0]: node 0 is its own ancestor"},
        BadGltf{"two_parents", triangleWith("", "", R"("scenes": [{"nodes": [0, 1]}],
                    "nodes": [{"children": [2]}, {"children": [2]}, {"mesh": 0}])"),
                "nodes[1].children[0]: node 2 already is a child of node 0"},
        BadGltf{"root_twice", triangleWith("", "", R"("scenes": [{"nodes": [0, 0]}],
                    "nodes": [{"mesh": 0}])"),
                "scenes[0].nodes[1]: node 0 appears twice in the hierarchy"},
        BadGltf{"missing_child", triangleWith("", "", R"("scenes": [{"nodes": [0]}],
                    "nodes": [{"mesh": 0, "children": [5]}])"),
                "nodes[0].children[0]: node 5 does not exist (1 nodes)"},
        BadGltf{"missing_mesh", triangleWith("", "", R"("scenes": [{"nodes": [0]}],
                    "nodes": [{"mesh": 3}])"),
                "nodes[0]: mesh 3 does not exist (1 meshes)"},
        BadGltf{"missing_scene", triangleWith("", "", R"("scene": 2, "scenes": [{"nodes": [0]}],
                    "nodes": [{"mesh": 0}])"),
                "scene 2 does not exist (1 scenes)"},
        BadGltf{"bad_matrix", triangleWith("", "", R"("scenes": [{"nodes": [0]}],
                    "nodes": [{"mesh": 0, "matrix": [1, 0, 0]}])"),
                "nodes[0].matrix has 3 numbers"},
        BadGltf{"missing_material",
                triangleWith("", std::string(kTrianglePrimitive) + R"(, "material": 2})"),
                "meshes[0].primitives[0]: material 2 does not exist (0 materials)"},
        BadGltf{"missing_texture",
                triangleWith("", "", R"("scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}])",
                             R"(, "materials": [{"normalTexture": {"index": 4}}])"),
                "materials[0].normalTexture: texture 4 does not exist (0 textures)"},
        BadGltf{"view_past_buffer",
                [] {
                    std::string json = triangleWith("");
                    const std::string from = R"("byteLength": 36})";
                    json.replace(json.find(from), from.size(), R"("byteLength": 3600})");
                    return json;
                }(),
                "buffer view 0 (3600 bytes from offset 0) reads past the end of buffer 0"},
        BadGltf{"required_extension",
                triangleWith("", "", R"("scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}])",
                             R"(, "extensionsUsed": ["KHR_draco_mesh_compression"],
                                  "extensionsRequired": ["KHR_draco_mesh_compression"])"),
                "requires the glTF extension 'KHR_draco_mesh_compression'"},
        BadGltf{"sparse_order",
                triangleWith(accessorsWith(0, R"({"bufferView": 0, "componentType": 5126,
                    "count": 3, "type": "VEC3", "sparse": {"count": 2,
                      "indices": {"bufferView": 3, "componentType": 5121},
                      "values": {"bufferView": 1}}})")),  // u8 view of u16 0: entries 0, 0
                "POSITION accessor 0: sparse index 0 (entry 1) is out of range or not increasing"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(GltfLoader, MissingBufferFileNamesIt) {
    const fs::path dir = test::scratchDir("gltf-missing-bin");
    std::string json = triangleGltf();
    const size_t uri = json.find("data:");
    json.replace(uri, json.find('"', uri) - uri, "gone.bin");
    writeFile(dir / "m.gltf", json);
    // Also absent from the working directory: only the glTF's folder is searched.
    const std::string message = test::errorMessage([&] { loadGltf(dir / "m.gltf"); });
    EXPECT_THAT(message, HasSubstr((dir / "m.gltf").string() + ": "));
    EXPECT_THAT(message, HasSubstr("File not found : gone.bin"));
}

TEST(GltfLoader, MissingFileIsAnOpenError) {
    const fs::path dir = test::scratchDir("gltf-missing");
    EXPECT_THAT(test::errorMessage([&] { loadGltf(dir / "none.glb"); }),
                HasSubstr("none.glb: cannot open: No such file or directory"));
}

TEST(GltfLoader, TruncatedGlbSaysWhatIsMissing) {
    const fs::path dir = test::scratchDir("gltf-truncated");
    const std::string whole = quadGlb();
    const auto errorAt = [&](size_t size) {
        writeFile(dir / "cut.glb", whole.substr(0, size));
        return test::errorMessage([&] { loadGltf(dir / "cut.glb"); });
    };
    EXPECT_THAT(errorAt(7),
                HasSubstr("cut.glb: truncated .glb: 7 bytes, the header alone needs 12"));
    EXPECT_THAT(errorAt(whole.size() - 1),
                HasSubstr(concat("cut.glb: truncated .glb: the header announces ", whole.size(),
                                 " bytes, the file has ", whole.size() - 1)));
    // A header whose length was patched to match the cut file: the BIN chunk lies.
    std::string patched = whole.substr(0, whole.size() - 8);
    const auto length = uint32_t(patched.size());
    std::memcpy(patched.data() + 8, &length, 4);
    writeFile(dir / "cut.glb", patched);
    EXPECT_THAT(test::errorMessage([&] { loadGltf(dir / "cut.glb"); }),
                HasSubstr("truncated .glb: the BIN chunk announces"));
}

// ------------------------------------------------------------------ loadGltfContents

// kHierarchyNodes with cameras: the perspective "main" on the root, the
// orthographic camera 1 on the mirrored node 2 (unnamed: "camera 1"), and
// camera 0 again on node 3, which is outside the default scene.
const char* kCameraNodes = R"(
    "scene": 1,
    "scenes": [{"nodes": [3]}, {"nodes": [0]}],
    "nodes": [
      {"name": "rig", "camera": 0, "translation": [10, 0, 0], "children": [1, 2]},
      {"mesh": 0, "rotation": [0, 0, 0.7071067811865476, 0.7071067811865476],
       "scale": [2, 2, 2]},
      {"mesh": 0, "camera": 1,
       "matrix": [-1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]},
      {"mesh": 0, "camera": 0, "translation": [0, 0, 100]}],
    "cameras": [
      {"name": "main", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}},
      {"type": "orthographic", "orthographic": {"xmag": 4, "ymag": 3, "znear": 0, "zfar": 9}}],)";

// `text` with its one occurrence of `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// Two loads of the same file give the same mesh and materials, bit for bit.
void expectSameMesh(const LoadedMesh& a, const LoadedMesh& b) {
    EXPECT_TRUE(test::sameBits(a.mesh.positions, b.mesh.positions));
    EXPECT_TRUE(test::sameBits(a.mesh.normals, b.mesh.normals));
    EXPECT_TRUE(test::sameBits(a.mesh.uvs, b.mesh.uvs));
    EXPECT_EQ(a.mesh.indices, b.mesh.indices);
    EXPECT_EQ(a.mesh.faceMaterials, b.mesh.faceMaterials);
    EXPECT_EQ(a.mesh.isPadded(), b.mesh.isPadded());
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) {
        SCOPED_TRACE(concat("material ", i));
        const MeshMaterial& x = a.materials[i];
        const MeshMaterial& y = b.materials[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.source, y.source);
        EXPECT_EQ(x.diffuse, y.diffuse);
        EXPECT_EQ(x.specular, y.specular);
        EXPECT_EQ(x.shininess, y.shininess);
        EXPECT_EQ(x.ior, y.ior);
        EXPECT_EQ(x.dissolve, y.dissolve);
        EXPECT_EQ(x.illum, y.illum);
        EXPECT_EQ(x.transmission, y.transmission);
        EXPECT_EQ(x.metallic, y.metallic);
        EXPECT_EQ(x.roughness, y.roughness);
        EXPECT_EQ(x.emission, y.emission);
        EXPECT_EQ(x.diffuseTexture, y.diffuseTexture);
        EXPECT_EQ(x.normalTexture, y.normalTexture);
        EXPECT_EQ(x.metallicRoughnessTexture, y.metallicRoughnessTexture);
        EXPECT_EQ(x.emissionTexture, y.emissionTexture);
    }
}

void expectSameCameras(const std::vector<GltfCamera>& a, const std::vector<GltfCamera>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        SCOPED_TRACE(concat("camera ", i));
        EXPECT_EQ(a[i].name, b[i].name);
        EXPECT_EQ(a[i].orthographic, b[i].orthographic);
        EXPECT_EQ(a[i].eye, b[i].eye);
        EXPECT_EQ(a[i].back, b[i].back);
        EXPECT_EQ(a[i].up, b[i].up);
        EXPECT_EQ(a[i].yfovDegrees, b[i].yfovDegrees);
        EXPECT_EQ(a[i].xmag, b[i].xmag);
        EXPECT_EQ(a[i].ymag, b[i].ymag);
    }
}

// One read and one parse give what loadGltf and loadGltfCameras give, on every
// file the tests above load, the DamagedHelmet too when ../shared/data is there.
TEST(GltfLoader, ContentsEqualLoadGltfAndLoadGltfCameras) {
    const fs::path dir = test::scratchDir("gltf-contents");
    writeFile(dir / "tri data.bin", Triangle().bytes.data);
    writeFile(dir / "tex dir" / "base color.png", "png");
    const std::pair<const char*, std::string> files[] = {
        {"pbr.gltf", pbrTriangleGltf()},
        {"default.gltf", triangleGltf()},
        {"Tri.GLTF", externalBufferGltf()},
        {"hierarchy.gltf", hierarchyGltf()},
        {"cameras.gltf", hierarchyGltf(kCameraNodes)},
        {"normals.gltf", slantedTriangleGltf()},
        {"interleaved.gltf", interleavedGltf()},
        {"flat.gltf", flatNormalsGltf()},
        {"lines.gltf", linesGltf()},
        {"textures.gltf", texturedGltf()},
        {"extensions.gltf", triangleGltf(kExtensionsUsed)},
        {"quad.glb", quadGlb()}};
    std::vector<fs::path> paths;
    for (const auto& [name, text] : files) {
        writeFile(dir / name, text);
        paths.push_back(dir / name);
    }
    const fs::path helmet = test::sharedData() / "damaged-helmet-gltf" / "DamagedHelmet.gltf";
    if (fs::exists(helmet)) paths.push_back(helmet);

    WarningCapture warnings;  // lines, textures and extensions warn
    for (const fs::path& file : paths) {
        SCOPED_TRACE(file.string());
        const GltfContents contents = loadGltfContents(file);
        expectSameMesh(contents.mesh, loadGltf(file));
        expectSameCameras(contents.cameras, loadGltfCameras(file));
    }

    // The cameras file places both cameras, in hierarchy order, and its mesh.
    const GltfContents cameras = loadGltfContents(dir / "cameras.gltf");
    EXPECT_EQ(cameras.mesh.mesh.triangleCount(), 2u);
    ASSERT_EQ(cameras.cameras.size(), 2u);
    EXPECT_EQ(cameras.cameras[0].name, "main");
    EXPECT_EQ(cameras.cameras[1].name, "camera 1");
    EXPECT_TRUE(cameras.cameras[1].orthographic);
    EXPECT_EQ(cameras.cameras[1].eye, Vec3(10, 0, 0));

    // The cache folders of the embedded images.
    for (const char* name : {"textures.gltf", "quad.glb"}) {
        for (const MeshMaterial& g : loadGltf(dir / name).materials) {
            for (const fs::path& image : {g.diffuseTexture, g.normalTexture})
                if (image.parent_path().filename().string().rfind("strahl-gltf-", 0) == 0)
                    fs::remove_all(image.parent_path());
        }
    }
}

// The first error is the one loadGltfCameras, then loadGltf would throw: the
// file's, the node hierarchy's and the cameras' before the mesh's.
TEST(GltfLoader, ContentsThrowTheFirstErrorOfLoadGltfCamerasThenLoadGltf) {
    const fs::path dir = test::scratchDir("gltf-contents-errors");
    const fs::path file = dir / "bad.gltf";
    const std::string good = hierarchyGltf(kCameraNodes);
    const auto contentsError = [&] { return test::errorMessage([&] { loadGltfContents(file); }); };
    const auto camerasError = [&] { return test::errorMessage([&] { loadGltfCameras(file); }); };
    const auto meshError = [&] { return test::errorMessage([&] { loadGltf(file); }); };

    // Unparsable: the same message from all three.
    writeFile(file, good.substr(0, good.size() / 2));
    EXPECT_THAT(contentsError(), HasSubstr("bad.gltf: "));
    EXPECT_EQ(contentsError(), camerasError());
    EXPECT_EQ(contentsError(), meshError());

    // Only the mesh is wrong: loadGltf's message.
    const std::string missingMaterial =
        replaced(good, R"("indices": 3}]}])", R"("indices": 3, "material": 5}]}])");
    writeFile(file, missingMaterial);
    EXPECT_EQ(loadGltfCameras(file).size(), 2u);
    EXPECT_EQ(contentsError(), meshError());
    EXPECT_THAT(contentsError(), HasSubstr("meshes[0].primitives[0]: material 5 does not exist"));

    // A camera and the mesh are wrong: the camera's message.
    writeFile(file, replaced(missingMaterial, R"("camera": 1,)", R"("camera": 7,)"));
    EXPECT_EQ(contentsError(), camerasError());
    EXPECT_THAT(contentsError(), HasSubstr("nodes[2]: camera 7 does not exist (2 cameras)"));
    EXPECT_NE(contentsError(), meshError());

    // The hierarchy and a material are wrong: the hierarchy's message, where
    // loadGltf alone, which converts materials first, names the material.
    writeFile(file, replaced(replaced(good, R"("children": [1, 2]})", R"("children": [1, 2, 0]})"),
                             R"("cameras": [)",
                             R"("materials": [{"normalTexture": {"index": 4}}], "cameras": [)"));
    EXPECT_EQ(contentsError(), camerasError());
    EXPECT_THAT(contentsError(), HasSubstr("nodes[0].children[2]: node 0 is its own ancestor"));
    EXPECT_THAT(meshError(), HasSubstr("materials[0].normalTexture: texture 4 does not exist"));
}

// The warnings of one load, once each: loadGltfCameras before loadGltf would
// repeat the file's own (here the unsupported extension).
TEST(GltfLoader, ContentsWarnWhatLoadGltfWarns) {
    const fs::path dir = test::scratchDir("gltf-contents-warnings");
    writeFile(dir / "lines.gltf", linesGltf(kExtensionsUsed));
    std::string loadWarnings;
    {
        WarningCapture warnings;
        loadGltf(dir / "lines.gltf");
        loadWarnings = warnings.text();
    }
    WarningCapture warnings;
    loadGltfContents(dir / "lines.gltf");
    EXPECT_EQ(warnings.text(), loadWarnings);
    EXPECT_THAT(warnings.text(), HasSubstr("ignoring the glTF extensions KHR_texture_transform"));
    EXPECT_THAT(warnings.text(), HasSubstr("mode 1 is not TRIANGLES (4)"));
    EXPECT_EQ(warnings.text().find("ignoring"), warnings.text().rfind("ignoring"));
}

// ------------------------------------------------------------------ shared data

TEST(GltfLoader, DamagedHelmetFromSharedData) {
    const fs::path file = test::sharedData() / "damaged-helmet-gltf" / "DamagedHelmet.gltf";
    if (!fs::exists(file))
        GTEST_SKIP() << "needs ../shared/data/damaged-helmet-gltf (the project's shared test "
                        "data set), which is not next to this checkout";
    WarningCapture warnings;
    const LoadedMesh m = loadMeshFile(file);
    EXPECT_EQ(warnings.text(), "");
    const TriangleMesh& mesh = m.mesh;
    EXPECT_EQ(mesh.triangleCount(), 15452u);  // 46356 indices
    EXPECT_EQ(mesh.vertexCount(), 14556u);
    EXPECT_EQ(mesh.normals.size(), 14556u);
    EXPECT_EQ(mesh.uvs.size(), 14556u);
    EXPECT_EQ(mesh.faceMaterials, std::vector<uint32_t>(15452, 0));
    for (const Vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-3f);
    // The node turns the y-up model by 90 degrees about x: y extent becomes z.
    const Bounds3 b = mesh.bounds();
    EXPECT_NEAR(b.min.x, -0.9474586f, 1e-5f);
    EXPECT_NEAR(b.max.x, 0.9424954f, 1e-5f);
    EXPECT_NEAR(b.min.z, -1.1871550f, 1e-5f);
    EXPECT_NEAR(b.max.z, 0.8128451f, 1e-5f);
    // glTF v in [1.0006, 1.9987] becomes 1 - v.
    for (const Vec2& uv : mesh.uvs) {
        ASSERT_GE(uv.y, -0.99867f);
        ASSERT_LE(uv.y, -0.00055f);
    }

    ASSERT_EQ(m.materials.size(), 1u);
    const MeshMaterial& g = m.materials[0];
    EXPECT_EQ(g.name, "Material_MR");
    EXPECT_EQ(g.emission, Color(1.0f));
    const fs::path dir = file.parent_path();
    EXPECT_EQ(g.diffuseTexture, dir / "Default_albedo.jpg");
    EXPECT_EQ(g.metallicRoughnessTexture, dir / "Default_metalRoughness.jpg");
    EXPECT_EQ(g.normalTexture, dir / "Default_normal.jpg");
    EXPECT_EQ(g.emissionTexture, dir / "Default_emissive.jpg");
    for (const fs::path& p :
         {g.diffuseTexture, g.metallicRoughnessTexture, g.normalTexture, g.emissionTexture})
        EXPECT_TRUE(fs::is_regular_file(p)) << p;
    // The fifth texture, Default_AO.jpg (occlusion), has no MeshMaterial field: a
    // path tracer computes occlusion itself.
    EXPECT_TRUE(fs::is_regular_file(dir / "Default_AO.jpg"));
}

}  // namespace
}  // namespace strahl
