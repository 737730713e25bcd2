// sample() against f() and pdf(): the values a sample reports equal the
// evaluated ones, pdf() integrates to the probability that sample() produces a
// non-delta direction, and the sampled directions follow pdf() (chi-square).

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "bsdf/bsdf_test_support.h"
#include "strahl/bsdf/bsdf.h"

namespace strahl {
namespace {

using test::Case;
using test::direction;

// A principled BSDF with every lobe on (anisotropic, tinted, metallic,
// clearcoated, sheened, flattened), transmitting `transmission`, or thin.
PrincipledParameters principledCase(bool thin, float transmission) {
    PrincipledParameters p;
    p.base = Color(0.7f, 0.4f, 0.2f);
    p.roughness = 0.4f;
    p.anisotropic = 0.5f;
    p.metallic = thin ? 0.0f : 0.3f;
    p.specularTint = 0.4f;
    p.sheen = 0.5f;
    p.sheenTint = 0.5f;
    p.clearcoat = thin ? 0.0f : 0.8f;
    p.clearcoatGloss = 0.3f;
    p.transmission = transmission;
    p.flatness = 0.3f;
    p.thin = thin;
    p.diffuseTransmission = thin ? 0.8f : 0.0f;
    return p;
}

// Every model with a non-delta lobe, at moderate parameters.
std::vector<Case> nonDeltaModels() {
    const MetalPreset gold = *findMetalPreset("gold");
    return {
        {"lambert", Bsdf::diffuse(Color(0.8f, 0.5f, 0.2f))},
        {"diffuse transmission", Bsdf::diffuseTransmission(Color(0.5f, 0.3f, 0.1f), Color(0.2f, 0.4f, 0.6f))},
        {"phong", Bsdf::phong(Color(0.3f), Color(0.6f), 20.0f)},
        {"blinn-phong", Bsdf::blinnPhong(Color(0.3f), Color(0.6f), 30.0f)},
        {"gold alpha 0.3", Bsdf::conductor(gold.eta, gold.k, 0.3f, 0.3f)},
        {"anisotropic conductor", Bsdf::conductor(gold.eta, gold.k, 0.15f, 0.5f)},
        {"beckmann anisotropic conductor, separable masking",
         Bsdf::conductor(gold.eta, gold.k, 0.2f, 0.4f,
                         {MicrofacetType::Beckmann, MicrofacetMasking::Separable})},
        {"rough glass 1.5", Bsdf::dielectric(1.5f, 0.3f)},
        {"beckmann glass 1.5", Bsdf::dielectric(1.5f, 0.25f, Color(1.0f), {MicrofacetType::Beckmann})},
        {"beckmann glass 1/1.5, separable masking",
         Bsdf::dielectric(1.0f / 1.5f, 0.25f, Color(1.0f),
                          {MicrofacetType::Beckmann, MicrofacetMasking::Separable})},
        {"rough glass 1/1.33", Bsdf::dielectric(1.0f / 1.33f, 0.2f, Color(0.9f, 0.8f, 1.0f))},
        {"rough plastic", Bsdf::plastic(Color(0.6f, 0.3f, 0.1f), 1.5f, 0.2f)},
        {"smooth plastic", Bsdf::plastic(Color(0.6f, 0.3f, 0.1f), 1.5f, 0.0f)},
        {"metallic-roughness", Bsdf::metallicRoughness(Color(0.9f, 0.6f, 0.3f), 0.5f, 0.4f)},
        {"smooth metallic-roughness", Bsdf::metallicRoughness(Color(0.9f, 0.6f, 0.3f), 0.3f, 0.0f)},
        {"principled, opaque", Bsdf::principled(principledCase(false, 0.0f))},
        {"principled, transmissive", Bsdf::principled(principledCase(false, 0.6f))},
        {"principled, thin", Bsdf::principled(principledCase(true, 0.5f))},
        {"blend of rough gold and lambert",
         Bsdf::blend(Bsdf::conductor(gold.eta, gold.k, 0.2f, 0.2f), Bsdf::diffuse(Color(0.7f)), 0.4f)},
        {"blend of smooth glass and rough plastic",
         Bsdf::blend(Bsdf::dielectric(1.5f, 0.0f), Bsdf::plastic(Color(0.5f), 1.5f, 0.3f), 0.7f)},
        {"blend of two blends",
         Bsdf::blend(Bsdf::blend(Bsdf::diffuse(Color(0.2f)), Bsdf::phong(Color(0.3f), Color(0.6f), 20.0f), 0.5f),
                     Bsdf::blend(Bsdf::dielectric(1.5f, 0.3f), Bsdf::conductor(gold.eta, gold.k, 0.0f, 0.0f), 0.5f),
                     0.3f)},
        {"coated gold, rough base, smooth coat",
         test::coatedConductor(gold.eta, gold.k, 0.2f, 1.5f, 0.0f, 0.01f)},
        {"coated gold, rough base, rough coat",
         test::coatedConductor(gold.eta, gold.k, 0.3f, 1.5f, 0.15f, 0.0f)},
        {"coated gold, smooth base, rough coat",
         test::coatedConductor(gold.eta, gold.k, 0.0f, 1.5f, 0.2f, 0.0f)},
    };
}

// Outgoing directions from normal to nearly grazing, on both sides (inside for
// the dielectric, the mirrored hemisphere for the opaque models).
std::vector<Vec3> outgoingDirections() {
    std::vector<Vec3> dirs;
    for (float theta : {0.0f, 35.0f, 70.0f, 88.0f}) {
        dirs.push_back(direction(theta, 50.0f));
        dirs.push_back(-direction(theta, 200.0f));
    }
    return dirs;
}

float relativeError(float a, float b) {
    return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-20f});
}

TEST(BsdfSampling, SampleReportsTheEvaluatedFAndPdf) {
    Pcg32 rng(3, 1);
    for (const Case& c : nonDeltaModels()) {
        for (const Vec3& wo : outgoingDirections()) {
            int nonDelta = 0;
            for (int i = 0; i < 2000; ++i) {
                const float uLobe = rng.nextFloat();
                const auto s = c.bsdf.sample(wo, uLobe, test::next2D(rng));
                if (!s) continue;
                ASSERT_TRUE(isFinite(s->f) && std::isfinite(s->pdf)) << c.name;
                ASSERT_GT(s->pdf, 0.0f) << c.name;
                ASSERT_NEAR(glm::length(s->wi), 1.0f, 1e-4f) << c.name;
                ASSERT_GE(glm::min(s->f.r, glm::min(s->f.g, s->f.b)), 0.0f) << c.name;
                if (c.bsdf.isOpaque()) {
                    EXPECT_GT(s->wi.z * wo.z, 0.0f) << c.name;
                }
                if (s->specular) continue;
                ++nonDelta;
                EXPECT_EQ(s->transmission, s->wi.z * wo.z < 0.0f) << c.name;
                EXPECT_LT(relativeError(s->pdf, c.bsdf.pdf(wo, s->wi)), 1e-5f) << c.name;
                const Color f = c.bsdf.f(wo, s->wi);
                for (int ch = 0; ch < 3; ++ch) {
                    EXPECT_LT(relativeError(s->f[ch], f[ch]), 1e-5f) << c.name;
                }
            }
            EXPECT_GT(nonDelta, 0) << c.name << " wo.z = " << wo.z;
        }
    }
}

TEST(BsdfSampling, PdfIntegratesToTheNonDeltaSampleRate) {
    const test::SphereGrid grid;
    uint64_t seed = 40;
    for (const Case& c : nonDeltaModels()) {
        for (float theta : {10.0f, 60.0f}) {
            for (float side : {1.0f, -1.0f}) {
                const Vec3 wo = side * direction(theta, 15.0f);
                const auto cells = test::integratePdfCells(c.bsdf, wo, grid);
                const double integral = std::accumulate(cells.begin(), cells.end(), 0.0);
                // The probability that sample() yields a non-delta direction.
                Pcg32 rng(seed++, 5);
                constexpr int kN = 100000;
                int produced = 0;
                for (int i = 0; i < kN; ++i) {
                    const float uLobe = rng.nextFloat();
                    const auto s = c.bsdf.sample(wo, uLobe, test::next2D(rng));
                    if (s && !s->specular) ++produced;
                }
                const double rate = static_cast<double>(produced) / kN;
                const double sigma = std::sqrt(rate * (1.0 - rate) / kN);
                EXPECT_LE(integral, 1.0 + 2e-3) << c.name;
                EXPECT_NEAR(integral, rate, 4.0 * sigma + 2e-3)
                    << c.name << " theta " << theta << " side " << side;
            }
        }
    }
    // Nothing is discarded by cosine sampling: the Lambert pdf integrates to 1.
    const auto cells = test::integratePdfCells(Bsdf::diffuse(Color(0.5f)), direction(30.0f), grid);
    EXPECT_NEAR(std::accumulate(cells.begin(), cells.end(), 0.0), 1.0, 1e-4);
}

TEST(BsdfSampling, ChiSquareGoodnessOfFit) {
    const MetalPreset copper = *findMetalPreset("copper");
    struct Chi2Case {
        std::string name;
        Bsdf bsdf;
        Vec3 wo;
    };
    const std::vector<Chi2Case> cases = {
        {"ggx conductor normal", Bsdf::conductor(copper.eta, copper.k, 0.3f, 0.3f), direction(0)},
        {"ggx conductor 45", Bsdf::conductor(copper.eta, copper.k, 0.3f, 0.3f), direction(45)},
        {"ggx conductor 75", Bsdf::conductor(copper.eta, copper.k, 0.5f, 0.5f), direction(75)},
        {"ggx anisotropic", Bsdf::conductor(copper.eta, copper.k, 0.15f, 0.5f), direction(45, 30)},
        {"rough glass out 30", Bsdf::dielectric(1.5f, 0.3f), direction(30, 10)},
        {"rough glass out 70", Bsdf::dielectric(1.5f, 0.5f), direction(70, 10)},
        {"rough glass in 20", Bsdf::dielectric(1.5f, 0.3f), -direction(20, 10)},
        {"rough glass in 60", Bsdf::dielectric(1.5f, 0.3f), -direction(60, 10)},
        {"phong", Bsdf::phong(Color(0.2f), Color(0.7f), 15.0f), direction(40, 80)},
        {"blinn-phong", Bsdf::blinnPhong(Color(0.2f), Color(0.7f), 30.0f), direction(50, 80)},
        {"rough plastic 30", Bsdf::plastic(Color(0.5f), 1.5f, 0.2f), direction(30, 60)},
        {"rough plastic 70", Bsdf::plastic(Color(0.5f), 1.5f, 0.3f), direction(70, 60)},
        {"smooth plastic", Bsdf::plastic(Color(0.5f), 1.5f, 0.0f), direction(45)},
        {"metallic-roughness", Bsdf::metallicRoughness(Color(0.8f, 0.6f, 0.4f), 0.5f, 0.3f),
         direction(50, 20)},
        {"lambert", Bsdf::diffuse(Color(0.5f)), direction(20)},
        {"coated copper, rough base 20", test::coatedConductor(copper.eta, copper.k, 0.3f, 1.5f, 0.0f, 0.0f),
         direction(20, 40)},
        {"coated copper, both rough 60", test::coatedConductor(copper.eta, copper.k, 0.4f, 1.6f, 0.2f, 0.0f),
         direction(60, 40)},
    };
    // Sidak correction: the whole suite rejects a correct sampler with
    // probability 1%, whatever the number of cases.
    const double significance = 1.0 - std::pow(0.99, 1.0 / static_cast<double>(cases.size()));
    uint64_t seed = 77;
    for (const Chi2Case& c : cases) {
        const auto r = test::chi2Test(c.bsdf, c.wo, 200000, seed++, significance);
        EXPECT_TRUE(r.ok) << c.name << ": " << r.message;
    }
}

TEST(BsdfSampling, ChiSquareDetectsAWrongPdf) {
    // The test has teeth: samples of one BSDF against the pdf of another fail.
    const Bsdf a = Bsdf::conductor(Color(0.0f), Color(1.0f), 0.3f, 0.3f);
    const Bsdf b = Bsdf::conductor(Color(0.0f), Color(1.0f), 0.36f, 0.36f);
    const Vec3 wo = direction(30);
    std::vector<double> observed(static_cast<size_t>(test::SphereGrid{}.cells()), 0.0);
    const test::SphereGrid grid;
    Pcg32 rng(9, 9);
    constexpr int kN = 200000;
    for (int i = 0; i < kN; ++i) {
        const float uLobe = rng.nextFloat();
        const auto s = a.sample(wo, uLobe, test::next2D(rng));
        if (s) observed[static_cast<size_t>(grid.cellOf(s->wi))] += 1.0;
    }
    const auto expected = test::integratePdfCells(b, wo, grid);
    double chi2 = 0.0;
    int dof = -1;
    for (size_t i = 0; i < observed.size(); ++i) {
        const double e = expected[i] * kN;
        if (e < 5.0) continue;
        chi2 += (observed[i] - e) * (observed[i] - e) / e;
        ++dof;
    }
    EXPECT_LT(test::gammaQ(0.5 * dof, 0.5 * chi2), 1e-6);
}

}  // namespace
}  // namespace strahl
