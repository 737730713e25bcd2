// Bsdf::roughened (filter glossy): glossy and sharp lobes become at least as
// rough as asked, everything else is left exactly as it was.

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/bsdf/bsdf.h"

namespace strahl {
namespace {

const Vec3 kWo = glm::normalize(Vec3(0.3f, 0.1f, 0.9f));
// Not the mirror direction of kWo: a sharp lobe gives 0 there, a rough one not.
const Vec3 kWi = glm::normalize(Vec3(-0.1f, 0.3f, 0.8f));

TEST(RoughenedBsdf, SharpLobesTurnRoughAndLambertStaysExact) {
    const Bsdf mirror = Bsdf::conductor(Color(0.2f), Color(3.0f), 0.0f, 0.0f);
    ASSERT_TRUE(mirror.isSpecular());
    const Bsdf blurred = mirror.roughened(0.3f);
    EXPECT_FALSE(blurred.isSpecular());
    EXPECT_GT(blurred.f(kWo, kWi).r, 0.0f);
    EXPECT_GT(blurred.pdf(kWo, kWi), 0.0f);

    const Bsdf glass = Bsdf::dielectric(1.5f, 0.0f);
    EXPECT_TRUE(glass.isSpecular());
    EXPECT_FALSE(glass.roughened(0.3f).isSpecular());

    const Bsdf lambert = Bsdf::diffuse(Color(0.5f));
    EXPECT_EQ(lambert.roughened(0.5f).f(kWo, kWi).r, lambert.f(kWo, kWi).r);
    // Off (alpha 0) and already rougher lobes: unchanged.
    EXPECT_TRUE(mirror.roughened(0.0f).isSpecular());
    const Bsdf rough = Bsdf::conductor(Color(0.2f), Color(3.0f), 0.6f, 0.6f);
    EXPECT_EQ(rough.roughened(0.3f).f(kWo, kWi).g, rough.f(kWo, kWi).g);
}

TEST(RoughenedBsdf, PhongGetsTheExponentOfTheSameWidthAndBlendsEveryTerm) {
    // alpha 0.5 is Phong exponent 2 / 0.25 - 2 = 6.
    const Bsdf sharp = Bsdf::phong(Color(0.0f), Color(0.5f), 1000.0f);
    const Bsdf six = Bsdf::phong(Color(0.0f), Color(0.5f), 6.0f);
    EXPECT_FLOAT_EQ(sharp.roughened(0.5f).f(kWo, kWi).r, six.f(kWo, kWi).r);
    const Bsdf broad = Bsdf::phong(Color(0.0f), Color(0.5f), 2.0f);
    EXPECT_FLOAT_EQ(broad.roughened(0.5f).f(kWo, kWi).r, broad.f(kWo, kWi).r);

    const Bsdf mirror = Bsdf::conductor(Color(0.2f), Color(3.0f), 0.0f, 0.0f);
    const Bsdf blend = Bsdf::blend(Bsdf::diffuse(Color(0.5f)), mirror, 0.5f);
    const Bsdf expected =
        Bsdf::blend(Bsdf::diffuse(Color(0.5f)), mirror.roughened(0.4f), 0.5f);
    EXPECT_FLOAT_EQ(blend.roughened(0.4f).f(kWo, kWi).b, expected.f(kWo, kWi).b);
    EXPECT_GT(blend.roughened(0.4f).f(kWo, kWi).b, blend.f(kWo, kWi).b);
}

}  // namespace
}  // namespace strahl
