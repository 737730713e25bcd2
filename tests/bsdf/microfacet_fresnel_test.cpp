// The building blocks: GGX normalisation and visible normals, Fresnel
// equations, the tabulated GGX albedo, and the metal presets.

#include <gtest/gtest.h>

#include <cmath>

#include "bsdf/bsdf_test_support.h"
#include "strahl/bsdf/bsdf.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/ggx_albedo.h"
#include "strahl/bsdf/local_frame.h"
#include "strahl/bsdf/microfacet.h"

namespace strahl {
namespace {

using test::direction;
using test::kPiD;

// Midpoint quadrature over the upper hemisphere in (theta, phi), finer near
// the pole where narrow GGX lobes live (theta = (pi / 2) t^2).
template <typename Fn>
double integrateHemisphere(Fn&& fn, int n = 800) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double t = (i + 0.5) / n;
        const double theta = 0.5 * kPiD * t * t, dTheta = kPiD * t / n;
        for (int j = 0; j < n; ++j) {
            const double phi = 2.0 * kPiD * (j + 0.5) / n;
            const Vec3 m(static_cast<float>(std::sin(theta) * std::cos(phi)),
                         static_cast<float>(std::sin(theta) * std::sin(phi)),
                         static_cast<float>(std::cos(theta)));
            sum += fn(m) * std::sin(theta) * dTheta * (2.0 * kPiD / n);
        }
    }
    return sum;
}

TEST(Ggx, ProjectedNormalAreaIsOne) {
    for (auto [ax, ay] : {std::pair{0.05f, 0.05f}, {0.3f, 0.3f}, {1.0f, 1.0f}, {0.1f, 0.7f}}) {
        const MicrofacetDistribution ggx(ax, ay);
        const double integral = integrateHemisphere([&](const Vec3& m) { return ggx.d(m) * m.z; });
        EXPECT_NEAR(integral, 1.0, 2e-3) << ax << " " << ay;
    }
}

TEST(Ggx, VisibleNormalsAreNormalised) {
    // integral D_w(m) dm = 1: the projected area of the visible microfacets
    // equals that of the macro surface (the Smith G1 definition).
    const MicrofacetDistribution ggx(0.4f, 0.2f);
    for (float theta : {0.0f, 45.0f, 80.0f}) {
        const Vec3 w = direction(theta, 30.0f);
        const double integral =
            integrateHemisphere([&](const Vec3& m) { return ggx.normalPdf(w, m); });
        EXPECT_NEAR(integral, 1.0, 3e-3) << theta;
    }
}

TEST(Beckmann, ProjectedNormalAreaIsOne) {
    for (auto [ax, ay] : {std::pair{0.05f, 0.05f}, {0.3f, 0.3f}, {1.0f, 1.0f}, {0.1f, 0.7f}}) {
        const MicrofacetDistribution beckmann(ax, ay, {MicrofacetType::Beckmann});
        const double integral =
            integrateHemisphere([&](const Vec3& m) { return beckmann.d(m) * m.z; });
        EXPECT_NEAR(integral, 1.0, 2e-3) << ax << " " << ay;
    }
}

TEST(Beckmann, SmithLambdaIsTheVisibleAreaOfItsDistribution) {
    // Smith's Lambda is defined by integral max(0, w.m) D(m) dm = cos(theta_w) (1 + Lambda(w)):
    // the microfacets facing w project onto (1 + Lambda) times the macro area.
    // This checks the closed form (erf) of Beckmann's Lambda against its D.
    const MicrofacetDistribution beckmann(0.5f, 0.25f, {MicrofacetType::Beckmann});
    for (float theta : {20.0f, 60.0f, 85.0f}) {
        const Vec3 w = direction(theta, 30.0f);
        const double visible = integrateHemisphere(
            [&](const Vec3& m) { return std::max(0.0f, glm::dot(w, m)) * beckmann.d(m); }, 1200);
        EXPECT_NEAR(visible / (w.z * (1.0 + beckmann.lambda(w))), 1.0, 3e-3) << theta;
    }
}

TEST(Microfacets, SampledNormalDensitiesIntegrateToOne) {
    for (const MicrofacetType type : {MicrofacetType::Ggx, MicrofacetType::Beckmann}) {
        const MicrofacetDistribution dist(0.35f, 0.2f, {type});
        const Vec3 w = direction(60.0f, 120.0f);
        const double integral =
            integrateHemisphere([&](const Vec3& m) { return dist.normalPdf(w, m); });
        EXPECT_NEAR(integral, 1.0, 3e-3) << int(type);
    }
}

TEST(Microfacets, SeparableMaskingIsTheProductOfTheMaskings) {
    const MicrofacetDistribution correlated(0.4f, 0.4f),
        separable(0.4f, 0.4f, {MicrofacetType::Ggx, MicrofacetMasking::Separable});
    const Vec3 a = direction(30, 10), b = direction(75, 200);
    EXPECT_FLOAT_EQ(separable.g(a, b), separable.g1(a) * separable.g1(b));
    // Shadowing that ignores the correlation of heights over-counts: G1 G1 <= G2.
    EXPECT_LT(separable.g(a, b), correlated.g(a, b));
}

TEST(Ggx, SmithTermsAreBoundedAndSymmetric) {
    const MicrofacetDistribution ggx(0.5f, 0.5f);
    EXPECT_FLOAT_EQ(ggx.g1(Vec3(0, 0, 1)), 1.0f);  // no masking at normal view
    EXPECT_EQ(ggx.g1(Vec3(1, 0, 0)), 0.0f);        // full masking at grazing
    const Vec3 a = direction(30, 10), b = direction(70, 200);
    EXPECT_FLOAT_EQ(ggx.g(a, b), ggx.g(b, a));
    EXPECT_LE(ggx.g(a, b), std::min(ggx.g1(a), ggx.g1(b)));
    EXPECT_TRUE(MicrofacetDistribution(0.0f, 0.0f).smooth());
    EXPECT_TRUE(MicrofacetDistribution(9e-4f, 5e-4f).smooth());
    EXPECT_FALSE(MicrofacetDistribution(0.0f, 0.2f).smooth());
    EXPECT_TRUE(std::isfinite(MicrofacetDistribution(0.0f, 0.2f).d(Vec3(0, 0, 1))));
}

TEST(Fresnel, DielectricSanity) {
    EXPECT_NEAR(fresnelDielectric(1.0f, 1.5f), 0.04f, 1e-6f);
    EXPECT_NEAR(fresnelDielectric(-1.0f, 1.5f), 0.04f, 1e-6f);  // same from inside
    EXPECT_FLOAT_EQ(fresnelDielectric(0.0f, 1.5f), 1.0f);       // grazing from outside
    EXPECT_FLOAT_EQ(fresnelDielectric(0.7f, 1.0f), 0.0f);       // index matched
    // Brewster's angle tan(theta_B) = 1.5: only the s-polarised half reflects.
    const float cosB = std::cos(std::atan(1.5f));
    const float sinB = std::sin(std::atan(1.5f)), cosT = std::sqrt(1.0f - sinB * sinB / 2.25f);
    const float rPerp = (cosB - 1.5f * cosT) / (cosB + 1.5f * cosT);
    EXPECT_NEAR(fresnelDielectric(cosB, 1.5f), 0.5f * rPerp * rPerp, 1e-6f);
    // Total internal reflection beyond the critical angle asin(1 / 1.5) = 41.8 deg.
    EXPECT_FLOAT_EQ(fresnelDielectric(-std::cos(0.75f), 1.5f), 1.0f);  // 43 deg inside
    EXPECT_LT(fresnelDielectric(-std::cos(0.70f), 1.5f), 1.0f);        // 40 deg inside
    // Reflectance is the same on both sides of a refraction pair.
    Vec3 wt;
    float etap;
    const Vec3 wo = direction(50.0f);
    ASSERT_TRUE(refractDir(wo, Vec3(0, 0, 1), 1.5f, wt, etap));
    EXPECT_FLOAT_EQ(etap, 1.5f);
    EXPECT_NEAR(fresnelDielectric(wo.z, 1.5f), fresnelDielectric(wt.z, 1.5f), 1e-6f);
}

TEST(Fresnel, SmoothDielectricBsdfReflectsTotallyBeyondTheCriticalAngle) {
    const Bsdf glass = Bsdf::dielectric(1.5f, 0.0f);
    const Vec3 inside = -direction(45.0f, 30.0f);  // 45 deg > 41.8 deg
    for (float uLobe : {0.0f, 0.5f, 0.999f}) {
        const auto s = glass.sample(inside, uLobe, Vec2(0.5f));
        ASSERT_TRUE(s);
        EXPECT_FALSE(s->transmission);
        EXPECT_FLOAT_EQ(s->pdf, 1.0f);
        EXPECT_NEAR(s->f.r * std::abs(s->wi.z), 1.0f, 1e-6f);
    }
    // At normal incidence 4% reflects; transmission carries 0.96 / 1.5^2.
    const auto t = glass.sample(Vec3(0, 0, 1), 0.5f, Vec2(0.5f));
    ASSERT_TRUE(t && t->transmission);
    EXPECT_NEAR(t->pdf, 0.96f, 1e-6f);
    EXPECT_NEAR(t->eta, 1.5f, 1e-6f);
    EXPECT_NEAR(t->f.g * std::abs(t->wi.z) / t->pdf, 1.0f / 2.25f, 1e-6f);
    EXPECT_NEAR(t->wi.z, -1.0f, 1e-6f);
}

TEST(Fresnel, ConductorMatchesTheNormalIncidenceFormula) {
    // F0 = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2).
    for (auto [n, k] : {std::pair{0.2f, 3.6f}, {2.9f, 3.1f}, {1.5f, 0.0f}}) {
        const float f0 = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
        EXPECT_NEAR(fresnelConductor(1.0f, n, k), f0, 1e-5f);
    }
    // eta = 0: a lossless mirror at every angle.
    for (float c : {1.0f, 0.5f, 0.1f, 0.0f}) {
        EXPECT_NEAR(fresnelConductor(c, 0.0f, 1.0f), 1.0f, 1e-6f);
    }
    // Every metal reflects all at grazing incidence and stays within [0, 1].
    EXPECT_NEAR(fresnelConductor(0.0f, 0.2f, 3.6f), 1.0f, 1e-5f);
    for (float c = 0.0f; c <= 1.0f; c += 0.01f) {
        const float f = fresnelConductor(c, 2.9f, 3.1f);
        EXPECT_TRUE(f >= 0.0f && f <= 1.0f);
    }
}

TEST(Fresnel, DiffuseReflectanceMatchesQuadrature) {
    for (float eta : {1.1f, 1.33f, 1.5f, 2.4f, 1.0f / 1.5f}) {
        // Brute-force midpoint rule on 2 F(mu) mu.
        double sum = 0.0;
        constexpr int kN = 200000;
        for (int i = 0; i < kN; ++i) {
            const double mu = (i + 0.5) / kN;
            sum += 2.0 * mu * fresnelDielectric(static_cast<float>(mu), eta) / kN;
        }
        EXPECT_NEAR(fresnelDiffuseReflectance(eta), sum, 2e-5) << eta;
    }
    // The relation between the two sides (energy crossing the interface).
    const float ext = fresnelDiffuseReflectance(1.5f), in = fresnelDiffuseReflectance(1.0f / 1.5f);
    EXPECT_NEAR(1.0f - in, (1.0f - ext) / 2.25f, 1e-6f);
    EXPECT_NEAR(in, 0.596f, 1e-3f);  // the classic internal value for n = 1.5
}

TEST(GgxAlbedo, TableMatchesMonteCarlo) {
    Pcg32 rng(21, 3);
    for (float alpha : {0.05f, 0.3f, 0.8f}) {
        for (float theta : {0.0f, 50.0f, 80.0f}) {
            const Vec3 wo = direction(theta);
            const float f0 = 0.04f;
            // Evaluate the lobe through the metallic-roughness BSDF with metallic
            // 1 and base F0: a pure Schlick GGX reflector.
            const Bsdf b = Bsdf::metallicRoughness(Color(f0), 1.0f, alpha);
            const auto e = test::estimateAlbedo(b, wo, 100000, rng.nextUint());
            EXPECT_NEAR(ggxSchlickAlbedo(wo.z, alpha, f0), e.mean.g, 4.0f * e.stdError.g + 2e-3f)
                << alpha << " " << theta;
        }
        // The average is 2 integral E(mu) mu dmu.
        double avg = 0.0;
        constexpr int kN = 20000;
        for (int i = 0; i < kN; ++i) {
            const float mu = (static_cast<float>(i) + 0.5f) / kN;
            avg += 2.0 * mu * ggxSchlickAlbedo(mu, alpha, 0.5f) / kN;
        }
        EXPECT_NEAR(ggxSchlickAverageAlbedo(alpha, 0.5f), avg, 1e-4) << alpha;
    }
    EXPECT_NEAR(ggxSchlickAlbedo(0.3f, 0.0f, 0.04f), fresnelSchlick(0.04f, 0.3f), 1e-7f);
}

TEST(MetalPresets, AreCompleteAndPlausible) {
    for (const char* name : {"gold", "silver", "copper", "aluminium", "chromium", "iron",
                             "titanium", "nickel", "platinum"}) {
        const auto p = findMetalPreset(name);
        ASSERT_TRUE(p) << name;
        const Color f0 = fresnelConductor(1.0f, p->eta, p->k);
        EXPECT_GT(glm::min(f0.r, glm::min(f0.g, f0.b)), 0.4f) << name;  // metals are bright
        EXPECT_LE(maxComponent(f0), 1.0f) << name;
    }
    EXPECT_EQ(metalPresets().size(), 9u);
    EXPECT_TRUE(findMetalPreset("Aluminum"));
    EXPECT_FALSE(findMetalPreset("unobtainium"));

    const Color gold =
        Bsdf::conductor(findMetalPreset("gold")->eta, findMetalPreset("gold")->k, 0.0f, 0.0f)
            .albedo();
    EXPECT_GT(gold.r, gold.g);
    EXPECT_GT(gold.g, gold.b);
    EXPECT_GT(gold.r, 0.9f);
    const Color silver =
        fresnelConductor(1.0f, findMetalPreset("silver")->eta, findMetalPreset("silver")->k);
    EXPECT_GT(glm::min(silver.r, glm::min(silver.g, silver.b)), 0.95f);
    EXPECT_LT(maxComponent(silver) - glm::min(silver.r, glm::min(silver.g, silver.b)), 0.02f);
    const Color copper =
        fresnelConductor(1.0f, findMetalPreset("copper")->eta, findMetalPreset("copper")->k);
    EXPECT_GT(copper.r, copper.g);
    EXPECT_GT(copper.g, copper.b);
}

}  // namespace
}  // namespace strahl
