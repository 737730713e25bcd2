// Bump maps (texture/bump_map.h): a height rising along s tilts the normal
// back against the rise, along t (= 1 - v) towards +v, and no slope leaves the
// shading normal as it is.

#include "strahl/texture/bump_map.h"

#include <gtest/gtest.h>

namespace strahl {
namespace {

const Vec3 kN(0, 0, 1), kDpdu(1, 0, 0), kDpdv(0, 1, 0);

void expectNear(const Vec3& a, const Vec3& b) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], 1e-6f) << i;
}

TEST(BumpMap, NoSlopeKeepsTheShadingNormal) {
    expectNear(applyBumpMap(Vec2(0.0f), kN, kDpdu, kDpdv), kN);
    // Tangents with a component along n (smooth-shaded meshes) change nothing either.
    expectNear(applyBumpMap(Vec2(0.0f), kN, Vec3(1, 0, 0.3f), Vec3(0, 2, -0.2f)), kN);
}

TEST(BumpMap, TheNormalLeansAwayFromTheRise) {
    // h = 0.5 s: dp'/ds = (1, 0, 0.5), dp'/dt = (0, -1, 0), n' ~ (-0.5, 0, 1).
    expectNear(applyBumpMap(Vec2(0.5f, 0.0f), kN, kDpdu, kDpdv),
               glm::normalize(Vec3(-0.5f, 0.0f, 1.0f)));
    // h = 0.5 t rises towards -v, so the normal leans towards +v.
    expectNear(applyBumpMap(Vec2(0.0f, 0.5f), kN, kDpdu, kDpdv),
               glm::normalize(Vec3(0.0f, 0.5f, 1.0f)));
    // Longer tangents (a stretched uv mapping) make the same height flatter.
    expectNear(applyBumpMap(Vec2(0.5f, 0.0f), kN, 2.0f * kDpdu, kDpdv),
               glm::normalize(Vec3(-0.25f, 0.0f, 1.0f)));
}

TEST(BumpMap, WithoutTangentsTheNormalIsUnchanged) {
    expectNear(applyBumpMap(Vec2(0.5f), kN, Vec3(0.0f), kDpdv), kN);
    expectNear(applyBumpMap(Vec2(0.5f), kN, kDpdu, Vec3(0.0f)), kN);
}

}  // namespace
}  // namespace strahl
