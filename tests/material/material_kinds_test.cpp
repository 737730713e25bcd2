// The closed family of material kinds (strahl/material/material_kinds.h):
// the names come from the variant in its order, a kind is found by name,
// Material visits every kind's textures, and each kind's bsdf() with its
// default parameters is the BSDF of the factory its header documents.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "strahl/material/material.h"

namespace strahl {
namespace {

TEST(MaterialKinds, NamesFollowTheVariantOrder) {
    const auto names = kindNames<MaterialKind>();
    const std::vector<std::string_view> expected = {
        "diffuse",         "phong",   "blinn",              "conductor", "dielectric",
        "thin_dielectric", "diffuse_transmission", "plastic", "coated_conductor", "metallic_roughness", "principled", "hair", "blend", "emissive"};
    EXPECT_EQ(std::vector<std::string_view>(names.begin(), names.end()), expected);
}

TEST(MaterialKinds, AKindIsFoundByItsNameAndNothingByAnotherName) {
    for (std::string_view name : kindNames<MaterialKind>()) {
        const auto found = withKindNamed<MaterialKind>(
            name, [](auto kind) { return std::string(decltype(kind)::type::kName); });
        ASSERT_TRUE(found.has_value()) << name;
        EXPECT_EQ(*found, name);
    }
    EXPECT_FALSE(withKindNamed<MaterialKind>("velvet", [](auto) { return 0; }).has_value());
}

TEST(MaterialKinds, KindNameOfAMaterial) {
    Material m;
    EXPECT_EQ(kindName(m.kind), "diffuse");  // the default material is a grey diffuse
    m.kind = ConductorMaterial{};
    EXPECT_EQ(kindName(m.kind), "conductor");
}

// A blend's parts as the parser makes them.
BlendMaterial blendOfPlasticAndDiffuse(float weight = 0.5f) {
    BlendMaterial blend;
    blend.parts[0] = std::make_unique<MaterialKindBox>(MaterialKindBox{PlasticMaterial{}});
    blend.parts[1] = std::make_unique<MaterialKindBox>(MaterialKindBox{DiffuseMaterial{}});
    blend.weight.value = weight;
    return blend;
}

// How many textures each kind declares, plus the emission and the normal map
// every material has.
TEST(MaterialKinds, ForEachTextureVisitsTheKindsTexturesThenOpacityEmissionNormalAndBumpMap) {
    const std::vector<std::pair<MaterialKind, int>> cases = {
        {DiffuseMaterial{}, 1},    {PhongMaterial{}, 1},     {BlinnMaterial{}, 1},
        {ConductorMaterial{}, 2},  {DielectricMaterial{}, 2}, {ThinDielectricMaterial{}, 1},
        {PlasticMaterial{}, 2},       {CoatedConductorMaterial{}, 2},
        {MetallicRoughnessMaterial{}, 3}, {PrincipledMaterial{}, 12}, {blendOfPlasticAndDiffuse(), 2 + 1 + 1},
        {EmissiveMaterial{}, 0}};
    for (const auto& [kind, own] : cases) {
        Material m;
        m.kind = kind;
        std::vector<TextureEncoding> seen;
        m.forEachTexture([&](TextureRef&, TextureEncoding e) { seen.push_back(e); });
        ASSERT_EQ(seen.size(), size_t(own + 4)) << kindName(kind);
        EXPECT_EQ(seen[seen.size() - 4], TextureEncoding::Data) << "opacity";
        EXPECT_EQ(seen[seen.size() - 3], TextureEncoding::Color) << "emission";
        EXPECT_EQ(seen[seen.size() - 2], TextureEncoding::Data) << "normal map";
        EXPECT_EQ(seen.back(), TextureEncoding::Data) << "bump map";
    }
}

// f and pdf of two BSDFs agree on a few direction pairs (both hemispheres).
void expectSameBsdf(const Bsdf& a, const Bsdf& b, std::string_view what) {
    const Vec3 dirs[] = {glm::normalize(Vec3(0.3f, 0.2f, 0.9f)), glm::normalize(Vec3(-0.5f, 0.1f, 0.4f)),
                         glm::normalize(Vec3(0.1f, -0.7f, -0.6f))};
    for (const Vec3& wo : dirs) {
        for (const Vec3& wi : dirs) {
            EXPECT_EQ(a.f(wo, wi), b.f(wo, wi)) << what;
            EXPECT_EQ(a.pdf(wo, wi), b.pdf(wo, wi)) << what;
        }
    }
    EXPECT_EQ(a.isSpecular(), b.isSpecular()) << what;
    EXPECT_EQ(a.albedo(), b.albedo()) << what;
}

TEST(MaterialKinds, ABlendIsTheBlendOfItsPartsAndCopiesDeeply) {
    const ShadingPoint sp;
    const TextureMapping mapping;
    const MaterialPoint p{sp, mapping, nullptr};
    const BlendMaterial blend = blendOfPlasticAndDiffuse(0.3f);
    expectSameBsdf(blend.bsdf(p),
                   Bsdf::blend(PlasticMaterial{}.bsdf(p), DiffuseMaterial{}.bsdf(p), 0.3f), "blend");
    BlendMaterial copy = blend;
    std::get<DiffuseMaterial>(copy.parts[1]->kind).color.value = Color(0.1f);
    EXPECT_EQ(std::get<DiffuseMaterial>(blend.parts[1]->kind).color.value, Color(0.8f));
}

TEST(MaterialKinds, DefaultParametersGiveTheDocumentedBsdf) {
    const ShadingPoint sp;
    const TextureMapping mapping;
    const MaterialPoint p{sp, mapping, nullptr};
    const MetalPreset aluminium = *findMetalPreset("aluminium");
    expectSameBsdf(DiffuseMaterial{}.bsdf(p), Bsdf::diffuse(Color(0.8f)), "diffuse");
    expectSameBsdf(PhongMaterial{}.bsdf(p), Bsdf::phong(Color(0.8f), Color(0.2f), 32.0f), "phong");
    expectSameBsdf(BlinnMaterial{}.bsdf(p), Bsdf::blinnPhong(Color(0.8f), Color(0.2f), 32.0f),
                   "blinn");
    expectSameBsdf(ConductorMaterial{}.bsdf(p), Bsdf::conductor(aluminium.eta, aluminium.k, 0, 0),
                   "conductor");
    expectSameBsdf(DielectricMaterial{}.bsdf(p), Bsdf::dielectric(1.5f, 0.0f, Color(1.0f)),
                   "dielectric");
    expectSameBsdf(PlasticMaterial{}.bsdf(p), Bsdf::plastic(Color(0.8f), 1.5f, 0.0f), "plastic");
    expectSameBsdf(CoatedConductorMaterial{}.bsdf(p),
                   Bsdf::coatedConductor(CoatedBase(CoatedLayers{aluminium.eta, aluminium.k, 1.5f, 0.0f, {}}), 0.0f, 0.0f),
                   "coated_conductor");
    expectSameBsdf(MetallicRoughnessMaterial{}.bsdf(p),
                   Bsdf::metallicRoughness(Color(1.0f), 1.0f, 1.0f, 1.5f), "metallic_roughness");
    expectSameBsdf(EmissiveMaterial{}.bsdf(p), Bsdf::black(), "emissive");
}

TEST(MaterialKinds, TexturelessInputsAreClampedLikeTexels) {
    // A reflectance above 1 or NaN (what an HDR or corrupt texel gives) reaches
    // the factories clamped to [0, 1], NaN as 0; roughness likewise.
    const ShadingPoint sp;
    const TextureMapping mapping;
    const MaterialPoint p{sp, mapping, nullptr};
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(p.reflectance(TexturedColor{Color(2.0f, nan, -1.0f), {}}), Color(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(p.unit(TexturedFloat{nan, {}, 0}), 0.0f);
    EXPECT_EQ(p.alpha(TexturedFloat{0.5f, {}, 0}), 0.25f);
    EXPECT_EQ(p.alpha(TexturedFloat{3.0f, {}, 0}), 1.0f);
}

TEST(MaterialKinds, MaterialDiffuseIsAGreyLambertWithEmission) {
    const Material m = Material::diffuse("lamp", Color(0.5f), Color(2.0f));
    ASSERT_TRUE(std::holds_alternative<DiffuseMaterial>(m.kind));
    EXPECT_EQ(std::get<DiffuseMaterial>(m.kind).color.value, Color(0.5f));
    EXPECT_TRUE(m.emits());
    EXPECT_TRUE(m.hasUniformEmission());
    EXPECT_EQ(emittedRadiance(m, ShadingPoint{}, nullptr), Color(2.0f));
}

}  // namespace
}  // namespace strahl
