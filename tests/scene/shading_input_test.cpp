// Bad input to the shading parts of a scene file — materials, textures,
// lights, the render and film settings, the thin lens — and the exact message
// each gives (docs/scene-format.md, "Errors"). Problems the parser can see
// name the JSON pointer; files that exist but are not images are found when
// the world is built, and name the material or light and the file; a missing
// texture in an OBJ's .mtl is only a warning.

#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "scene_test_helpers.h"
#include "strahl/core/error.h"
#include "strahl/integrator/environment_light.h"
#include "strahl/material/diffuse.h"
#include "strahl/material/plastic.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using test::contains;
using test::errorWith;
using test::kTriangleShapes;
using test::writeFile;

std::string materialError(const std::string& material) {
    return errorWith(R"("materials": [)" + material + "]");
}

std::string lightError(const std::string& light) {
    return errorWith(R"("lights": [)" + light + "]");
}

// A scene file in `dir` made of kTriangleShapes plus `sections`, parsed with its
// real path (so relative files resolve against `dir`).
SceneDesc parseIn(const fs::path& dir, const std::string& sections) {
    const std::string text = "{" + sections + ", " + kTriangleShapes + "}";
    writeFile(dir / "scene.json", text);
    return parseSceneText(text, dir / "scene.json");
}

// Text that no image reader accepts, saved under an image extension.
const std::string kNotAnImage = "this is a text file, not an image\n";

// --- materials -----------------------------------------------------------------

TEST(ShadingInput, UnknownMaterialTypeListsTheTypes) {
    EXPECT_EQ(materialError(R"({"name": "m", "type": "velvet"})"),
              "scene.json: /materials/0/type: must be one of diffuse, phong, blinn, conductor, "
              "dielectric, thin_dielectric, diffuse_transmission, plastic, coated_conductor, metallic_roughness, principled, hair, blend, emissive, got 'velvet'");
}

TEST(ShadingInput, KeyOfAnotherTypeListsTheAllowedKeys) {
    EXPECT_EQ(materialError(R"({"name": "m", "type": "conductor", "color": [1, 0.8, 0.3]})"),
              "scene.json: /materials/0: unknown key 'color' for a conductor material (allowed: "
              "name, type, emission, two_sided, normal_map, bump_map, mapping, opacity, opacity_cutoff, metal, eta, k, roughness, "
              "roughness_u, roughness_v, distribution, masking)");
}

TEST(ShadingInput, NegativeColourNamesTheComponent) {
    EXPECT_EQ(materialError(R"({"name": "m", "color": [0.5, -0.25, 0.5]})"),
              "scene.json: /materials/0/color/1: must be >= 0, got -0.25");
}

TEST(ShadingInput, OverflowingNumberIsASyntaxErrorAtTheNumber) {
    // 1e999 exceeds even a double: the JSON reader reports it where it is.
    EXPECT_EQ(test::errorMessage([] {
                  parseSceneText("{\"materials\": [{\"name\": \"m\",\n \"color\": 1e999}], " +
                                     kTriangleShapes + "}",
                                 "scene.json");
              }),
              "scene.json:2:11: syntax error: number overflow parsing '1e999'");
}

TEST(ShadingInput, NumberBeyondTheFloatRangeIsRejectedNotInfinite) {
    // 1e39 is a double but no float: rejected rather than read as inf.
    EXPECT_EQ(materialError(R"({"name": "m", "emission": [1e39, 1, 1]})"),
              "scene.json: /materials/0/emission/0: must be a finite number within float "
              "range, got 1e+39");
    EXPECT_EQ(materialError(R"({"name": "m", "color": 1e39})"),
              "scene.json: /materials/0/color: must be a finite number within float range, got "
              "1e+39");
}

TEST(ShadingInput, RoughnessAboveOne) {
    EXPECT_EQ(materialError(R"({"name": "m", "type": "plastic", "roughness": 1.5})"),
              "scene.json: /materials/0/roughness: must be in [0, 1], got 1.5");
}

TEST(ShadingInput, IorBelowOne) {
    EXPECT_EQ(materialError(R"({"name": "m", "type": "dielectric", "ior": 0.5})"),
              "scene.json: /materials/0/ior: must be in [1.0001, 4], got 0.5");
}

TEST(ShadingInput, UnknownMetalListsThePresets) {
    EXPECT_EQ(materialError(R"({"name": "m", "type": "conductor", "metal": "unobtainium"})"),
              "scene.json: /materials/0/metal: unknown metal 'unobtainium' (known: gold, silver, "
              "copper, aluminium, chromium, iron, titanium, nickel, platinum)");
}

TEST(ShadingInput, MicrofacetModelKeys) {
    EXPECT_EQ(materialError(R"({"name": "m", "type": "conductor", "distribution": "phong"})"),
              "scene.json: /materials/0/distribution: must be one of ggx, beckmann, got 'phong'");
    EXPECT_EQ(materialError(R"({"name": "m", "type": "dielectric", "masking": "none"})"),
              "scene.json: /materials/0/masking: must be one of height_correlated, separable, "
              "got 'none'");
    EXPECT_EQ(materialError(
                  R"({"name": "m", "type": "conductor", "roughness": 0.2, "roughness_u": 0.1})"),
              "scene.json: /materials/0: give either 'roughness' or 'roughness_u' and "
              "'roughness_v', not both");
    EXPECT_EQ(materialError(R"({"name": "m", "type": "conductor", "roughness_v": 0.1})"),
              "scene.json: /materials/0: 'roughness_u' and 'roughness_v' go together");
    EXPECT_EQ(materialError(R"({"name": "m", "type": "plastic", "coat_transmittance": 1})"),
              "scene.json: /materials/0/coat_transmittance: expected a string, got number 1");
}

TEST(ShadingInput, BlendKeys) {
    EXPECT_EQ(materialError(R"({"name": "m", "type": "blend"})"),
              "scene.json: /materials/0: needs 'materials': [first, second], two material objects");
    EXPECT_EQ(materialError(R"({"name": "m", "type": "blend", "materials": [{"type": "diffuse"}]})"),
              "scene.json: /materials/0/materials: expected [first, second], two material objects, "
              "got 1");
    EXPECT_EQ(materialError(R"({"name": "m", "type": "blend", "materials": [{}, {"emission": 1}]})"),
              "scene.json: /materials/0/materials/1: unknown key 'emission' for a diffuse material "
              "(allowed: type, color, diffuse)");
    EXPECT_EQ(materialError(R"({"name": "m", "type": "blend", "weight": 2, "materials": [{}, {}]})"),
              "scene.json: /materials/0/weight: must be in [0, 1], got 2");
    const SceneDesc ok = parseSceneText(
        R"({"materials": [{"name": "m", "type": "blend", "weight": 0.25, "materials": [)"
        R"({"type": "conductor", "metal": "gold"}, {"type": "blend", "materials": [{}, {"color": 0.1}]}]}], )" +
            kTriangleShapes + "}",
        "scene.json");
    const auto& blend = std::get<BlendMaterial>(ok.materials.at(0).material.kind);
    EXPECT_EQ(blend.weight.value, 0.25f);
    EXPECT_TRUE(std::holds_alternative<ConductorMaterial>(blend.parts[0]->kind));
    const auto& inner = std::get<BlendMaterial>(blend.parts[1]->kind);
    EXPECT_EQ(std::get<DiffuseMaterial>(inner.parts[1]->kind).color.value, Color(0.1f));
}

TEST(ShadingInput, CoatedConductorKeys) {
    EXPECT_EQ(materialError(R"({"name": "m", "type": "coated_conductor", "thickness": -1})"),
              "scene.json: /materials/0/thickness: must be in [0, 100], got -1");
    EXPECT_EQ(materialError(R"({"name": "m", "type": "coated_conductor", "metal": "gold", "k": 2})"),
              "scene.json: /materials/0: give either 'metal' or 'eta' and 'k', not both");
    EXPECT_EQ(materialError(R"({"name": "m", "type": "coated_conductor", "ior": 0.5})"),
              "scene.json: /materials/0/ior: must be in [1.0001, 4], got 0.5");
    const SceneDesc ok = parseSceneText(
        R"({"materials": [{"name": "m", "type": "coated_conductor", "metal": "gold", "roughness": 0.3,
            "coat_roughness": 0.1, "ior": 1.6, "thickness": 0.01}], )" + kTriangleShapes + "}",
        "scene.json");
    const auto& m = std::get<CoatedConductorMaterial>(ok.materials.at(0).material.kind);
    EXPECT_EQ(m.layers->coatEta(), 1.6f);
    EXPECT_EQ(m.layers->thickness(), 0.01f);
    EXPECT_EQ(m.eta, findMetalPreset("gold")->eta);
}

TEST(ShadingInput, PrincipledKeys) {
    EXPECT_EQ(materialError(R"({"name": "m", "type": "principled", "specular": 0.5, "ior": 1.5})"),
              "scene.json: /materials/0: give either 'specular' or 'ior', not both");
    EXPECT_EQ(materialError(R"({"name": "m", "type": "principled", "thin": true, "clearcoat": 0.5})"),
              "scene.json: /materials/0: 'clearcoat' does not apply to a thin principled material");
    EXPECT_EQ(materialError(R"({"name": "m", "type": "principled", "diffuse_transmission": 1})"),
              "scene.json: /materials/0: 'diffuse_transmission' applies to a thin principled "
              "material only (\"thin\": true)");
    EXPECT_EQ(materialError(R"({"name": "m", "type": "principled", "sheen": {"checkerboard":
                  {"color0": [1, 0, 0], "color1": 0}}})"),
              "scene.json: /materials/0/sheen/checkerboard/color0: a scalar checkerboard takes "
              "numbers, got array");
    const SceneDesc ok = parseSceneText(
        R"({"materials": [{"name": "m", "type": "principled", "specular": 0.5, "metallic":
            {"checkerboard": {"color0": 0.7, "color1": 0.1, "scale": 25}}}], )" +
            kTriangleShapes + "}",
        "scene.json");
    const auto& principled = std::get<PrincipledMaterial>(ok.materials.at(0).material.kind);
    EXPECT_NEAR(principled.eta, 1.5f, 1e-6f);  // Mitsuba's specular 0.5 is eta 1.5
    ASSERT_TRUE(principled.metallic.checkerboard.has_value());
    EXPECT_EQ(principled.metallic.checkerboard->color1, Color(0.1f));
    EXPECT_TRUE(principled.metallic.varies());
}

TEST(ShadingInput, BumpMapKeys) {
    const fs::path dir = test::scratchDir("shading-bump");
    test::writeFile(dir / "h.png", "not read while parsing");
    const auto error = [&](const std::string& material) {
        return test::errorMessage([&] { parseIn(dir, R"("materials": [)" + material + "]"); });
    };
    EXPECT_THAT(error(R"({"name": "m", "bump_map": {"texture": "h.png"}, "normal_map": "h.png"})"),
                testing::HasSubstr("/materials/0/bump_map: give either 'normal_map' or 'bump_map', not both"));
    EXPECT_THAT(error(R"({"name": "m", "bump_map": "h.png"})"),
                testing::HasSubstr("/materials/0/bump_map: expected {\"texture\": file, \"scale\": ...}"));
    EXPECT_THAT(error(R"({"name": "m", "bump_map": {"texture": "h.png"}, "mapping": "triplanar"})"),
                testing::HasSubstr("/materials/0/bump_map: a bump map is read through the uvs: it cannot be mapped triplanar"));
    const SceneDesc ok = parseIn(dir, R"("materials": [{"name": "m", "bump_map": {"texture": "h.png", "scale": 0.02, "shadowing": true}}])");
    EXPECT_EQ(ok.materials[0].material.bumpScale, 0.02f);
    EXPECT_TRUE(ok.materials[0].material.terminatorShadowing);
}

TEST(ShadingInput, PhongThatReflectsMoreThanItReceives) {
    EXPECT_EQ(materialError(R"({"name": "m", "type": "phong", "color": 0.75, "specular": 0.5})"),
              "scene.json: /materials/0: color + specular must not exceed 1 in any channel "
              "(energy conservation), got (1.25, 1.25, 1.25)");
}

TEST(ShadingInput, EmissiveWithoutEmission) {
    EXPECT_EQ(materialError(R"({"name": "lamp", "type": "emissive"})"),
              "scene.json: /materials/0: an emissive material needs 'emission'");
}

// --- textures ------------------------------------------------------------------

TEST(ShadingInput, MissingTextureFileNamesThePointer) {
    const fs::path dir = test::scratchDir("shading-missing-texture");
    const std::string message = test::errorMessage([&] {
        parseIn(dir, R"("materials": [{"name": "m", "color": {"texture": "wood.png"}}])");
    });
    EXPECT_EQ(message, (dir / "scene.json").string() +
                           ": /materials/0/color/texture: no such texture file 'wood.png' "
                           "(looked at " + (dir / "wood.png").string() + ")");
}

TEST(ShadingInput, TextureSamplingKeys) {
    const fs::path dir = test::scratchDir("shading-texture-sampling");
    writeFile(dir / "wood.png", kNotAnImage);  // not read while parsing
    const SceneDesc desc = parseIn(dir, R"("materials": [{"name": "m", "color": {"texture": "wood.png",
        "wrap": "mirror", "filter": "nearest", "uv_transform": [[2, 0, -0.5], [0.5, 3, 0.25]]}}])");
    const auto& diffuse = std::get<DiffuseMaterial>(desc.materials.at(0).material.kind);
    const TextureRef& t = diffuse.color.texture;
    EXPECT_EQ(t.sampling.wrap, TextureWrap::Mirror);
    EXPECT_EQ(t.sampling.filter, TextureFilter::Nearest);
    // (s', t') = (2 s - 0.5, 0.5 s + 3 t + 0.25).
    const Vec3 mapped = t.stTransform * Vec3(1.0f, 2.0f, 1.0f);
    EXPECT_FLOAT_EQ(mapped.x, 1.5f);
    EXPECT_FLOAT_EQ(mapped.y, 6.75f);
    EXPECT_FLOAT_EQ(mapped.z, 1.0f);

    const auto error = [&](const std::string& material) {
        return test::errorMessage([&] { parseIn(dir, R"("materials": [)" + material + "]"); });
    };
    EXPECT_TRUE(contains(error(R"({"name": "m", "color": {"texture": "wood.png", "wrap": "tile"}})"),
                         "/materials/0/color/wrap: must be one of repeat, mirror, clamp"));
    EXPECT_TRUE(contains(error(R"({"name": "m", "color": {"texture": "wood.png", "uv_transform": [[1, 0], [0, 1]]}})"),
                         "/materials/0/color/uv_transform/0: expected a row of three numbers"));
    EXPECT_TRUE(contains(error(R"({"name": "m", "mapping": "triplanar",
        "color": {"texture": "wood.png", "uv_transform": [[2, 0, 0], [0, 2, 0]]}})"),
                         "/materials/0/mapping: a triplanar mapping has no uv"));
    EXPECT_TRUE(contains(error(R"({"name": "m", "color": {"checkerboard": {}, "filter": "nearest"}})"),
                         "/materials/0/color/filter: applies to image textures, not to a checkerboard"));
}

TEST(ShadingInput, MixKeys) {
    const fs::path dir = test::scratchDir("shading-mix");
    test::writeFile(dir / "wood.png", "not read while parsing");
    const SceneDesc ok = parseIn(dir, R"("materials": [{"name": "m", "color": {"mix": [[1, 0, 0],
        {"mix": [0.2, {"texture": "wood.png"}]}], "amount": {"checkerboard": {"color0": 0, "color1": 1}},
        "scale": 2}, "roughness": {"mix": [0.1, 0.9], "amount": 0.25}, "type": "plastic"}])");
    const auto& plastic = std::get<PlasticMaterial>(ok.materials.at(0).material.kind);
    ASSERT_TRUE(plastic.color.mix);
    EXPECT_EQ(plastic.color.value, Color(2.0f));
    EXPECT_EQ(plastic.color.mix->a.value, Color(1.0f, 0.0f, 0.0f));
    ASSERT_TRUE(plastic.color.mix->b.mix);  // nested, amount 0.5 by default
    EXPECT_EQ(plastic.color.mix->b.mix->amount.value, 0.5f);
    EXPECT_EQ(plastic.color.mix->b.mix->b.texture.file.filename(), "wood.png");
    EXPECT_TRUE(plastic.color.mix->amount.checkerboard.has_value());
    EXPECT_TRUE(plastic.color.varies());
    ASSERT_TRUE(plastic.roughness.mix);
    EXPECT_EQ(plastic.roughness.mix->amount.value, 0.25f);
    EXPECT_FALSE(plastic.roughness.varies());

    EXPECT_EQ(materialError(R"({"name": "m", "color": {"mix": [1, 0, 0]}})"),
              "scene.json: /materials/0/color/mix: expected [a, b], the two inputs the amount "
              "blends, got 3 values");
    EXPECT_EQ(materialError(R"({"name": "m", "color": {"mix": [1, 0], "weight": 0.5}})"),
              "scene.json: /materials/0/color/weight: not a key of a mix (allowed: mix, amount, scale)");
    EXPECT_EQ(materialError(R"({"name": "m", "color": {"mix": [1, 0], "amount": 1.5}})"),
              "scene.json: /materials/0/color/amount: must be in [0, 1], got 1.5");
    EXPECT_THAT(materialError(R"({"name": "m", "opacity": {"mix": [1, 0]}})"),
                testing::HasSubstr("/materials/0/opacity: an opacity is one image or a number: a mix cannot be one"));
    std::string deep = "0.5";
    for (int i = 0; i < 17; ++i) deep = R"({"mix": [)" + deep + ", 1]}";
    EXPECT_THAT(materialError(R"({"name": "m", "color": )" + deep + "}"),
                testing::HasSubstr("mixes nested deeper than 16 are not supported"));
}

TEST(ShadingInput, TextureThatIsNotAnImageFailsWhenTheWorldIsBuilt) {
    const fs::path dir = test::scratchDir("shading-fake-texture");
    writeFile(dir / "wood.png", kNotAnImage);
    const SceneDesc desc =
        parseIn(dir, R"("materials": [{"name": "m", "color": {"texture": "wood.png"}}])");
    const std::string message = test::errorMessage([&] { buildWorld(desc, BuildOptions{}); });
    const std::string prefix =
        "scene.json: /materials/0: " + (dir / "wood.png").string() + ": cannot read the texture: ";
    EXPECT_EQ(message.substr(0, prefix.size()), prefix) << message;
    EXPECT_GT(message.size(), prefix.size()) << "OpenImageIO's reason is missing: " << message;
    EXPECT_FALSE(contains(message, "\n")) << message;
}

// --- environment light ---------------------------------------------------------

TEST(ShadingInput, MissingEnvironmentFileNamesThePointer) {
    const fs::path dir = test::scratchDir("shading-missing-environment");
    const std::string message = test::errorMessage([&] {
        parseIn(dir, R"("lights": [{"type": "environment", "file": "sky.hdr"}])");
    });
    EXPECT_EQ(message, (dir / "scene.json").string() +
                           ": /lights/0/file: no such image file 'sky.hdr' (looked at " +
                           (dir / "sky.hdr").string() + ")");
}

TEST(ShadingInput, EnvironmentThatIsNotAnImageFailsWhenTheWorldIsBuilt) {
    const fs::path dir = test::scratchDir("shading-fake-environment");
    writeFile(dir / "sky.hdr", kNotAnImage);
    const SceneDesc desc =
        parseIn(dir, R"("lights": [{"type": "environment", "file": "sky.hdr"}])");
    const std::string message = test::errorMessage([&] { buildWorld(desc, BuildOptions{}); });
    const std::string prefix = "scene.json: /lights/0: " + (dir / "sky.hdr").string() +
                               ": cannot read the environment image: ";
    EXPECT_EQ(message.substr(0, prefix.size()), prefix) << message;
    EXPECT_GT(message.size(), prefix.size()) << "OpenImageIO's reason is missing: " << message;
    EXPECT_FALSE(contains(message, "\n")) << message;
}

TEST(ShadingInput, NegativeEnvironmentScale) {
    const fs::path dir = test::scratchDir("shading-environment-scale");
    writeFile(dir / "sky.hdr", kNotAnImage);  // never opened: the parser stops first
    const std::string message = test::errorMessage([&] {
        parseIn(dir, R"("lights": [{"type": "environment", "file": "sky.hdr", "scale": -2}])");
    });
    EXPECT_EQ(message, (dir / "scene.json").string() + ": /lights/0/scale: must be >= 0, got -2");
}

TEST(ShadingInput, EnvironmentRowsAreCentredOrFromPoleToPole) {
    const fs::path dir = test::scratchDir("shading-environment-rows");
    writeFile(dir / "sky.hdr", kNotAnImage);  // never opened while parsing
    const auto rowsOf = [&](const std::string& key) {
        const SceneDesc desc = parseIn(
            dir, R"("lights": [{"type": "environment", "file": "sky.hdr")" + key + "}]");
        return std::get<EnvironmentLight>(desc.lights.at(0).light.kind).rows;
    };
    EXPECT_EQ(rowsOf(""), RowLayout::Centred);
    EXPECT_EQ(rowsOf(R"(, "rows": "poles")"), RowLayout::PoleToPole);
    const std::string message = test::errorMessage([&] { rowsOf(R"(, "rows": "edges")"); });
    EXPECT_TRUE(contains(message, "/lights/0/rows: ")) << message;
    EXPECT_TRUE(contains(message, "must be one of")) << message;
    EXPECT_TRUE(contains(message, "centred")) << message;
}

// --- spot light ----------------------------------------------------------------

const std::string kSpot = R"("type": "spot", "position": [0, 2, 0], "direction": [0, -1, 0])";

TEST(ShadingInput, SpotFalloffStartBeyondTheCone) {
    EXPECT_EQ(lightError("{" + kSpot + R"(, "cone_angle": 20, "falloff_start": 25})"),
              "scene.json: /lights/0/falloff_start: must not exceed cone_angle (20 degrees), "
              "got 25");
    // Against the default cone of 30 degrees, which the message names.
    EXPECT_EQ(lightError("{" + kSpot + R"(, "falloff_start": 40})"),
              "scene.json: /lights/0/falloff_start: must not exceed cone_angle (30 degrees), "
              "got 40");
}

// A 2 x 2 float image: red, green / blue, white.
void writeQuadImage(const fs::path& image) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(image.string());
    ASSERT_TRUE(out);
    const float texels[] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
    ASSERT_TRUE(out->open(image.string(), OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, texels));
    ASSERT_TRUE(out->close());
}

// A spot projecting an image (Mitsuba's spot): the quad image spread over the
// cone's base square; the image's s runs along up × axis and its t along
// axis × (up × axis).
TEST(ShadingInput, SpotProjectsItsImageOverTheCone) {
    const fs::path dir = test::scratchDir("shading-spot-image");
    writeQuadImage(dir / "quad.exr");
    // Along -y from (0, 1, 0); up +z, so s runs along z × -y = +x and t along
    // -y × x = +z. The cone's half-angle is 45 degrees: the image spans
    // [-1, 1]² on the plane y = 0.
    const SceneDesc desc = parseIn(dir, R"("lights": [{"type": "spot", "position": [0, 1, 0],
        "direction": [0, -1, 0], "cone_angle": 45, "falloff_start": 45, "up": [0, 0, 1],
        "intensity": 2, "texture": {"texture": "quad.exr", "filter": "nearest"}}])");
    const World world = buildWorld(desc, BuildOptions{});
    ASSERT_TRUE(world.textures);
    const Light& spot = world.lights.at(0);
    const auto at = [&](float x, float z) {
        LightSampleContext ctx{Vec3(x, 0, z), Vec3(0, 1, 0), world.textures.get()};
        const auto s = sampleLi(spot, ctx, Vec2(0.5f));
        return s ? Color(s->L * (1.0f + x * x + z * z) / 2.0f) : Color(0.0f);  // / (I / r²)
    };
    EXPECT_EQ(at(-0.5f, -0.5f), Color(1, 0, 0));  // s < 1/2, t < 1/2: top left
    EXPECT_EQ(at(0.5f, -0.5f), Color(0, 1, 0));
    EXPECT_EQ(at(-0.5f, 0.5f), Color(0, 0, 1));
    EXPECT_EQ(at(0.5f, 0.5f), Color(1, 1, 1));

    EXPECT_TRUE(contains(lightError(R"({"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0],
        "up": [0, 0, 1], "texture": {"texture": "quad.exr"}})"),
                         "/lights/0/texture/texture: no such texture file"));
    const std::string along = test::errorMessage([&] {
        parseIn(dir, R"("lights": [{"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0],
            "up": [0, 1, 0], "texture": {"texture": "quad.exr"}}])");
    });
    EXPECT_TRUE(contains(along, "/lights/0/up: the image's up ([0, 1, 0]) is along the spot's axis")) << along;
    const std::string wide = test::errorMessage([&] {
        parseIn(dir, R"("lights": [{"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0],
            "cone_angle": 100, "texture": {"texture": "quad.exr"}}])");
    });
    EXPECT_TRUE(contains(wide, "/lights/0/texture: a projected image needs cone_angle < 90 degrees")) << wide;
    EXPECT_TRUE(contains(lightError("{" + kSpot + R"(, "up": [0, 0, 1]})"),
                         "/lights/0/up: only a spot with a 'texture' has an up side"));
}

// A projector shows its image as on a screen seen from behind it: the
// image's right on the projector's right (axis × up), its top towards up.
TEST(ShadingInput, ProjectorShowsItsImageUnmirrored) {
    const fs::path dir = test::scratchDir("shading-projector-image");
    writeQuadImage(dir / "quad.exr");
    // From (0, 1, 0) down, up +z: right = -y × z = -x. fov 90: the image
    // spans [-1, 1]² on the floor.
    const SceneDesc desc = parseIn(dir, R"("lights": [{"type": "projector", "position": [0, 1, 0],
        "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "irradiance": 2,
        "texture": {"texture": "quad.exr", "filter": "nearest"}}])");
    const World world = buildWorld(desc, BuildOptions{});
    const Light& projector = world.lights.at(0);
    const auto at = [&](float x, float z) {
        LightSampleContext ctx{Vec3(x, 0, z), Vec3(0, 1, 0), world.textures.get()};
        const auto s = sampleLi(projector, ctx, Vec2(0.5f));
        if (!s) return Color(0.0f);
        return Color(s->L * glm::dot(s->wi, ctx.n) / 2.0f);  // irradiance / the scene's 2
    };
    const auto near = [](const Color& a, const Color& b) { return glm::length(a - b) < 1e-5f; };
    EXPECT_TRUE(near(at(0.5f, 0.5f), Color(1, 0, 0)));    // left, top
    EXPECT_TRUE(near(at(-0.5f, 0.5f), Color(0, 1, 0)));   // right, top
    EXPECT_TRUE(near(at(0.5f, -0.5f), Color(0, 0, 1)));   // left, bottom
    EXPECT_TRUE(near(at(-0.5f, -0.5f), Color(1, 1, 1)));  // right, bottom
    EXPECT_EQ(at(1.2f, 0.0f), Color(0.0f));               // outside the frustum
    EXPECT_TRUE(contains(lightError(R"({"type": "projector", "position": [0, 1, 0], "direction": [0, -1, 0],
        "up": [0, 0, 1], "fov": 180})"),
                         "/lights/0/fov: must be strictly between 0 and 180 degrees, got 180"));
    EXPECT_TRUE(contains(lightError(R"({"type": "projector", "position": [0, 1, 0], "direction": [0, -1, 0],
        "fov": 40})"),
                         "the image's up is along the projector's axis"));
}

TEST(ShadingInput, SpotConeAngleZero) {
    EXPECT_EQ(lightError("{" + kSpot + R"(, "cone_angle": 0})"),
              "scene.json: /lights/0/cone_angle: must be in [0.01, 180] degrees, got 0");
}

TEST(ShadingInput, SpotWithBothDirectionAndLookAt) {
    EXPECT_EQ(lightError("{" + kSpot + R"(, "look_at": [0, 0, 0]})"),
              "scene.json: /lights/0: give exactly one of 'direction' and 'look_at'");
}

// --- render --------------------------------------------------------------------

TEST(ShadingInput, MaxDepthNegative) {
    EXPECT_EQ(errorWith(R"("render": {"integrator": "path", "max_depth": -1})"),
              "scene.json: /render/max_depth: must be between 0 and 1024, got -1");
}

TEST(ShadingInput, MaxDepthTooLarge) {
    EXPECT_EQ(errorWith(R"("render": {"integrator": "path", "max_depth": 2000})"),
              "scene.json: /render/max_depth: must be between 0 and 1024, got 2000");
}

TEST(ShadingInput, AoSamplesZero) {
    EXPECT_EQ(errorWith(R"("render": {"integrator": "ao", "ao_samples": 0})"),
              "scene.json: /render/ao_samples: must be between 1 and 4096, got 0");
}

// --- film filter ---------------------------------------------------------------

TEST(ShadingInput, UnknownFilterListsTheFilters) {
    EXPECT_EQ(errorWith(R"("film": {"filter": "mitchell"})"),
              "scene.json: /film/filter: must be one of box, gaussian, blackman-harris, tent, got "
              "'mitchell'");
    EXPECT_EQ(errorWith(R"("film": {"filter": {"type": "mitchell", "radius": 2}})"),
              "scene.json: /film/filter/type: must be one of box, gaussian, blackman-harris, tent, got "
              "'mitchell'");
}

TEST(ShadingInput, FilterRadiusZero) {
    EXPECT_EQ(errorWith(R"("film": {"filter": {"type": "gaussian", "radius": 0}})"),
              "scene.json: /film/filter/radius: must be greater than 0 and at most 16 pixels, "
              "got 0");
}

// --- camera --------------------------------------------------------------------

TEST(ShadingInput, NegativeApertureRadius) {
    EXPECT_EQ(errorWith(R"("camera": {"aperture_radius": -1})"),
              "scene.json: /camera/aperture_radius: must be at least 0, got -1");
}

TEST(ShadingInput, FocusDistanceZero) {
    EXPECT_EQ(errorWith(R"("camera": {"aperture_radius": 0.1, "focus_distance": 0})"),
              "scene.json: /camera/focus_distance: must be greater than 0, got 0");
}

// --- OBJ materials -------------------------------------------------------------

// Collects mesh-loader warnings for the lifetime of the object.
class WarningCapture {
public:
    WarningCapture() {
        setMeshWarningHandler([this](const std::string& m) { messages_.push_back(m); });
    }
    ~WarningCapture() { setMeshWarningHandler(nullptr); }
    WarningCapture(const WarningCapture&) = delete;
    WarningCapture& operator=(const WarningCapture&) = delete;
    const std::vector<std::string>& messages() const { return messages_; }

private:
    std::vector<std::string> messages_;
};

TEST(ShadingInput, MissingMtlTextureIsAWarningAndKeepsTheConstantColour) {
    const fs::path dir = test::scratchDir("shading-mtl-texture");
    writeFile(dir / "tri.mtl", "newmtl red\nKd 0.6 0.1 0.1\nmap_Kd missing.png\n");
    writeFile(dir / "tri.obj",
              "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
    const std::string text = R"({"shapes": [{"type": "mesh", "file": "tri.obj"}]})";
    writeFile(dir / "scene.json", text);
    const SceneDesc desc = parseSceneText(text, dir / "scene.json");

    WarningCapture warnings;
    const World world = buildWorld(desc, BuildOptions{});
    ASSERT_EQ(warnings.messages().size(), 1u);
    EXPECT_EQ(warnings.messages()[0], (dir / "tri.mtl").string() +
                                          ":3: texture 'missing.png' not found; material 'red' "
                                          "gets no diffuse texture");

    // The material table: the built-in default, then the OBJ's "red".
    ASSERT_EQ(world.materials.size(), 2u);
    const Material& red = world.materials[1];
    EXPECT_EQ(red.name, "tri/red");
    ASSERT_TRUE(std::holds_alternative<DiffuseMaterial>(red.kind));
    EXPECT_FALSE(std::get<DiffuseMaterial>(red.kind).color.texture.valid());
    EXPECT_EQ(std::get<DiffuseMaterial>(red.kind).color.value, Color(0.6f, 0.1f, 0.1f));
}

// A mesh whose triangles all use one of its file's materials keeps that
// material alone, without a per-triangle slot table; a mesh of two keeps the
// table and both.
TEST(ShadingInput, MeshOfOneMaterialDropsItsPerTriangleSlots) {
    const fs::path dir = test::scratchDir("shading-uniform-slots");
    writeFile(dir / "two.mtl", "newmtl red\nKd 0.6 0.1 0.1\nnewmtl blue\nKd 0.1 0.1 0.6\n");
    const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
    writeFile(dir / "uniform.obj",
              "mtllib two.mtl\n" + quad + "usemtl blue\nf 1 2 3\nf 1 3 4\n");
    writeFile(dir / "mixed.obj",
              "mtllib two.mtl\n" + quad + "usemtl red\nf 1 2 3\nusemtl blue\nf 1 3 4\n");
    const std::string text = R"({"shapes": [{"type": "mesh", "file": "uniform.obj"},
                                            {"type": "mesh", "file": "mixed.obj"}]})";
    writeFile(dir / "scene.json", text);
    const World world = buildWorld(parseSceneText(text, dir / "scene.json"), BuildOptions{});
    ASSERT_EQ(world.shapes.size(), 2u);

    const SceneShape& uniform = world.shapes[0];
    EXPECT_TRUE(uniform.mesh.faceMaterials.empty());
    ASSERT_EQ(uniform.materialOfSlot.size(), 1u);
    EXPECT_EQ(world.materials[uniform.materialOfSlot[0]].name, "uniform/blue");
    for (uint32_t prim = 0; prim < 2; ++prim) {
        Hit hit;
        hit.geomID = 0;
        hit.primID = prim;
        hit.u = hit.v = 0.25f;
        const Ray ray{Vec3(0.5f, 0.5f, 1.0f), Vec3(0.0f, 0.0f, -1.0f)};
        EXPECT_EQ(world.material(hit, world.interaction(ray, hit)).name, "uniform/blue");
    }

    const SceneShape& mixed = world.shapes[1];
    EXPECT_EQ(mixed.mesh.faceMaterials, (std::vector<uint32_t>{0, 1}));
    ASSERT_EQ(mixed.materialOfSlot.size(), 2u);
    EXPECT_EQ(world.materials[mixed.materialOfSlot[0]].name, "mixed/red");
    EXPECT_EQ(world.materials[mixed.materialOfSlot[1]].name, "mixed/blue");
}

}  // namespace
}  // namespace strahl
