// The hair BSDF (Bsdf::hair, bsdf_models.h HairModel; docs/materials.md,
// "Hair"): a lossless fibre returns all light in a white furnace, sampling
// matches pdf() (weights of 1 without absorption, the chi-square test), the
// colour <-> absorption mapping round-trips, and the entry offset h derived
// from wo puts the R lobe where a mirror cylinder reflects.

#include <gtest/gtest.h>

#include <cmath>

#include "bsdf_test_support.h"
#include "strahl/core/error.h"

namespace strahl {
namespace {

using test::direction;

// Fibre frame: x along the fibre, z the normal at the hit.
Vec3 fibreDirection(float sinTheta, float phi) {
    const float c = std::sqrt(1.0f - sinTheta * sinTheta);
    return Vec3(sinTheta, c * std::cos(phi), c * std::sin(phi));
}

TEST(Hair, ALosslessFibreReturnsAllLightInAWhiteFurnace) {
    // ∫ f |cos θ| dω over the sphere by uniform sampling, for fixed h and for
    // h from wo, across roughnesses, tilts and directions.
    Pcg32 rng(5, 1);
    for (float betaM : {0.15f, 0.5f, 1.0f}) {
        for (float betaN : {0.2f, 0.8f}) {
            for (float h : {-0.7f, 0.4f, 2.0f}) {
                const Bsdf hair = Bsdf::hair(Color(0.0f), betaM, betaN, 2.0f, 1.55f, h);
                const Vec3 wo = glm::normalize(Vec3(rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f, rng.nextFloat()));
                constexpr int kSamples = 200000;
                double sum = 0.0;
                for (int i = 0; i < kSamples; ++i) {
                    const Vec3 wi = sampleUniformSphere(test::next2D(rng));
                    sum += double(hair.f(wo, wi).g) * std::abs(wi.z) * (4.0 * test::kPiD);
                }
                // Narrow lobes (beta_m 0.15) make uniform sampling noisy: 5 %.
                EXPECT_NEAR(sum / kSamples, 1.0, 0.05) << betaM << " " << betaN << " h " << h;
            }
        }
    }
}

TEST(Hair, WithoutAbsorptionEverySampleWeighsOne) {
    Pcg32 rng(9, 2);
    for (float betaM : {0.1f, 0.4f, 0.9f}) {
        for (float betaN : {0.1f, 0.4f, 0.9f}) {
            const Bsdf hair = Bsdf::hair(Color(0.0f), betaM, betaN, 3.0f);
            for (int i = 0; i < 2000; ++i) {
                const Vec3 wo = sampleUniformSphere(test::next2D(rng));
                const auto s = hair.sample(wo, rng.nextFloat(), test::next2D(rng));
                if (!s) continue;
                const float weight = s->f.g * std::abs(s->wi.z) / s->pdf;
                ASSERT_NEAR(weight, 1.0f, 2e-3f) << betaM << " " << betaN;
            }
        }
    }
    // And the albedo by importance sampling is 1 too.
    const test::AlbedoEstimate a = test::estimateAlbedo(Bsdf::hair(Color(0.0f), 0.3f, 0.3f, 2.0f), direction(50, 30),
                                                        100000, 4, false);
    EXPECT_NEAR(a.maxMean(), 1.0f, 1e-3f);
}

TEST(Hair, SamplingFollowsThePdf) {
    const Color brown = Bsdf::hairSigmaAFromColor(Color(0.45f, 0.25f, 0.12f), 0.3f);
    struct HairCase {
        Bsdf bsdf;
        Vec3 wo;
    };
    const HairCase cases[] = {
        {Bsdf::hair(brown, 0.3f, 0.3f, 2.0f), direction(40, 20)},
        {Bsdf::hair(brown, 0.6f, 0.6f, 0.0f, 1.55f, 0.5f), direction(70, 120)},
        {Bsdf::hair(Color(0.0f), 0.25f, 0.8f, -3.0f), -direction(30, 60)},
    };
    const double significance = 1.0 - std::pow(0.99, 1.0 / 3.0);
    uint64_t seed = 101;
    for (const HairCase& c : cases) {
        const auto r = test::chi2Test(c.bsdf, c.wo, 200000, seed++, significance);
        EXPECT_TRUE(r.ok) << r.message;
        double total = 0.0;
        for (double cell : test::integratePdfCells(c.bsdf, c.wo, test::SphereGrid{})) total += cell;
        EXPECT_NEAR(total, 1.0, 5e-3);
    }
}

TEST(Hair, AbsorptionDarkensAndTheColourMappingRoundTrips) {
    const Color c(0.6f, 0.3f, 0.1f);
    const Color sigma = Bsdf::hairSigmaAFromColor(c, 0.3f);
    const Color back = Bsdf::hairColorFromSigmaA(sigma, 0.3f);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], c[i], 1e-5f);
    EXPECT_GT(sigma.b, sigma.g);
    EXPECT_GT(sigma.g, sigma.r);
    const Vec3 wo = direction(60, 10);
    const float white = test::estimateAlbedo(Bsdf::hair(Color(0.0f), 0.3f, 0.3f, 2.0f), wo, 50000, 3, false).mean.b;
    const float dark = test::estimateAlbedo(Bsdf::hair(sigma, 0.3f, 0.3f, 2.0f), wo, 50000, 3, false).mean.b;
    EXPECT_LT(dark, 0.8f * white);
    EXPECT_NEAR(Bsdf::hair(sigma, 0.3f, 0.3f, 2.0f).albedo().r, 0.6f, 1e-5f);
}

TEST(Hair, TheEntryOffsetFromWoPutsTheReflectionWhereAMirrorCylinderSendsIt) {
    // wo in the normal plane (θ = 0) at angle θw from the frame's y axis; the
    // normal at the hit is z. A mirror reflects ŵ about z to the angle π − θw,
    // so the R lobe (smooth, no tilt, other paths absorbed) peaks there.
    const Bsdf hair = Bsdf::hair(Color(50.0f), 0.1f, 0.05f, 0.0f);
    for (float thetaW : {1.2f, 1.9f}) {
        const Vec3 wo = fibreDirection(0.0f, thetaW);
        float bestPhi = 0.0f, best = -1.0f;
        for (int k = 0; k < 3600; ++k) {
            const float phi = -kPi + 2.0f * kPi * (static_cast<float>(k) + 0.5f) / 3600.0f;
            const float value = hair.f(wo, fibreDirection(0.0f, phi)).r * std::abs(std::sin(phi));
            if (value > best) best = value, bestPhi = phi;
        }
        EXPECT_NEAR(bestPhi, kPi - thetaW, 0.02f) << thetaW;
    }
}

TEST(Hair, BadParametersAreRefused) {
    EXPECT_THROW(Bsdf::hair(Color(-1.0f), 0.3f, 0.3f, 2.0f), Error);
    EXPECT_THROW(Bsdf::hair(Color(0.0f), 1.5f, 0.3f, 2.0f), Error);
    EXPECT_THROW(Bsdf::hair(Color(0.0f), 0.3f, -0.1f, 2.0f), Error);
    EXPECT_THROW(Bsdf::hair(Color(0.0f), 0.3f, 0.3f, 60.0f), Error);
    EXPECT_THROW(Bsdf::hair(Color(0.0f), 0.3f, 0.3f, 2.0f, 0.9f), Error);
    EXPECT_TRUE(Bsdf::hair(Color(0.0f), 0.3f, 0.3f, 2.0f).isFibre());
    EXPECT_FALSE(Bsdf::hair(Color(0.0f), 0.3f, 0.3f, 2.0f).isOpaque());
    EXPECT_FALSE(Bsdf::diffuse(Color(0.5f)).isFibre());
}

}  // namespace
}  // namespace strahl
