// Mesh attributes read by materials (docs/materials.md, "Mesh attributes"):
// a PLY file's face and vertex attributes reach the BSDF at the hit, through
// Embree and the naive tracer alike, instanced or not; a material that reads an
// attribute its mesh lacks, or that sits on a shape that is no mesh, is one
// clear error when the world is built.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "albedo_probe.h"
#include "strahl/core/error.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// The unit square in z = 0 as two triangles, (0,0) (1,0) (1,1) red and
// (0,0) (1,1) (0,1) green, with a per-vertex heat of 0 on the left and 1 on
// the right (x).
fs::path writeSquare() {
    const fs::path dir = test::scratchDir("mesh-attribute-scene");
    std::ofstream(dir / "square.ply") << "ply\nformat ascii 1.0\n"
                                         "element vertex 4\nproperty float x\nproperty float y\n"
                                         "property float z\nproperty float heat_0\n"
                                         "element face 2\nproperty list uchar int vertex_indices\n"
                                         "property float color_0\nproperty float color_1\n"
                                         "property float color_2\nend_header\n"
                                         "0 0 0 0\n1 0 0 1\n1 1 0 1\n0 1 0 0\n"
                                         "3 0 1 2 1 0 0\n3 0 2 3 0 1 0\n";
    return dir;
}

World build(const std::string& material, const std::string& shapes,
            AccelKind accel = AccelKind::Embree, const std::string& groups = "[]") {
    const fs::path dir = writeSquare();
    const std::string text = R"({"materials": [)" + material + R"(], "shapes": [)" + shapes +
                             R"(], "groups": )" + groups + "}";
    BuildOptions options;
    options.accel = accel;
    return buildWorld(parseSceneText(text, dir / "scene.json"), options);
}

const std::string kSquare = R"({"type": "mesh", "file": "square.ply", "material": "m"})";

using test::albedoAt;

TEST(MeshAttributeScene, FaceColoursReachTheBsdfThroughEveryTracer) {
    const std::string material = R"({"name": "m", "color": {"attribute": "face_color", "scale": 0.5}})";
    for (const AccelKind accel : {AccelKind::Embree, AccelKind::Naive}) {
        const World world = build(material, kSquare, accel);
        EXPECT_EQ(albedoAt(world, 0.8f, 0.2f), Color(0.5f, 0.0f, 0.0f));
        EXPECT_EQ(albedoAt(world, 0.2f, 0.8f), Color(0.0f, 0.5f, 0.0f));
    }
}

TEST(MeshAttributeScene, VertexAttributesAreInterpolatedAndOneChannelIsGrey) {
    const World world = build(R"({"name": "m", "color": {"attribute": "vertex_heat"}})", kSquare);
    const Color c = albedoAt(world, 0.25f, 0.5f);
    EXPECT_NEAR(c.r, 0.25f, 1e-5f);
    EXPECT_EQ(c.g, c.r);
    EXPECT_EQ(c.b, c.r);
}

TEST(MeshAttributeScene, AScalarInputReadsAChannelAndInstancesKeepTheirAttributes) {
    // A blend weighted by the face colour's red channel: all of the second
    // (white) material on the red face, all of the first (black) on the green.
    const std::string material =
        R"({"name": "m", "type": "blend", "weight": {"attribute": "face_color", "channel": "r"},
            "materials": [{"color": 0}, {"color": 1}]})";
    const World world =
        build(material, R"({"type": "instance", "group": "g", "transform": [{"translate": [2, 0, 0]}]})",
              AccelKind::Embree, R"([{"name": "g", "shapes": [)" + kSquare + "]}]");
    EXPECT_EQ(albedoAt(world, 2.8f, 0.2f), Color(1.0f));
    EXPECT_EQ(albedoAt(world, 2.2f, 0.8f), Color(0.0f));
}

TEST(MeshAttributeScene, AMissingAttributeOrAShapeWithoutAttributesIsAnError) {
    EXPECT_THAT(test::errorMessage([&] {
                    build(R"({"name": "m", "color": {"attribute": "face_weight"}})", kSquare);
                }),
                HasSubstr("square.ply): material 'm' reads the mesh attribute 'face_weight', which "
                          "the mesh does not have (it has vertex_heat, face_color)"));
    EXPECT_THAT(test::errorMessage([&] {
                    build(R"({"name": "m", "color": {"attribute": "face_color"}})",
                          R"({"type": "implicit", "material": "m", "surface": {"type": "sphere"}})");
                }),
                HasSubstr("material 'm' reads the mesh attribute 'face_color', but this shape is not a mesh"));
}

TEST(MeshAttributeScene, AttributeKeysAreChecked) {
    EXPECT_THAT(test::errorMessage([&] {
                    build(R"({"name": "m", "color": {"attribute": "face_color", "wrap": "clamp"}})", kSquare);
                }),
                HasSubstr("/materials/0/color/wrap: not a key of a mesh attribute texture (allowed: attribute, scale)"));
    EXPECT_THAT(test::errorMessage([&] {
                    build(R"({"name": "m", "color": {"attribute": ""}})", kSquare);
                }),
                HasSubstr("/materials/0/color/attribute: must name an attribute"));
    EXPECT_THAT(test::errorMessage([&] {
                    build(R"({"name": "m", "opacity": {"attribute": "vertex_heat"}})", kSquare);
                }),
                HasSubstr("/materials/0/opacity: an opacity is read where rays are tested, through the uvs only"));
}

}  // namespace
}  // namespace strahl
