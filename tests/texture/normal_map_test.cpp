// Tangent-space normal maps: the flat value keeps ns, red and green tilt
// towards the tangent and the bitangent ns x t, and degenerate frames still
// give a unit normal.

#include "strahl/texture/normal_map.h"

#include <gtest/gtest.h>

#include <cmath>

namespace strahl {
namespace {

void expectNear(const Vec3& actual, const Vec3& expected, float tolerance) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance) << "component " << c;
}

void expectUnit(const Vec3& v) {
    EXPECT_TRUE(isFinite(v));
    EXPECT_NEAR(glm::length(v), 1.0f, 1e-6f);
}

TEST(NormalMap, FlatValueReturnsTheShadingNormal) {
    const Vec3 flat(0.5f, 0.5f, 1.0f);
    for (const Vec3 ns : {Vec3(0, 0, 1), glm::normalize(Vec3(1, -2, 0.5f))}) {
        const Vec3 n = applyNormalMap(flat, ns, Vec3(0.3f, 1.0f, 0.0f));
        expectNear(n, ns, 1e-6f);
        expectUnit(n);
    }
}

TEST(NormalMap, RedTiltsTowardsDpdu) {
    const Vec3 ns(0, 0, 1);
    const Vec3 dpdu(2.0f, 0.0f, 0.5f);  // not perpendicular to ns: Gram-Schmidt gives +x
    // n = (0.5, 0, sqrt(0.75)) in tangent space: 30 degrees towards the tangent.
    const Vec3 encoded(0.75f, 0.5f, 0.5f + 0.5f * std::sqrt(0.75f));
    const Vec3 n = applyNormalMap(encoded, ns, dpdu);
    expectUnit(n);
    expectNear(n, Vec3(0.5f, 0.0f, std::sqrt(0.75f)), 1e-6f);
    EXPECT_GT(glm::dot(n, dpdu), 0.0f);
}

TEST(NormalMap, GreenTiltsTowardsNsCrossTangent) {
    const Vec3 ns(0, 0, 1);
    const Vec3 dpdu(1, 0, 0);
    // OpenGL convention: green up is +v, which is ns x t = +y here.
    const Vec3 n = applyNormalMap(Vec3(0.5f, 1.0f, 0.5f), ns, dpdu);
    expectNear(n, Vec3(0, 1, 0), 1e-6f);
}

TEST(NormalMap, FrameFollowsARotatedSurface) {
    const Vec3 ns = glm::normalize(Vec3(1, 1, 0));
    const Vec3 dpdu(0, 0, 3);
    const Vec3 n = applyNormalMap(Vec3(1.0f, 0.5f, 0.5f), ns, dpdu);  // fully along t
    expectNear(n, Vec3(0, 0, 1), 1e-6f);
}

TEST(NormalMap, DegenerateDpduStillGivesAUnitNormal) {
    const Vec3 ns = glm::normalize(Vec3(0.2f, -0.3f, 0.9f));
    const Vec3 encoded(0.8f, 0.3f, 0.9f);
    for (const Vec3 dpdu : {Vec3(0.0f), 5.0f * ns, -ns, Vec3(kInfinity, 0, 0),
                            Vec3(std::nanf(""), 0, 0)}) {
        const Vec3 n = applyNormalMap(encoded, ns, dpdu);
        expectUnit(n);
        // The tilt is the same whatever tangent was chosen: as far from ns.
        const Vec3 m = glm::normalize(2.0f * encoded - 1.0f);
        EXPECT_NEAR(glm::dot(n, ns), m.z, 1e-5f);
    }
}

TEST(NormalMap, NonUnitShadingNormalIsNormalised) {
    const Vec3 n = applyNormalMap(Vec3(0.5f, 0.5f, 1.0f), Vec3(0, 0, 7), Vec3(1, 0, 0));
    expectNear(n, Vec3(0, 0, 1), 1e-6f);
    // A map value with no direction keeps the (normalised) shading normal.
    expectNear(applyNormalMap(Vec3(0.5f), Vec3(0, 3, 0), Vec3(1, 0, 0)), Vec3(0, 1, 0), 0.0f);
}

}  // namespace
}  // namespace strahl
