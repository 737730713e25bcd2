// Mixes of textured inputs (material/textured.h, ColorMix and FloatMix):
// (1 − amount) a + amount b at each point, the amount itself an input; deep
// copies; and that every texture inside a mix is visited for binding.

#include <gtest/gtest.h>

#include "strahl/material/material.h"
#include "strahl/material/textured.h"

namespace strahl {
namespace {

// A mix whose amount is a checkerboard of 0 and 1 shows a in one square and
// b in the other; a constant amount blends them.
TEST(TextureMix, BlendsTwoColoursByTheAmountAtThePoint) {
    ColorMix mix;
    mix.a.value = Color(1.0f, 0.0f, 0.0f);
    mix.b.value = Color(0.0f, 0.0f, 1.0f);
    mix.amount.value = 1.0f;
    mix.amount.checkerboard = Checkerboard{Color(0.0f), Color(1.0f), Vec2(1.0f)};
    TexturedColor color;
    color.value = Color(2.0f);
    color.mix = NodeBox<ColorMix>(mix);
    const TextureMapping mapping;
    ShadingPoint sp;
    sp.uv = Vec2(0.25f, 0.75f);  // color0 of the checkerboard: amount 0
    EXPECT_EQ(evaluateColor(color, mapping, sp, nullptr), Color(2.0f, 0.0f, 0.0f));
    sp.uv = Vec2(0.75f, 0.75f);  // amount 1
    EXPECT_EQ(evaluateColor(color, mapping, sp, nullptr), Color(0.0f, 0.0f, 2.0f));
    color.mix->amount = TexturedFloat{0.25f, {}, 0};
    const Color blended = evaluateColor(color, mapping, sp, nullptr);
    EXPECT_FLOAT_EQ(blended.r, 2.0f * 0.75f);
    EXPECT_FLOAT_EQ(blended.g, 0.0f);
    EXPECT_FLOAT_EQ(blended.b, 2.0f * 0.25f);
    EXPECT_TRUE(color.varies() == false);  // constants only
    color.mix->b.checkerboard = Checkerboard{};
    EXPECT_TRUE(color.varies());
}

TEST(TextureMix, ScalarsMixAndNest) {
    // mix(0.2, mix(0.4, 0.8, 0.5), 0.5) = 0.5 * 0.2 + 0.5 * 0.6 = 0.4
    FloatMix inner{TexturedFloat{0.4f, {}, 0}, TexturedFloat{0.8f, {}, 0}, TexturedFloat{0.5f, {}, 0}};
    TexturedFloat innerInput{1.0f, {}, 0};
    innerInput.mix = NodeBox<FloatMix>(inner);
    TexturedFloat f{1.0f, {}, 0};
    f.mix = NodeBox<FloatMix>(FloatMix{TexturedFloat{0.2f, {}, 0}, innerInput, TexturedFloat{0.5f, {}, 0}});
    const TextureMapping mapping;
    const ShadingPoint sp;
    EXPECT_FLOAT_EQ(evaluateFloat(f, mapping, sp, nullptr), 0.4f);
}

TEST(TextureMix, CopiesAreDeep) {
    TexturedColor original;
    original.mix = NodeBox<ColorMix>(ColorMix{});
    original.mix->a.value = Color(0.5f);
    TexturedColor copy = original;
    copy.mix->a.value = Color(0.9f);
    EXPECT_EQ(original.mix->a.value, Color(0.5f));
    copy = original;
    EXPECT_EQ(copy.mix->a.value, Color(0.5f));
    const TexturedColor moved = std::move(copy);
    EXPECT_EQ(moved.mix->a.value, Color(0.5f));
}

// The world binds a material's textures through forEachTexture: those
// inside mixes must be visited too, the amount's as data.
TEST(TextureMix, EveryTextureInsideIsVisitedWithItsEncoding) {
    Material m = Material::diffuse("m", Color(1.0f));
    TexturedColor color;
    ColorMix mix;
    mix.a.texture.file = "a.png";
    mix.b.texture.file = "b.png";
    mix.amount.texture.file = "mask.png";
    color.mix = NodeBox<ColorMix>(mix);
    std::get<DiffuseMaterial>(m.kind).color = color;
    std::vector<std::pair<std::string, TextureEncoding>> seen;
    m.forEachTexture([&](TextureRef& t, TextureEncoding e) {
        if (!t.file.empty()) seen.emplace_back(t.file.string(), e);
    });
    ASSERT_EQ(seen.size(), 3u);
    EXPECT_EQ(seen[0], std::make_pair(std::string("a.png"), TextureEncoding::Color));
    EXPECT_EQ(seen[1], std::make_pair(std::string("b.png"), TextureEncoding::Color));
    EXPECT_EQ(seen[2], std::make_pair(std::string("mask.png"), TextureEncoding::Data));
}

}  // namespace
}  // namespace strahl
