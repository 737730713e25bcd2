// The procedural checkerboard of textured colours (material/textured.h): its
// squares in image-texture coordinates (s, t) = (u, 1 − v), as Mitsuba's
// checkerboard places them, and that it needs no texture system.

#include <gtest/gtest.h>

#include "strahl/material/textured.h"

namespace strahl {
namespace {

TEST(Checkerboard, ColorZeroWhereBothHalvesAgree) {
    Checkerboard c;  // Mitsuba's defaults: 0.4 and 0.2, one square per unit
    // (s, t) = (0.25, 0.25): both lower halves -> color0; v = 1 - t.
    EXPECT_EQ(c.at(Vec2(0.25f, 0.75f)), Color(0.4f));
    EXPECT_EQ(c.at(Vec2(0.75f, 0.25f)), Color(0.4f));  // both upper halves
    EXPECT_EQ(c.at(Vec2(0.75f, 0.75f)), Color(0.2f));
    EXPECT_EQ(c.at(Vec2(0.25f, 0.25f)), Color(0.2f));
    c.scale = Vec2(5.0f, 5.0f);  // 5 x 5 squares
    EXPECT_EQ(c.at(Vec2(0.05f, 0.95f)), Color(0.4f));
    EXPECT_EQ(c.at(Vec2(0.15f, 0.95f)), Color(0.2f));
    EXPECT_EQ(c.at(Vec2(1.05f, 0.95f)), Color(0.4f));  // repeats beyond [0, 1]
}

TEST(Checkerboard, ATexturedColourEvaluatesItWithoutATextureSystem) {
    TexturedColor color;
    color.value = Color(2.0f);
    color.checkerboard = Checkerboard{Color(1.0f, 0.0f, 0.0f), Color(0.0f, 0.0f, 1.0f), Vec2(1.0f)};
    const TextureMapping mapping;
    ShadingPoint sp;
    sp.uv = Vec2(0.25f, 0.75f);
    EXPECT_EQ(evaluateColor(color, mapping, sp, nullptr), Color(2.0f, 0.0f, 0.0f));
    sp.uv = Vec2(0.75f, 0.75f);
    EXPECT_EQ(evaluateColor(color, mapping, sp, nullptr), Color(0.0f, 0.0f, 2.0f));
}

}  // namespace
}  // namespace strahl
