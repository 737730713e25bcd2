// The rough coat of a plastic: the quadrature of a rough interface's albedos
// agrees with the rough dielectric it describes, reaches the smooth
// interface's values as the roughness vanishes, and a plastic built on it
// conserves energy.

#include <gtest/gtest.h>

#include <array>

#include "bsdf/bsdf_test_support.h"
#include "strahl/bsdf/bsdf.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/rough_coat.h"
#include "strahl/core/error.h"

namespace strahl {
namespace {

using test::direction;
using test::estimateAlbedo;

// Reflection and (radiance-scaling undone) transmission of the rough
// dielectric, estimated by sampling it: the quantities roughInterfaceAlbedo integrates.
test::AlbedoEstimate lobeAlbedo(const Bsdf& glass, const Vec3& wo, bool transmission) {
    Pcg32 rng(42, 3);
    constexpr int kSamples = 400000;
    double sum = 0.0, sumSq = 0.0;
    for (int i = 0; i < kSamples; ++i) {
        const float uLobe = rng.nextFloat();
        const auto s = glass.sample(wo, uLobe, test::next2D(rng));
        if (!s || s->transmission != transmission) continue;
        double w = double(s->f.r) * std::abs(double(s->wi.z)) / double(s->pdf);
        if (s->transmission) w *= double(s->eta) * double(s->eta);
        sum += w;
        sumSq += w * w;
    }
    test::AlbedoEstimate e;
    const double mean = sum / kSamples;
    e.mean = Color(float(mean));
    e.stdError = Color(float(std::sqrt(std::max(0.0, sumSq / kSamples - mean * mean) / kSamples)));
    return e;
}

TEST(RoughCoat, QuadratureMatchesTheRoughDielectricItDescribes) {
    for (const MicrofacetModel model :
         {MicrofacetModel{}, MicrofacetModel{MicrofacetType::Beckmann, MicrofacetMasking::Separable}}) {
        for (const float alpha : {0.1f, 0.5f}) {
            for (const float eta : {1.5f, 1.0f / 1.5f}) {
                const Bsdf glass = Bsdf::dielectric(eta, alpha, Color(1.0f), model);
                for (const float theta : {10.0f, 60.0f, 85.0f}) {
                    const Vec3 wo = direction(theta, 0.0f);
                    const InterfaceAlbedo q = roughInterfaceAlbedo(
                        MicrofacetDistribution(alpha, alpha, model), wo.z, eta, 64);
                    const auto r = lobeAlbedo(glass, wo, false), t = lobeAlbedo(glass, wo, true);
                    EXPECT_NEAR(q.reflectance, r.mean.r, 4.0f * r.stdError.r + 2e-3f)
                        << int(model.type) << " alpha " << alpha << " eta " << eta << " theta " << theta;
                    EXPECT_NEAR(q.transmittance, t.mean.r, 4.0f * t.stdError.r + 2e-3f)
                        << int(model.type) << " alpha " << alpha << " eta " << eta << " theta " << theta;
                    EXPECT_LE(q.reflectance + q.transmittance, 1.0f + 1e-4f);
                }
            }
        }
    }
}

TEST(RoughCoat, ANearlySmoothCoatHasTheSmoothInterfacesValues) {
    const std::array<float, 1> alphas = {0.002f};
    const RoughCoat coat(MicrofacetModel{}, 1.5f, alphas);
    for (const float cosTheta : {1.0f, 0.7f, 0.3f}) {
        EXPECT_NEAR(coat.transmittance(0.002f, cosTheta), 1.0f - fresnelDielectric(cosTheta, 1.5f),
                    2e-3f)
            << cosTheta;
    }
    // Mitsuba's rule for the average sits 1.5 % below the integral.
    EXPECT_NEAR(coat.internalReflectance(0.002f), 0.985f * fresnelDiffuseReflectance(1.0f / 1.5f),
                3e-3f);
}

TEST(RoughCoat, TexturedRoughnessInterpolatesBetweenNodes) {
    const std::array<float, 2> alphas = {0.1f, 0.4f};
    const RoughCoat coat(MicrofacetModel{}, 1.5f, alphas);
    const float lo = coat.transmittance(0.1f, 0.5f), hi = coat.transmittance(0.4f, 0.5f);
    EXPECT_FLOAT_EQ(coat.transmittance(0.25f, 0.5f), 0.5f * (lo + hi));
    EXPECT_FLOAT_EQ(coat.transmittance(1.0f, 0.5f), hi);  // clamped to the last node
    EXPECT_GT(coat.internalReflectance(0.4f), 0.0f);
    EXPECT_THROW(RoughCoat(MicrofacetModel{}, 1.5f, std::array<float, 2>{0.4f, 0.1f}), Error);
}

TEST(RoughCoat, RoughPlasticOnItConservesEnergy) {
    for (const float alpha : {0.05f, 0.3f, 1.0f}) {
        const std::array<float, 1> alphas = {alpha};
        const RoughCoat coat(MicrofacetModel{}, 1.5f, alphas);
        const Bsdf white = Bsdf::plastic(Color(1.0f), 1.5f, alpha, {{}, true, &coat});
        const Bsdf fresnelCoat = Bsdf::plastic(Color(1.0f), 1.5f, alpha);
        for (const float theta : {0.0f, 45.0f, 80.0f, 89.0f}) {
            const Vec3 wo = direction(theta, 20.0f);
            const auto e = estimateAlbedo(white, wo, 200000, 9);
            EXPECT_LE(e.maxMean(), 1.0f + 4.0f * e.maxError()) << alpha << " " << theta;
            // The single-scattering coat loses what its microfacets mask, most
            // of all inside, where total internal reflection sends the light
            // back at grazing angles: darker than the Fresnel coat when rough.
            const auto f = estimateAlbedo(fresnelCoat, wo, 200000, 9);
            if (alpha >= 0.3f && theta <= 45.0f) {
                EXPECT_LT(e.mean.r, f.mean.r - 0.1f) << alpha << " " << theta;
                EXPECT_GT(f.mean.r, 0.9f) << alpha << " " << theta;
            }
        }
    }
}

TEST(RoughCoat, TheLinearSeriesLeavesTheBaseColourOutOfTheInterreflections) {
    // Linear: kd / (1 - Fbar_int); nonlinear: kd / (1 - kd Fbar_int).
    const Bsdf linear = Bsdf::plastic(Color(0.5f), 1.5f, 0.0f, {{}, false, nullptr});
    const Bsdf nonlinear = Bsdf::plastic(Color(0.5f), 1.5f, 0.0f, {{}, true, nullptr});
    const Vec3 wo = direction(20.0f, 0.0f), wi = direction(40.0f, 180.0f);
    const float fbar = fresnelDiffuseReflectance(1.0f / 1.5f);
    EXPECT_NEAR(linear.f(wo, wi).r / nonlinear.f(wo, wi).r, (1.0f - 0.5f * fbar) / (1.0f - fbar),
                1e-5f);
}

}  // namespace
}  // namespace strahl
