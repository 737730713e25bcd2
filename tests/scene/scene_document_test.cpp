// SceneDocument (strahl/scene/scene_document.h): command-line patches of the
// scene document, the errors they give, and the hash a render's fingerprint
// is built from — which every setting of the document changes.

#include "strahl/scene/scene_document.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "strahl/core/error.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kScene = R"({
  // a comment
  "film": { "width": 16, "height": 12 },
  "shapes": [ { "type": "mesh", "positions": [[-1,-1,0],[1,-1,0],[1,1,0]], "indices": [0,1,2] } ]
})";

SceneDocument jsonDocument(const std::string& text = kScene) {
    return SceneDocument::fromText(text, "scene.json");
}

TEST(ScenePatch, SetArgumentsAreJsonOrPlainStrings) {
    EXPECT_EQ(parseSetArgument("/render/spp=64").value, "64");
    EXPECT_EQ(parseSetArgument("/render/russian_roulette=false").value, "false");
    EXPECT_EQ(parseSetArgument("/film/aovs=[\"normal\",\"depth\"]").value, "[\"normal\",\"depth\"]");
    EXPECT_EQ(parseSetArgument("/render/integrator=path").value, "\"path\"");
    EXPECT_EQ(parseSetArgument("/render/integrator=\"path\"").value, "\"path\"");
    EXPECT_EQ(parseSetArgument("/film/outputs/0=a=b.exr").value, "\"a=b.exr\"");  // the first '='
    const ScenePatch p = parseSetArgument("/film/width=8");
    EXPECT_EQ(p.pointer, "/film/width");
    EXPECT_EQ(p.origin, "--set /film/width=8");
}

TEST(ScenePatch, MalformedSetArgumentsAreErrors) {
    EXPECT_EQ(test::errorMessage([] { parseSetArgument("/render/spp"); }),
              "--set /render/spp: expected POINTER=VALUE, such as /render/spp=64");
    EXPECT_EQ(test::errorMessage([] { parseSetArgument("render/spp=4"); }),
              "--set render/spp=4: the pointer must start with '/', such as /render/spp");
}

TEST(ScenePatch, PatchesChangeWhatIsParsedAndCreateMissingObjects) {
    SceneDocument doc = jsonDocument();
    doc.apply(parseSetArgument("/film/width=32"));
    doc.apply(parseSetArgument("/render/spp=7"));  // no "render" object in the file
    doc.apply(parseSetArgument("/render/integrator=path"));
    doc.apply(parseSetArgument("/shapes/0/positions/2=[1,2,0]"));
    const SceneDesc desc = doc.parse();
    EXPECT_EQ(desc.film.width, 32);
    EXPECT_EQ(desc.film.height, 12);
    EXPECT_EQ(desc.render.spp, 7);
    EXPECT_EQ(desc.render.integrator, "path");
    ASSERT_EQ(doc.patches().size(), 4u);
    EXPECT_EQ(doc.patches()[1].origin, "--set /render/spp=7");
}

TEST(ScenePatch, ALaterPatchWins) {
    SceneDocument doc = jsonDocument();
    doc.apply({"/render/spp", "4", "--spp 4"});
    doc.apply(parseSetArgument("/render/spp=9"));
    EXPECT_EQ(doc.parse().render.spp, 9);
}

TEST(ScenePatch, PatchesThatCannotApplyNameTheirOrigin) {
    SceneDocument doc = jsonDocument();
    EXPECT_EQ(test::errorMessage([&] { doc.apply(parseSetArgument("/film/width/x=1")); }),
              "scene.json: /film/width is a number, not an object (--set /film/width/x=1)");
    EXPECT_EQ(test::errorMessage([&] { doc.apply(parseSetArgument("/shapes/3/type=mesh")); }),
              "scene.json: /shapes is an array of 1 values; '3' is not an index in it "
              "(--set /shapes/3/type=mesh)");
    EXPECT_EQ(test::errorMessage([&] { doc.apply(parseSetArgument("/shapes/-/type=mesh")); }),
              "scene.json: /shapes is an array of 1 values; '-' is not an index in it "
              "(--set /shapes/-/type=mesh)");
    EXPECT_EQ(test::errorMessage([&] { doc.apply({"/film/~2", "1", "--width 1"}); }),
              "--width 1: '/film/~2' is not a JSON pointer (RFC 6901: /key/key/index)");
    EXPECT_EQ(test::errorMessage([] { parseSetArgument("/film/~2=1"); }),
              "--set /film/~2=1: '/film/~2' is not a JSON pointer (RFC 6901: /key/key/index)");
    EXPECT_TRUE(doc.patches().empty());  // nothing half-applied
}

TEST(ScenePatch, AParseErrorAtAPatchedPlaceNamesThePatch) {
    SceneDocument doc = jsonDocument();
    doc.apply({"/film/width", "30000", "--width 30000"});
    doc.apply({"/film/height", "30000", "--height 30000"});
    doc.apply(parseSetArgument("/render/seed=3"));
    EXPECT_EQ(test::errorMessage([&] { doc.parse(); }),
              "scene.json: /film: width x height = 900000000 pixels, more than the limit of "
              "268435456 (2^28) (set by --width 30000, --height 30000)");
    SceneDocument typo = jsonDocument();
    typo.apply(parseSetArgument("/render/spq=4"));
    EXPECT_NE(test::errorMessage([&] { typo.parse(); }).find("(set by --set /render/spq=4)"),
              std::string::npos);
    // An error elsewhere is left as it is.
    SceneDocument other = jsonDocument(R"({"film": {"width": 0}, "shapes": []})");
    other.apply(parseSetArgument("/render/spp=2"));
    EXPECT_EQ(test::errorMessage([&] { other.parse(); }),
              "scene.json: /film/width: must be between 1 and 32768, got 0");
}

// Scene files are read by the format their extension names
// (src/scene/scene_formats.h); strahl's JSON takes every extension no other
// format claims, in any case.
TEST(SceneFormats, JsonIsTheDefaultForAnyExtension) {
    for (const char* name : {"scene.json", "scene.JSON", "scene.strahl", "scene"}) {
        const SceneDesc desc = SceneDocument::fromText(kScene, name).parse();
        EXPECT_EQ(desc.film.width, 16) << name;
    }
    EXPECT_TRUE(test::contains(
        test::errorMessage([] { SceneDocument::fromText("{ broken", "scene.Json"); }),
        "scene.Json:1:"));
}

TEST(SceneHash, IgnoresCommentsAndSpacingButNotValues) {
    const uint64_t h = jsonDocument().hash();
    EXPECT_EQ(SceneDocument::fromText(json::parse(kScene, nullptr, true, true).dump(4), "x.json")
                  .hash(),
              h);
    SceneDocument doc = jsonDocument();
    doc.apply(parseSetArgument("/film/width=17"));
    EXPECT_NE(doc.hash(), h);
    // Leaving out the value two documents differ in gives the same hash (the
    // parts of a split render differ only in their samples per pixel).
    SceneDocument part1 = jsonDocument(), part2 = jsonDocument();
    part1.apply(parseSetArgument("/render/spp=17"));
    part2.apply(parseSetArgument("/render/spp=5"));
    EXPECT_NE(part1.hash(), part2.hash());
    EXPECT_EQ(part1.hash({"/render/spp"}), part2.hash({"/render/spp"}));
    EXPECT_EQ(jsonDocument().hash({"/no/such/key"}), h);
}

// Every leaf of the document: its pointer and a different value of the same type.
void collectLeaves(const json& value, const std::string& pointer,
                   std::vector<std::pair<std::string, json>>& out) {
    if (value.is_object()) {
        for (const auto& [key, child] : value.items()) collectLeaves(child, pointer + "/" + key, out);
    } else if (value.is_array()) {
        for (size_t i = 0; i < value.size(); ++i)
            collectLeaves(value[i], pointer + "/" + std::to_string(i), out);
    } else if (value.is_boolean()) {
        out.emplace_back(pointer, !value.get<bool>());
    } else if (value.is_number()) {
        out.emplace_back(pointer, value.get<double>() + 1.0);
    } else if (value.is_string()) {
        out.emplace_back(pointer, value.get<std::string>() + "x");
    } else {
        out.emplace_back(pointer, 1);
    }
}

TEST(SceneHash, EverySceneKeyChangedBySetChangesTheHash) {
    // Every scene the project ships for tests and the default scene: every
    // value in them, changed through --set, changes the hash (and so the
    // fingerprint of the image).
    size_t keys = 0;
    for (const char* name : {"scenes/default.json", "scenes/regression/cornell_direct.json",
                             "scenes/regression/instances.json", "scenes/regression/parametric.json",
                             "scenes/regression/implicit_direct.json",
                             "scenes/statistical/glossy_room.json"}) {
        const fs::path file = test::sourceDir() / name;
        const std::string text = test::readFile(file);
        const uint64_t base = SceneDocument::fromText(text, file).hash();
        std::vector<std::pair<std::string, json>> leaves;
        collectLeaves(json::parse(text, nullptr, true, true), "", leaves);
        ASSERT_FALSE(leaves.empty()) << name;
        std::set<uint64_t> seen{base};
        for (const auto& [pointer, changed] : leaves) {
            SceneDocument doc = SceneDocument::fromText(text, file);
            doc.apply(parseSetArgument(pointer + "=" + changed.dump()));
            EXPECT_TRUE(seen.insert(doc.hash()).second) << name << ": " << pointer;
            ++keys;
        }
    }
    EXPECT_GT(keys, 100u);
}

}  // namespace
}  // namespace strahl
