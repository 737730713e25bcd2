// White-furnace tests: the directional albedo, estimated by Monte Carlo over
// sample(), is 1 for the lossless BSDFs and at most 1 for every BSDF at several
// roughnesses and incident angles (docs/materials.md, "Testing").

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bsdf/bsdf_test_support.h"
#include "sanitizers/sanitized.h"
#include "strahl/bsdf/bsdf.h"

namespace strahl {
namespace {

using test::Case;
using test::direction;
using test::estimateAlbedo;

constexpr int kFurnaceSamples = 40000;
// Allowed excess beyond the 4-sigma noise band: float rounding, and for the
// metallic-roughness BSDF the error of its tabulated specular albedo.
constexpr float kSlack = 2e-3f;

void expectLossless(const Case& c, const Vec3& wo, uint64_t seed) {
    const auto e = estimateAlbedo(c.bsdf, wo, kFurnaceSamples, seed);
    for (int ch = 0; ch < 3; ++ch) {
        EXPECT_NEAR(e.mean[ch], 1.0f, 4.0f * e.stdError[ch] + kSlack)
            << c.name << " wo.z = " << wo.z << " channel " << ch;
    }
}

TEST(WhiteFurnace, LosslessBsdfsReflectEverything) {
    const std::vector<Case> cases = {
        {"white lambert", Bsdf::diffuse(Color(1.0f))},
        {"perfect mirror", Bsdf::conductor(Color(0.0f), Color(1.0f), 0.0f, 0.0f)},
        {"smooth glass 1.5", Bsdf::dielectric(1.5f, 0.0f)},
        {"smooth glass 1.33", Bsdf::dielectric(1.33f, 0.0f)},
        {"thin glass 1.5", Bsdf::thinDielectric(1.5f)},
        {"smooth plastic white", Bsdf::plastic(Color(1.0f), 1.5f, 0.0f)},
        {"smooth plastic white eta 2", Bsdf::plastic(Color(1.0f), 2.0f, 0.0f)},
        {"smooth metallic-roughness white", Bsdf::metallicRoughness(Color(1.0f), 0.0f, 0.0f)},
        {"rough metallic-roughness white", Bsdf::metallicRoughness(Color(1.0f), 0.0f, 0.25f)},
        // Last, so the cases above keep their seeds.
        {"diffuse transmission R + T = 1", Bsdf::diffuseTransmission(Color(0.7f, 0.5f, 0.2f), Color(0.3f, 0.5f, 0.8f))},
        // A perfect mirror (|r| = 1) under a smooth coat: every round trip summed.
        {"coated perfect mirror", test::coatedConductor(Color(0.0f), Color(1.0f), 0.0f, 1.5f, 0.0f, 0.0f)},
    };
    uint64_t seed = 1;
    for (const Case& c : cases) {
        for (float theta : {0.0f, 30.0f, 60.0f, 85.0f}) {
            expectLossless(c, direction(theta, 20.0f), seed++);
            if (!c.bsdf.isOpaque()) expectLossless(c, -direction(theta, 20.0f), seed++);
        }
    }
}

TEST(WhiteFurnace, LowRoughnessGgxWithUnitFresnelIsLossless) {
    // eta = 0, k > 0 makes |r| = 1 exactly: a conductor that absorbs nothing,
    // so only masking-shadowing (negligible at alpha 0.02) can lose energy.
    const Case c{"ggx F=1 alpha 0.02", Bsdf::conductor(Color(0.0f), Color(1.0f), 0.02f, 0.02f)};
    uint64_t seed = 100;
    for (float theta : {0.0f, 30.0f, 60.0f}) expectLossless(c, direction(theta, 45.0f), seed++);
    // Smooth (delta) dielectric with tint: R + T scaled by the tint exactly.
    const Bsdf tinted = Bsdf::dielectric(1.5f, 0.0f, Color(0.5f, 0.25f, 1.0f));
    const auto e = estimateAlbedo(tinted, direction(40.0f), kFurnaceSamples, 7);
    EXPECT_NEAR(e.mean.r, 0.5f, 1e-5f);
    EXPECT_NEAR(e.mean.g, 0.25f, 1e-5f);
    EXPECT_NEAR(e.mean.b, 1.0f, 1e-5f);
}

// Every model, white or maximal parameters, several roughnesses and angles.
std::vector<Case> everyModel() {
    std::vector<Case> cases;
    cases.push_back({"lambert", Bsdf::diffuse(Color(1.0f))});
    for (float n : {0.0f, 1.0f, 10.0f, 200.0f}) {
        cases.push_back({"phong n=" + std::to_string(n), Bsdf::phong(Color(0.5f), Color(0.5f), n)});
        cases.push_back(
            {"phong ks=1 n=" + std::to_string(n), Bsdf::phong(Color(0.0f), Color(1.0f), n)});
        cases.push_back(
            {"blinn n=" + std::to_string(n), Bsdf::blinnPhong(Color(0.5f), Color(0.5f), n)});
        cases.push_back(
            {"blinn ks=1 n=" + std::to_string(n), Bsdf::blinnPhong(Color(0.0f), Color(1.0f), n)});
    }
    for (float a : {0.0f, 0.05f, 0.2f, 0.5f, 1.0f}) {
        const std::string s = " alpha=" + std::to_string(a);
        cases.push_back({"conductor F=1" + s, Bsdf::conductor(Color(0.0f), Color(1.0f), a, a)});
        const MetalPreset silver = *findMetalPreset("silver");
        cases.push_back({"silver" + s, Bsdf::conductor(silver.eta, silver.k, a, a)});
        cases.push_back({"glass 1.5" + s, Bsdf::dielectric(1.5f, a)});
        cases.push_back({"glass 1/1.5" + s, Bsdf::dielectric(1.0f / 1.5f, a)});
        const MicrofacetModel beckmann{MicrofacetType::Beckmann, MicrofacetMasking::Separable};
        cases.push_back({"beckmann F=1" + s,
                         Bsdf::conductor(Color(0.0f), Color(1.0f), a, a, beckmann)});
        cases.push_back(
            {"beckmann glass 1.5" + s, Bsdf::dielectric(1.5f, a, Color(1.0f), beckmann)});
        cases.push_back({"plastic" + s, Bsdf::plastic(Color(1.0f), 1.5f, a)});
        for (float metallic : {0.0f, 0.5f, 1.0f}) {
            cases.push_back({"metallic-roughness m=" + std::to_string(metallic) + s,
                             Bsdf::metallicRoughness(Color(1.0f), metallic, a)});
        }
    }
    cases.push_back({"anisotropic F=1", Bsdf::conductor(Color(0.0f), Color(1.0f), 0.05f, 0.6f)});
    cases.push_back({"diffuse transmission", Bsdf::diffuseTransmission(Color(0.6f), Color(0.4f))});  // last: the others keep their seeds
    for (float base : {0.0f, 0.05f, 0.3f, 1.0f}) {
        for (float coat : {0.0f, 0.1f, 0.5f}) {
            for (float eta : {1.2f, 1.5f, 2.5f}) {
                cases.push_back({"coated F=1 base alpha=" + std::to_string(base) + " coat alpha=" + std::to_string(coat) +
                                     " eta=" + std::to_string(eta),
                                 test::coatedConductor(Color(0.0f), Color(eta), base, eta, coat, 0.0f)});
            }
        }
    }
    return cases;
}

TEST(WhiteFurnace, NoModelCreatesEnergy) {
    // A quarter of the samples per direction (a sixteenth under the
    // sanitizers): the bound below widens with the estimate's error.
    const int samples = kFurnaceSamples / test::fullOrSanitized(4, 16);
    uint64_t seed = 1000;
    for (const Case& c : everyModel()) {
        for (float theta : {0.0f, 30.0f, 60.0f, 80.0f, 89.0f}) {
            for (float side : {1.0f, -1.0f}) {
                const Vec3 wo = side * direction(theta, 30.0f);
                const auto e = estimateAlbedo(c.bsdf, wo, samples, seed++);
                EXPECT_LE(e.maxMean(), 1.0f + 4.0f * e.maxError() + kSlack)
                    << c.name << " theta = " << theta << " side " << side;
            }
        }
    }
}

TEST(WhiteFurnace, OpaqueBsdfsAreTwoSidedMirrorImages) {
    const Bsdf b = Bsdf::plastic(Color(0.7f, 0.5f, 0.2f), 1.5f, 0.3f);
    const auto up = estimateAlbedo(b, direction(50.0f, 10.0f), kFurnaceSamples, 5);
    Vec3 down = direction(50.0f, 10.0f);
    down.z = -down.z;
    const auto low = estimateAlbedo(b, down, kFurnaceSamples, 5);
    for (int ch = 0; ch < 3; ++ch) EXPECT_FLOAT_EQ(up.mean[ch], low.mean[ch]);
}

}  // namespace
}  // namespace strahl
