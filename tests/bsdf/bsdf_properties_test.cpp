// Structural properties of the BSDFs: reciprocity, robustness on degenerate
// directions, the delta / opaque / albedo queries and parameter validation.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bsdf/bsdf_test_support.h"
#include "strahl/bsdf/bsdf.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/local_frame.h"
#include "strahl/core/error.h"
#include "test_support.h"

namespace strahl {
namespace {

using test::Case;
using test::direction;
using test::sampleHemisphere;

std::vector<Case> reflectionModels() {
    const MetalPreset iron = *findMetalPreset("iron");
    return {
        {"lambert", Bsdf::diffuse(Color(0.5f))},
        {"phong", Bsdf::phong(Color(0.2f), Color(0.5f), 12.0f)},
        {"blinn-phong", Bsdf::blinnPhong(Color(0.2f), Color(0.5f), 40.0f)},
        {"conductor", Bsdf::conductor(iron.eta, iron.k, 0.2f, 0.2f)},
        {"anisotropic conductor", Bsdf::conductor(iron.eta, iron.k, 0.1f, 0.4f)},
        {"rough plastic", Bsdf::plastic(Color(0.4f, 0.6f, 0.8f), 1.5f, 0.3f)},
        {"smooth plastic", Bsdf::plastic(Color(0.4f, 0.6f, 0.8f), 1.5f, 0.0f)},
        {"metallic-roughness", Bsdf::metallicRoughness(Color(0.7f, 0.4f, 0.2f), 0.4f, 0.3f)},
        {"coated conductor", test::coatedConductor(iron.eta, iron.k, 0.3f, 1.5f, 0.2f, 0.05f)},
    };
}

std::vector<Case> allModels() {
    std::vector<Case> cases = reflectionModels();
    cases.push_back({"black", Bsdf::black()});
    cases.push_back({"mirror", Bsdf::conductor(Color(0.2f), Color(3.0f), 0.0f, 0.0f)});
    cases.push_back({"smooth glass", Bsdf::dielectric(1.5f, 0.0f)});
    cases.push_back({"rough glass", Bsdf::dielectric(1.5f, 0.3f)});
    cases.push_back({"tiny-alpha glass", Bsdf::dielectric(1.5f, 1.5e-3f)});
    cases.push_back(
        {"tiny-alpha conductor", Bsdf::conductor(Color(0.2f), Color(3.0f), 1.2e-3f, 1.2e-3f)});
    cases.push_back({"index-matched glass", Bsdf::dielectric(1.0f, 0.3f)});
    cases.push_back(
        {"smooth metallic-roughness", Bsdf::metallicRoughness(Color(0.5f), 0.5f, 0.0f)});
    cases.push_back({"phong n=0", Bsdf::phong(Color(0.5f), Color(0.5f), 0.0f)});
    return cases;
}

TEST(BsdfProperties, ReflectionIsReciprocal) {
    Pcg32 rng(12, 4);
    for (const Case& c : reflectionModels()) {
        for (int i = 0; i < 500; ++i) {
            const Vec3 a = sampleHemisphere(rng), b = sampleHemisphere(rng);
            const Color fab = c.bsdf.f(a, b), fba = c.bsdf.f(b, a);
            for (int ch = 0; ch < 3; ++ch) {
                EXPECT_NEAR(fab[ch], fba[ch], 1e-4f * std::max(1.0f, fab[ch])) << c.name;
            }
        }
    }
}

TEST(BsdfProperties, DiffuseTransmissionIsReciprocalOnBothSidesAndThrough) {
    const Bsdf leaf = Bsdf::diffuseTransmission(Color(0.5f, 0.4f, 0.3f), Color(0.1f, 0.2f, 0.3f));
    EXPECT_FALSE(leaf.isOpaque());
    Pcg32 rng(8, 8);
    for (int i = 0; i < 500; ++i) {
        const Vec3 a = sampleHemisphere(rng);
        Vec3 b = sampleHemisphere(rng);
        if (i % 2) b.z = -b.z;
        EXPECT_EQ(leaf.f(a, b), leaf.f(b, a));
        EXPECT_EQ(leaf.f(-a, -b), leaf.f(a, b));  // the same from the back
        const Color expected = (i % 2 ? Color(0.1f, 0.2f, 0.3f) : Color(0.5f, 0.4f, 0.3f)) * kInvPi;
        EXPECT_EQ(leaf.f(a, b), expected);
    }
}

TEST(BsdfProperties, DielectricObeysGeneralisedReciprocity) {
    // Reflection is symmetric; radiance-transport transmission satisfies
    // f(wo, wi) / n_o^2 = f(wi, wo) / n_i^2 (Veach 1997, 5.2).
    const float eta = 1.5f;
    const Bsdf glass = Bsdf::dielectric(eta, 0.4f);
    Pcg32 rng(5, 5);
    int transmissions = 0;
    for (int i = 0; i < 1000; ++i) {
        const Vec3 wo = sampleHemisphere(rng);
        Vec3 wi = sampleHemisphere(rng);
        if (i % 2) wi.z = -wi.z;
        const float nO = wo.z > 0.0f ? 1.0f : eta, nI = wi.z > 0.0f ? 1.0f : eta;
        const float lhs = glass.f(wo, wi).g / (nO * nO), rhs = glass.f(wi, wo).g / (nI * nI);
        EXPECT_NEAR(lhs, rhs, 1e-4f * std::max(1.0f, lhs));
        if (wi.z < 0.0f && lhs > 0.0f) ++transmissions;
    }
    EXPECT_GT(transmissions, 100);
}

TEST(BsdfProperties, DegenerateDirectionsGiveNoNaNs) {
    const std::vector<Vec3> dirs = {
        Vec3(1, 0, 0),           Vec3(0, 0, 1),      Vec3(0, 0, -1),
        Vec3(0.6f, 0.8f, 0.0f),  direction(89.999f), -direction(89.999f, 30.0f),
        direction(1e-3f, 70.0f),
    };
    for (const Case& c : allModels()) {
        for (const Vec3& wo : dirs) {
            for (const Vec3& wi : dirs) {
                for (const Vec3& w : {wi, -wo, wo, reflectZ(wo)}) {
                    EXPECT_TRUE(isFinite(c.bsdf.f(wo, w))) << c.name;
                    EXPECT_TRUE(std::isfinite(c.bsdf.pdf(wo, w))) << c.name;
                    EXPECT_GE(c.bsdf.pdf(wo, w), 0.0f) << c.name;
                }
            }
            for (float uLobe : {0.0f, 0.5f, 0.9999f}) {
                for (const Vec2& u : {Vec2(0.0f), Vec2(0.5f), Vec2(0.9999f, 0.0f), Vec2(0.9999f)}) {
                    const auto s = c.bsdf.sample(wo, uLobe, u);
                    if (wo.z == 0.0f) {
                        EXPECT_FALSE(s) << c.name;
                    }
                    if (!s) continue;
                    EXPECT_TRUE(isFinite(s->f) && isFinite(s->wi)) << c.name;
                    EXPECT_TRUE(std::isfinite(s->pdf) && s->pdf > 0.0f) << c.name;
                }
            }
        }
    }
}

TEST(BsdfProperties, DeltaOpaqueAndAlbedoQueries) {
    EXPECT_TRUE(Bsdf::black().isSpecular());
    EXPECT_FALSE(Bsdf::black().sample(Vec3(0, 0, 1), 0.5f, Vec2(0.5f)));
    EXPECT_EQ(Bsdf::black().albedo(), Color(0.0f));
    EXPECT_FALSE(Bsdf::diffuse(Color(0.5f)).isSpecular());
    EXPECT_TRUE(Bsdf::conductor(Color(0.2f), Color(3.0f), 0.0f, 0.0f).isSpecular());
    EXPECT_FALSE(Bsdf::conductor(Color(0.2f), Color(3.0f), 0.0f, 0.1f).isSpecular());
    EXPECT_TRUE(Bsdf::dielectric(1.5f, 0.0f).isSpecular());
    EXPECT_FALSE(Bsdf::dielectric(1.5f, 0.2f).isSpecular());
    EXPECT_FALSE(Bsdf::plastic(Color(0.5f), 1.5f, 0.0f).isSpecular());
    EXPECT_TRUE(Bsdf::plastic(Color(0.0f), 1.5f, 0.0f).isSpecular());
    EXPECT_TRUE(Bsdf::metallicRoughness(Color(0.5f), 1.0f, 0.0f).isSpecular());
    EXPECT_FALSE(Bsdf::metallicRoughness(Color(0.5f), 0.5f, 0.0f).isSpecular());

    EXPECT_FALSE(Bsdf::dielectric(1.5f, 0.0f).isOpaque());
    EXPECT_TRUE(Bsdf::plastic(Color(0.5f), 1.5f, 0.1f).isOpaque());

    // Delta lobes are invisible to f() and pdf().
    const Bsdf mirror = Bsdf::conductor(Color(0.2f), Color(3.0f), 0.0f, 0.0f);
    const Vec3 wo = direction(30.0f, 40.0f);
    EXPECT_EQ(mirror.f(wo, reflectZ(wo)), Color(0.0f));
    EXPECT_EQ(mirror.pdf(wo, reflectZ(wo)), 0.0f);

    EXPECT_EQ(Bsdf::diffuse(Color(0.1f, 0.2f, 0.3f)).albedo(), Color(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(Bsdf::dielectric(1.5f, 0.0f).albedo(), Color(1.0f));
    EXPECT_EQ(Bsdf::plastic(Color(0.3f), 1.5f, 0.0f).albedo(), Color(0.3f));
    const Color f0 = ((Color(0.2f) - 1.0f) * (Color(0.2f) - 1.0f) + 9.0f) /
                     ((Color(0.2f) + 1.0f) * (Color(0.2f) + 1.0f) + 9.0f);
    EXPECT_NEAR(mirror.albedo().r, f0.r, 1e-5f);
    EXPECT_EQ(Bsdf::metallicRoughness(Color(0.9f, 0.5f, 0.1f), 0.5f, 0.2f).albedo(),
              Color(0.9f, 0.5f, 0.1f));
}

TEST(BsdfProperties, OpaqueLowerHemisphereMirrorsTheUpperOne) {
    for (const Case& c : reflectionModels()) {
        const Vec3 wo = direction(40.0f, 10.0f), wi = direction(25.0f, 170.0f);
        const Vec3 woLow(wo.x, wo.y, -wo.z), wiLow(wi.x, wi.y, -wi.z);
        EXPECT_EQ(c.bsdf.f(wo, wi), c.bsdf.f(woLow, wiLow)) << c.name;
        EXPECT_EQ(c.bsdf.pdf(wo, wi), c.bsdf.pdf(woLow, wiLow)) << c.name;
        EXPECT_EQ(c.bsdf.f(wo, wiLow), Color(0.0f)) << c.name;  // no transmission
        const auto s = c.bsdf.sample(woLow, 0.3f, Vec2(0.4f, 0.7f));
        ASSERT_TRUE(s) << c.name;
        EXPECT_LT(s->wi.z, 0.0f) << c.name;
    }
}

TEST(BsdfProperties, InvalidParametersAreRejected) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(Bsdf::diffuse(Color(-0.1f)), Error);
    EXPECT_THROW(Bsdf::diffuse(Color(nan)), Error);
    EXPECT_THROW(Bsdf::phong(Color(0.5f), Color(0.5f), -1.0f), Error);
    EXPECT_THROW(Bsdf::conductor(Color(0.2f), Color(-1.0f), 0.1f, 0.1f), Error);
    EXPECT_THROW(Bsdf::conductor(Color(0.2f), Color(1.0f), -0.1f, 0.1f), Error);
    EXPECT_THROW(Bsdf::dielectric(0.0f, 0.1f), Error);
    EXPECT_THROW(Bsdf::dielectric(1.5f, nan), Error);
    EXPECT_THROW(Bsdf::plastic(Color(0.5f), -1.5f, 0.1f), Error);
    EXPECT_THROW(Bsdf::metallicRoughness(Color(0.5f), -0.5f, 0.1f), Error);
    const std::string message = test::errorMessage([] { Bsdf::dielectric(-2.0f, 0.1f); });
    EXPECT_NE(message.find("eta"), std::string::npos) << message;
}

TEST(BsdfProperties, MetallicRoughnessLimitsAreItsLobes) {
    // metallic 1: a Schlick conductor with F0 = base, no diffuse.
    const Bsdf metal = Bsdf::metallicRoughness(Color(0.9f, 0.6f, 0.3f), 1.0f, 0.2f);
    const Vec3 wo = direction(20.0f), wi = direction(60.0f, 180.0f);
    const Color f = metal.f(wo, wi);
    EXPECT_GT(f.r, f.g);
    EXPECT_GT(f.g, f.b);
    // metallic 0, black base: only the 4% dielectric specular remains, so the
    // mirror direction of a smooth surface carries F = F0 at normal incidence.
    const Bsdf coat = Bsdf::metallicRoughness(Color(0.0f), 0.0f, 0.0f);
    const auto s = coat.sample(Vec3(0, 0, 1), 0.5f, Vec2(0.5f));
    ASSERT_TRUE(s && s->specular);
    EXPECT_NEAR(s->f.r * s->wi.z / s->pdf, 0.04f, 1e-6f);
}

TEST(ThinDielectric, ReflectsTheSheetsSummedReflectanceAndPassesStraightThrough) {
    const Bsdf sheet = Bsdf::thinDielectric(1.5f, Color(1.0f, 0.5f, 1.0f));
    const Vec3 wo = glm::normalize(Vec3(0.3f, -0.2f, 0.9f));
    const float r = fresnelDielectric(wo.z, 1.5f), summed = 2.0f * r / (1.0f + r);
    const auto reflected = sheet.sample(wo, 0.5f * summed, Vec2(0.5f));
    ASSERT_TRUE(reflected);
    EXPECT_EQ(reflected->wi, Vec3(-wo.x, -wo.y, wo.z));
    EXPECT_NEAR(reflected->pdf, summed, 1e-6f);
    const auto through = sheet.sample(wo, 0.99f, Vec2(0.5f));
    ASSERT_TRUE(through);
    EXPECT_EQ(through->wi, -wo);  // undeviated
    EXPECT_TRUE(through->transmission);
    EXPECT_EQ(through->eta, 1.0f);
    // Weight: the tint, as the lobes are chosen by their share.
    const Color weight = through->f * std::abs(through->wi.z) / through->pdf;
    EXPECT_NEAR(weight.g, 0.5f, 1e-6f);
    // At normal incidence, glass 1.5: R = 0.04, R' = 0.08 / 1.04.
    const auto normal = sheet.sample(Vec3(0, 0, 1), 0.0f, Vec2(0.5f));
    EXPECT_NEAR(normal->pdf, 0.08f / 1.04f, 1e-6f);
    EXPECT_TRUE(sheet.isSpecular());
    EXPECT_FALSE(sheet.isOpaque());
}

TEST(Blend, IsTheWeightedSumOfItsModels) {
    const Bsdf a = Bsdf::diffuse(Color(0.0f, 0.5f, 0.5f)), b = Bsdf::diffuse(Color(1.0f, 1.0f, 0.0f));
    const Bsdf mix = Bsdf::blend(a, b, 0.25f);
    const Bsdf lambert = Bsdf::diffuse(0.75f * Color(0.0f, 0.5f, 0.5f) + 0.25f * Color(1.0f, 1.0f, 0.0f));
    const Vec3 wo = direction(30.0f, 40.0f), wi = direction(50.0f, 250.0f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mix.f(wo, wi)[c], lambert.f(wo, wi)[c], 1e-7f);
    EXPECT_NEAR(mix.pdf(wo, wi), lambert.pdf(wo, wi), 1e-7f);
    EXPECT_NEAR(mix.albedo().g, lambert.albedo().g, 1e-7f);
    // A sample reports the mixture's f and pdf, whichever model drew it.
    for (float uLobe : {0.1f, 0.9f}) {
        const auto s = mix.sample(wo, uLobe, Vec2(0.3f, 0.6f));
        ASSERT_TRUE(s);
        EXPECT_NEAR(s->pdf, lambert.pdf(wo, s->wi), 1e-6f);
        EXPECT_NEAR(s->f.b, lambert.f(wo, s->wi).b, 1e-7f);
    }
    // Weights 0 and 1 leave one model; NaN is refused.
    EXPECT_EQ(Bsdf::blend(a, b, 0.0f).f(wo, wi), a.f(wo, wi));
    EXPECT_EQ(Bsdf::blend(a, b, 1.0f).f(wo, wi), b.f(wo, wi));
    EXPECT_THROW(Bsdf::blend(a, b, std::numeric_limits<float>::quiet_NaN()), Error);
}

TEST(Blend, ADeltaLobeKeepsItsShareAndTheQueriesSeeEveryModel) {
    const Bsdf glass = Bsdf::dielectric(1.5f, 0.0f), matte = Bsdf::diffuse(Color(0.5f));
    const Bsdf mix = Bsdf::blend(glass, matte, 0.5f);
    EXPECT_FALSE(mix.isSpecular());
    EXPECT_FALSE(mix.isOpaque());
    EXPECT_TRUE(Bsdf::blend(glass, Bsdf::thinDielectric(1.5f), 0.5f).isSpecular());
    EXPECT_TRUE(Bsdf::blend(matte, Bsdf::plastic(Color(0.5f), 1.5f, 0.1f), 0.5f).isOpaque());
    // uLobe below 1/2 picks the glass: a delta sample at half the glass's weight.
    const Vec3 wo = direction(20.0f);
    const auto s = mix.sample(wo, 0.2f, Vec2(0.5f));
    const auto g = glass.sample(wo, 0.4f, Vec2(0.5f));
    ASSERT_TRUE(s && g && s->specular);
    EXPECT_NEAR(s->f.r * std::abs(s->wi.z) / s->pdf, g->f.r * std::abs(g->wi.z) / g->pdf, 1e-6f);
}

TEST(Blend, ABlendOfBlendsIsOneFlatSum) {
    const Bsdf a = Bsdf::diffuse(Color(0.2f)), b = Bsdf::diffuse(Color(0.6f));
    const Bsdf c = Bsdf::conductor(Color(0.2f), Color(3.0f), 0.3f, 0.3f);
    const Bsdf nested = Bsdf::blend(Bsdf::blend(a, b, 0.5f), Bsdf::blend(c, a, 0.25f), 0.5f);
    const Vec3 wo = direction(30.0f, 40.0f), wi = direction(50.0f, 250.0f);
    const Color expected = 0.25f * a.f(wo, wi) + 0.25f * b.f(wo, wi) + 0.375f * c.f(wo, wi) +
                           0.125f * a.f(wo, wi);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(nested.f(wo, wi)[k], expected[k], 1e-6f);
}

TEST(Principled, AllMetalIsSchlicksConductorOfTheBaseColour) {
    PrincipledParameters p;
    p.base = Color(0.9f, 0.6f, 0.3f);
    p.metallic = 1.0f;
    p.roughness = 0.5f;
    const Bsdf metal = Bsdf::principled(p);
    const MicrofacetDistribution ggx(0.25f, 0.25f, {MicrofacetType::Ggx, MicrofacetMasking::Separable});
    const Vec3 wo = direction(30.0f, 10.0f), wi = direction(50.0f, 200.0f);
    const Vec3 h = glm::normalize(wo + wi);
    const Color expected = fresnelSchlick(p.base, glm::dot(wo, h)) *
                           (ggx.d(h) * ggx.g(wo, wi) / (4.0f * wo.z * wi.z));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(metal.f(wo, wi)[c], expected[c], 1e-5f * expected[c]);
    EXPECT_TRUE(metal.isOpaque());
    EXPECT_EQ(metal.f(wo, -wi), Color(0.0f));  // nothing passes an opaque surface
}

TEST(Principled, ThinDiffuseTransmissionSplitsTheLambertLobe) {
    PrincipledParameters p;
    p.base = Color(0.8f, 0.5f, 0.2f);
    p.thin = true;
    p.diffuseTransmission = 2.0f;  // all of the diffuse lobe passes through
    const Bsdf sheet = Bsdf::principled(p);
    const Vec3 wo = direction(40.0f, 30.0f), below = -direction(25.0f, 100.0f);
    const Color through = sheet.f(wo, below);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(through[c], p.base[c] * kInvPi, 1e-6f);
    EXPECT_EQ(sheet.f(wo, direction(25.0f, 100.0f)), Color(0.0f));
    // The same from the other side.
    EXPECT_EQ(sheet.f(-wo, -below), through);
    EXPECT_FALSE(sheet.isOpaque());
}

TEST(Principled, ATransmissiveSolidOnlyRefractsAndReflectsFromInside) {
    PrincipledParameters p;
    p.base = Color(0.5f);
    p.transmission = 1.0f;
    p.roughness = 0.3f;
    p.sheen = 1.0f;
    p.clearcoat = 1.0f;
    const Bsdf glass = Bsdf::principled(p);
    EXPECT_FALSE(glass.isOpaque());
    // From inside, reflection is the dielectric's alone: the same with or
    // without the front-only lobes.
    PrincipledParameters plain = p;
    plain.sheen = plain.clearcoat = 0.0f;
    const Vec3 wo = -direction(20.0f, 0.0f), wi = -direction(35.0f, 180.0f);
    EXPECT_EQ(glass.f(wo, wi), Bsdf::principled(plain).f(wo, wi));
    EXPECT_GT(glass.f(wo, direction(10.0f, 180.0f)).r, 0.0f);  // refraction out
    EXPECT_THROW(Bsdf::principled([] {
                     PrincipledParameters q;
                     q.eta = 1.0f;
                     return q;
                 }()),
                 Error);
}

}  // namespace
}  // namespace strahl
