// "curves" shapes in scene files (docs/scene-format.md, "Curves"): every key
// parsed into the CurveSetDesc it documents, strand files, the transform of
// points and radii, and one message naming the JSON pointer for bad input.

#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <string>

#include "scene_test_helpers.h"
#include "strahl/integrator/world.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

using testing::HasSubstr;

using test::parseShapes;
using test::shapesError;

TEST(CurveScene, InlineStrandsWithEveryKey) {
    const SceneDesc d = parseShapes(R"({"type": "curves", "name": "fur", "basis": "catmull_rom", "profile": "flat",
        "flat_segments": 8, "radius": 0.05, "strands": [4, 5],
        "points": [[0,0,0], [0,0,1], [0,1,2], [0,1,3,0.1], [1,0,0], [1,0,1], [1,1,2], [1,1,3], [1,2,4]],
        "transform": [{"scale": 2}]})");
    const ShapeDesc& s = d.shapes.at(0);
    EXPECT_EQ(s.kind, ShapeKind::Curves);
    EXPECT_EQ(s.name, "fur");
    EXPECT_EQ(s.material, "default");
    EXPECT_EQ(s.curves.basis, CurveBasis::CatmullRom);
    EXPECT_EQ(s.curves.type, CurveType::Flat);
    EXPECT_EQ(s.curves.flatSegments, 8);
    EXPECT_EQ(s.curves.points[0].w, 0.05f);  // the shape's radius
    EXPECT_EQ(s.curves.points[3].w, 0.1f);   // the point's own
    EXPECT_EQ(s.curves.segments, (std::vector<uint32_t>{0, 4, 5}));
    // Built: points moved, radii scaled by the transform's mean scale.
    const World world = buildWorld(d, BuildOptions{});
    const CurveSet* c = world.shapes.at(0).user->asCurves();
    ASSERT_NE(c, nullptr);
    EXPECT_EQ(c->desc().points[3], Vec4(0, 2, 6, 0.2f));
    EXPECT_EQ(c->primitiveCount(), 3u);
}

TEST(CurveScene, StrandFilesAreReadWhenTheWorldIsBuilt) {
    const auto dir = test::scratchDir("curve-scene");
    test::writeFile(dir / "fur.txt", "0 0 0 0.1\n0 0 1 0.1\n\n1 0 0 0.1\n1 0 1 0.1\n1 0 2 0.1\n");
    const SceneDesc d = parseShapes(R"({"type": "curves", "basis": "linear", "file": "fur.txt"})", dir / "scene.json");
    EXPECT_EQ(buildWorld(d, BuildOptions{}).shapes.at(0).user->primitiveCount(), 3u);
    test::writeFile(dir / "fur.txt", "0 0 0 0.1\n0 0 nan 0.1\n");
    EXPECT_THAT(test::errorMessage([&] { buildWorld(d, BuildOptions{}); }),
                HasSubstr("fur.txt:2: z coordinate 'nan' is not a finite float"));
    test::writeFile(dir / "fur.txt", "0 0 0 -1\n");
    EXPECT_THAT(test::errorMessage([&] { buildWorld(d, BuildOptions{}); }), HasSubstr("fur.txt:1: radius -1 is negative"));
    test::writeFile(dir / "fur.txt", "# nothing\n");
    EXPECT_THAT(test::errorMessage([&] { buildWorld(d, BuildOptions{}); }), HasSubstr("fur.txt: no control points"));
}

TEST(CurveScene, BadInputNamesItsPlace) {
    EXPECT_THAT(shapesError(R"({"type": "curves"})"), HasSubstr("/shapes/0: needs 'points'"));
    EXPECT_THAT(
        shapesError(R"({"type": "curves", "points": [[0,0,0], [1,1,1], [2,2,2], [3,3,3]]})"),
        HasSubstr("/shapes/0/points/0: gives no radius"));
    EXPECT_THAT(shapesError(R"({"type": "curves", "points": [[0,0,0,-1], [1,1,1,1], [2,2,2,1], [3,3,3,1]]})"),
                HasSubstr("/shapes/0/points/0: radius -1 must be >= 0"));
    EXPECT_THAT(shapesError(R"({"type": "curves", "radius": 1, "strands": [2, 2], "points": [[0,0,0], [1,1,1], [2,2,2], [3,3,3]]})"),
                HasSubstr("/shapes/0/strands: curves '/shapes/0': strand 0 has 2 control points, but a bspline segment needs 4"));
    EXPECT_THAT(shapesError(R"({"type": "curves", "radius": 1, "strands": [3], "points": [[0,0,0], [1,1,1], [2,2,2], [3,3,3]]})"),
                HasSubstr("/shapes/0/strands: the strands hold 3 points, but 'points' has 4"));
    EXPECT_THAT(shapesError(R"({"type": "curves", "flat_segments": 3, "radius": 1, "points": [[0,0,0], [1,1,1], [2,2,2], [3,3,3]]})"),
                HasSubstr("/shapes/0/flat_segments: only for \"profile\": \"flat\""));
    EXPECT_THAT(shapesError(R"({"type": "curves", "basis": "hermite", "radius": 1, "points": [[0,0,0], [1,1,1]]})"),
                HasSubstr("/shapes/0/basis"));
    EXPECT_THAT(shapesError(R"({"type": "curves", "file": "a.txt", "points": [[0,0,0,1]]})"),
                HasSubstr("'file' and 'points' are exclusive"));
    EXPECT_THAT(shapesError(R"({"type": "curves", "file": "no-such-file.txt"})"), HasSubstr("no-such-file.txt"));
    EXPECT_THAT(shapesError(R"({"type": "curves", "radius": 1, "points": [[0,0,0], [1,1,1], [2,2,2], [3,3,3]], "normals": []})"),
                HasSubstr("normals"));
}

}  // namespace
}  // namespace strahl

namespace strahl {
namespace {

TEST(CurveScene, HairMaterialsTakeAColourAnAbsorptionOrMelanin) {
    const auto hairOf = [](const std::string& keys) {
        const SceneDesc d = parseSceneText(R"({"materials": [{"name": "h", "type": "hair", )" + keys +
                                               R"(}], "shapes": [{"type": "curves", "material": "h", "radius": 0.1,
                                               "points": [[0,0,0], [0,0,1], [0,1,2], [0,1,3]]}]})",
                                           "scene.json");
        return std::get<HairMaterial>(d.materials.at(0).material.kind);
    };
    const HairMaterial brown = hairOf(R"("beta_m": 0.2, "alpha": -3, "ior": 1.6)");
    EXPECT_FALSE(brown.byColor);
    EXPECT_NEAR(brown.sigmaA.b, 1.3f * 1.37f, 1e-6f);  // eumelanin 1.3 by default
    EXPECT_EQ(brown.betaM, 0.2f);
    EXPECT_EQ(brown.alpha, -3.0f);
    EXPECT_EQ(brown.ior, 1.6f);
    const HairMaterial red = hairOf(R"("eumelanin": 0.5, "pheomelanin": 2)");
    EXPECT_NEAR(red.sigmaA.r, 0.5f * 0.419f + 2.0f * 0.187f, 1e-6f);
    EXPECT_TRUE(hairOf(R"("color": [0.6, 0.4, 0.2])").byColor);
    EXPECT_EQ(hairOf(R"("sigma_a": [0.1, 0.2, 0.3])").sigmaA, Color(0.1f, 0.2f, 0.3f));
    const auto error = [](const std::string& keys) {
        return test::errorMessage([&] {
            parseSceneText(R"({"materials": [{"name": "h", "type": "hair", )" + keys + R"(}], "shapes": []})",
                           "scene.json");
        });
    };
    EXPECT_THAT(error(R"("color": 0.5, "eumelanin": 1)"), HasSubstr("give one of 'color', 'sigma_a' or 'eumelanin'"));
    EXPECT_THAT(error(R"("beta_n": 1.5)"), HasSubstr("/materials/0/beta_n"));
    EXPECT_THAT(error(R"("alpha": 90)"), HasSubstr("/materials/0/alpha"));
}

}  // namespace
}  // namespace strahl
