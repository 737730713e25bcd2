// "subdivision" shapes in scene files (docs/scene-format.md, "Subdivision
// surfaces"): every key parsed into the cage it documents, OBJ cages, the
// transform, displacement by formula and by image, and one message naming
// the JSON pointer (or the file and line) for bad input.

#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <cmath>
#include <string>

#include <OpenImageIO/imageio.h>

#include "scene_test_helpers.h"
#include "strahl/geometry/subdivision_surface.h"
#include "strahl/integrator/world.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

#include "../../src/scene/subdivision_parser.h"  // internal to the scene module

namespace strahl {
namespace {

using testing::HasSubstr;

constexpr const char* kCube = R"("positions": [[-1,-1,-1],[1,-1,-1],[-1,1,-1],[1,1,-1],[-1,-1,1],[1,-1,1],[-1,1,1],[1,1,1]],
    "faces": [[0,2,3,1],[4,5,7,6],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]])";

std::string cube(const std::string& extra) {
    std::string s = R"({"type": "subdivision", )";
    s.append(kCube);
    if (!extra.empty()) s.append(", ").append(extra);
    s.append("}");
    return s;
}

using test::parseShapes;
using test::shapesError;

const SubdivisionSurface& surfaceOf(const World& world) {
    const SubdivisionSurface* s = world.shapes.at(0).user->asSubdivision();
    if (!s) throw std::runtime_error("not a subdivision surface");
    return *s;
}

TEST(SubdivisionScene, InlineCageWithEveryKey) {
    const SceneDesc d = parseShapes(cube(R"("name": "box", "levels": 4, "boundary": "pin_corners",
        "uvs": [[0,0],[1,0],[0,1],[1,1],[0,0],[1,0],[0,1],[1,1]],
        "creases": [[4, 5, "inf"], [5, 7, 2.5]], "corners": [[0, 1.5]], "holes": [2],
        "transform": [{"scale": 2}])"));
    const ShapeDesc& s = d.shapes.at(0);
    EXPECT_EQ(s.kind, ShapeKind::Subdivision);
    EXPECT_EQ(s.name, "box");
    EXPECT_EQ(s.material, "default");
    const SubdivisionCage& c = s.subdivision.cage;
    EXPECT_EQ(s.subdivision.levels, 4);
    EXPECT_EQ(c.boundary, SubdivisionBoundary::PinCorners);
    EXPECT_EQ(c.faceSizes, (std::vector<uint32_t>(6, 4)));
    EXPECT_EQ(c.creaseEdges, (std::vector<uint32_t>{4, 5, 5, 7}));
    EXPECT_TRUE(std::isinf(c.creaseWeights[0]));
    EXPECT_EQ(c.creaseWeights[1], 2.5f);
    EXPECT_EQ(c.cornerVertices, (std::vector<uint32_t>{0}));
    EXPECT_EQ(c.holes, (std::vector<uint32_t>{2}));
    EXPECT_EQ(c.uvs.size(), 8u);
    // Built: the cage moved by the transform, refined.
    const World world = buildWorld(d, BuildOptions{});
    const SubdivisionSurface& surface = surfaceOf(world);
    EXPECT_EQ(surface.cage().positions[7], DVec3(2, 2, 2));
    EXPECT_EQ(surface.tessellationRate(), 16);
    EXPECT_EQ(surface.refinedQuadCount(), 5u * 256u);  // the hole has none
    EXPECT_THAT(surface.describe(), HasSubstr("6 faces (1 holes), 4 levels"));
}

TEST(SubdivisionScene, FormulaDisplacementInObjectUnits) {
    // h = 0.5 · 0.1 + 0.02 at every point, doubled by the transform's scale:
    // the face centre moves from 2 · 68/81 by 2 · 0.07.
    const SceneDesc d = parseShapes(cube(R"("levels": 2, "transform": [{"scale": 2}],
        "displacement": {"formula": "a * 0.1", "parameters": {"a": 0.5}, "offset": 0.02})"));
    const World world = buildWorld(d, BuildOptions{});
    const SubdivisionSurface& surface = surfaceOf(world);
    ASSERT_TRUE(surface.displaced());
    EXPECT_NEAR(surface.pointAt(1, 0.5f, 0.5f).z, 2.0 * (68.0 / 81.0 + 0.07), 1e-6);
    EXPECT_THAT(surface.describe(), HasSubstr("displaced by 'a * 0.1' + 0.02"));
}

TEST(SubdivisionScene, ImageDisplacementReadsTheCagesUvs) {
    // A 2 × 2 image of 0.25 everywhere: every point moves out by 0.25 · scale.
    const auto dir = test::scratchDir("subdivision-image");
    const float pixels[4] = {0.25f, 0.25f, 0.25f, 0.25f};
    auto out = OIIO::ImageOutput::create((dir / "h.exr").string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open((dir / "h.exr").string(), OIIO::ImageSpec(2, 2, 1, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels));
    out->close();
    const SceneDesc d = parseShapes(cube(R"("levels": 2, "uvs": [[0,0],[1,0],[0,1],[1,1],[0,0],[1,0],[0,1],[1,1]],
        "displacement": {"image": "h.exr", "scale": 0.4})"), dir / "scene.json");
    const World world = buildWorld(d, BuildOptions{});
    const SubdivisionSurface& surface = surfaceOf(world);
    EXPECT_NEAR(surface.pointAt(1, 0.5f, 0.5f).z, 68.0 / 81.0 + 0.1, 1e-6);
    EXPECT_THAT(shapesError(cube(R"("displacement": {"image": "h.exr"})")), HasSubstr("displacement image"));
}

TEST(SubdivisionScene, ObjCagesKeepTheirPolygons) {
    const auto dir = test::scratchDir("subdivision-obj");
    test::writeFile(dir / "cage.obj",
                    "# a cube\nv -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n"
                    "vt 0 0\nvt 1 1\nvn 0 0 1\ns 1\n"
                    "f 1/1 3/1 4/1 2/1\nf 5/2 6/2 8/2 7/2\nf 1/1 2/1 6/2 5/2\nf 3 7 8 4\nf -8 -4 -2 -6\nf 2//1 4//1 8//1 6//1\n");
    const SceneDesc d = parseShapes(R"({"type": "subdivision", "file": "cage.obj", "levels": 3})", dir / "scene.json");
    const World world = buildWorld(d, BuildOptions{});
    const SubdivisionSurface& surface = surfaceOf(world);
    EXPECT_EQ(surface.cage().faceSizes, (std::vector<uint32_t>(6, 4)));
    EXPECT_TRUE(surface.cage().uvs.empty());  // not every corner has one
    EXPECT_NEAR(surface.pointAt(1, 0.5f, 0.5f).z, 68.0 / 81.0, 1e-9);
    test::writeFile(dir / "cage.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
    EXPECT_THAT(test::errorMessage([&] { buildWorld(d, BuildOptions{}); }),
                HasSubstr("cage.obj:3: a face of 2 vertices (3 to 15)"));
    test::writeFile(dir / "cage.obj", "v 0 0 0\nv 1 0 nan\nf 1 2 3\n");
    EXPECT_THAT(test::errorMessage([&] { buildWorld(d, BuildOptions{}); }),
                HasSubstr("cage.obj:2: expected a finite number, got 'nan'"));
    test::writeFile(dir / "cage.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
    EXPECT_THAT(test::errorMessage([&] { buildWorld(d, BuildOptions{}); }),
                HasSubstr("cage.obj:3: vertex index 3 is out of range (2 so far)"));
    test::writeFile(dir / "cage.txt", "");
    EXPECT_THAT(test::errorMessage([&] {
                    parseShapes(R"({"type": "subdivision", "file": "cage.txt"})",
                                dir / "scene.json");
                }),
                HasSubstr("a cage file must be an OBJ file"));
}

TEST(SubdivisionScene, LevelsFromScreenSpaceEdgeLength) {
    // The cube's nearest edges (length 2) are 5 units from the eye of a
    // 40°, 128-pixel-high camera: a pixel there is 2 tan 20° · 5 / 128 =
    // 0.028 units, so an edge spans 70 pixels and needs 2^5 > 70 / 4 segments
    // for 4 pixels, 2^7 > 70 for 1.
    const auto levelsFor = [](const std::string& pixels) {
        std::string text = R"({"camera": {"eye": [0, -6, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 40},
            "film": {"width": 128, "height": 128}, "shapes": [)";
        text.append(cube(R"("max_edge_pixels": )" + pixels)).append("]}");
        const World world = buildWorld(parseSceneText(text, "scene.json"), BuildOptions{});
        return std::make_pair(surfaceOf(world).desc().levels, surfaceOf(world).describe());
    };
    const auto [five, text] = levelsFor("4");
    EXPECT_EQ(five, 5);
    EXPECT_THAT(text, HasSubstr("5 levels (from max_edge_pixels 4, 32 segments per edge"));
    EXPECT_EQ(levelsFor("1").first, 7);
    EXPECT_EQ(levelsFor("1000").first, 1);
    // The memory limit caps them: 24 quads after one level, 24 · 4^(L−1) at
    // L, 150 bytes each: 200 KB hold 3 levels (58 KB) but not 4 (230 KB).
    SubdivisionCage cage = parseShapes(cube("")).shapes.at(0).subdivision.cage;
    const auto tiny = [](const DVec3&) { return 1e-3; };
    bool capped = false;
    EXPECT_EQ(scene_detail::levelsForEdgeLength(cage, tiny, 0, capped), 8);
    EXPECT_FALSE(capped);
    EXPECT_EQ(scene_detail::levelsForEdgeLength(cage, tiny, 200000, capped), 3);
    EXPECT_TRUE(capped);
    EXPECT_THAT(shapesError(cube(R"("levels": 2, "max_edge_pixels": 3)")),
                HasSubstr("give 'levels' or 'max_edge_pixels', not both"));
}

TEST(SubdivisionScene, BadInputNamesItsPlace) {
    EXPECT_THAT(shapesError(R"({"type": "subdivision"})"), HasSubstr("/shapes/0: needs 'positions' and 'faces'"));
    EXPECT_THAT(shapesError(cube(R"("levels": 9)")), HasSubstr("/shapes/0/levels"));
    EXPECT_THAT(shapesError(R"({"type": "subdivision", "positions": [[0,0,0],[1,0,0]], "faces": [[0,1]]})"),
                HasSubstr("/shapes/0/faces/0: expected an array of 3 to 15 vertex indices"));
    EXPECT_THAT(shapesError(R"({"type": "subdivision", "positions": [[0,0,0],[1,0,0],[0,1,0]], "faces": [[0,1,3]]})"),
                HasSubstr("/shapes/0/faces/0/2"));
    EXPECT_THAT(shapesError(cube(R"("creases": [[0, 7, 1]])")),
                HasSubstr("scene.json: /shapes/0: the cage: crease 0 (0-7) is not an edge of the mesh"));
    EXPECT_THAT(shapesError(cube(R"("creases": [[0, 1, -1]])")),
                HasSubstr("/shapes/0/creases/0/2"));
    EXPECT_THAT(shapesError(cube(R"("creases": [[0, 1, "infinite"]])")), HasSubstr("/shapes/0/creases/0/2"));
    EXPECT_THAT(shapesError(cube(R"("creases": [[0, 1]])")), HasSubstr("expected [vertex, vertex, sharpness]"));
    EXPECT_THAT(shapesError(cube(R"("corners": [[9, 1]])")), HasSubstr("corner 0 names vertex 9, but there are 8"));
    EXPECT_THAT(shapesError(cube(R"("holes": [6])")), HasSubstr("hole 6 is not a face (6 faces)"));
    EXPECT_THAT(shapesError(cube(R"("boundary": "none")")), HasSubstr("/shapes/0/boundary"));
    EXPECT_THAT(shapesError(cube(R"("displacement": {"formula": "x +"})")), HasSubstr("/shapes/0/displacement/formula"));
    EXPECT_THAT(shapesError(cube(R"("displacement": {"formula": "x", "image": "h.png"})")),
                HasSubstr("give 'formula' or 'image', not both"));
    EXPECT_THAT(shapesError(cube(R"("displacement": {"scale": 2})")), HasSubstr("needs 'formula'"));
    EXPECT_THAT(shapesError(cube(R"("uvs": [[0,0]])")), HasSubstr("/shapes/0/uvs: expected one [u, v] per position (8)"));
    EXPECT_THAT(shapesError(cube(R"("flip_normals": true)")),
                HasSubstr("unknown key 'flip_normals' (allowed: type, name, material, transform, motion, positions, "
                          "faces, uvs, file, levels, max_edge_pixels, creases, corners, holes, boundary, displacement)"));
}

}  // namespace
}  // namespace strahl
