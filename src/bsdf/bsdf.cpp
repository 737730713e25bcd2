// Bsdf: parameter validation in the factories, the mirror-image rule of the
// opaque BSDFs, the dispatch (std::visit) to the models of bsdf_models.h, and
// the weighted sums of blend().

#include "strahl/bsdf/bsdf.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/local_frame.h"
#include "strahl/core/error.h"

namespace strahl {

namespace {

using bsdf_models::CoatedConductorModel;
using bsdf_models::ConductorModel;
using bsdf_models::DielectricModel;
using bsdf_models::DiffuseTransmissionModel;
using bsdf_models::HairModel;
using bsdf_models::LambertModel;
using bsdf_models::MetallicRoughnessModel;
using bsdf_models::PhongModel;
using bsdf_models::PlasticModel;
using bsdf_models::PrincipledModel;
using bsdf_models::ThinDielectricModel;

void requireColor(const char* bsdf, const char* what, const Color& c) {
    if (!isFinite(c) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f) {
        fail(bsdf, ": ", what, " must be finite and non-negative, got (", c.r, ", ", c.g, ", ", c.b,
             ")");
    }
}

void requireNonNegative(const char* bsdf, const char* what, float v) {
    if (!std::isfinite(v) || v < 0.0f) {
        fail(bsdf, ": ", what, " must be finite and non-negative, got ", v);
    }
}

void requirePositive(const char* bsdf, const char* what, float v) {
    if (!std::isfinite(v) || v <= 0.0f) fail(bsdf, ": ", what, " must be positive, got ", v);
}

Color clamp01(const Color& c) {
    return glm::clamp(c, Color(0.0f), Color(1.0f));
}

// The opaque BSDFs act on the lower hemisphere as the mirror image of the
// upper one: flip both directions' z when wo is below. wo on the horizon or wi
// on the other side scatters nothing.
bool toUpperHemisphere(Vec3& wo, Vec3& wi) {
    if (wo.z == 0.0f || !sameHemisphere(wo, wi)) return false;
    if (wo.z < 0.0f) {
        wo.z = -wo.z;
        wi.z = -wi.z;
    }
    return true;
}

}  // namespace

// ---- Factories -----------------------------------------------------------------

Bsdf Bsdf::black() {
    return Bsdf();
}

Bsdf Bsdf::diffuse(const Color& reflectance) {
    requireColor("diffuse", "reflectance", reflectance);
    return Bsdf(LambertModel{reflectance}, reflectance);
}

Bsdf Bsdf::diffuseTransmission(const Color& reflectance, const Color& transmittance) {
    requireColor("diffuse transmission", "reflectance", reflectance);
    requireColor("diffuse transmission", "transmittance", transmittance);
    return Bsdf(DiffuseTransmissionModel{reflectance, transmittance}, reflectance + transmittance);
}

Bsdf Bsdf::phong(const Color& kd, const Color& ks, float exponent) {
    requireColor("phong", "kd", kd);
    requireColor("phong", "ks", ks);
    requireNonNegative("phong", "exponent", exponent);
    return Bsdf(PhongModel{kd, ks, exponent, false}, glm::min(kd + ks, Color(1.0f)));
}

Bsdf Bsdf::blinnPhong(const Color& kd, const Color& ks, float exponent) {
    Bsdf b = phong(kd, ks, exponent);
    std::get<PhongModel>(b.model_).blinn = true;
    return b;
}

Bsdf Bsdf::conductor(const Color& eta, const Color& k, float alphaX, float alphaY,
                     MicrofacetModel microfacets) {
    requireColor("conductor", "eta", eta);
    requireColor("conductor", "k", k);
    requireNonNegative("conductor", "alphaX", alphaX);
    requireNonNegative("conductor", "alphaY", alphaY);
    // albedo: the normal-incidence reflectance F0.
    return Bsdf(ConductorModel{MicrofacetDistribution(alphaX, alphaY, microfacets), eta, k},
                fresnelConductor(1.0f, eta, k));
}

Bsdf Bsdf::dielectric(float eta, float alpha, const Color& tint, MicrofacetModel microfacets) {
    requirePositive("dielectric", "eta", eta);
    requireNonNegative("dielectric", "alpha", alpha);
    requireColor("dielectric", "tint", tint);
    // albedo: glass passes everything (R + T = 1) up to the tint.
    return Bsdf(DielectricModel{MicrofacetDistribution(alpha, alpha, microfacets), eta, tint}, tint);
}

Bsdf Bsdf::thinDielectric(float eta, const Color& tint) {
    requirePositive("thinDielectric", "eta", eta);
    requireColor("thinDielectric", "tint", tint);
    return Bsdf(ThinDielectricModel{eta, tint}, tint);
}

Bsdf Bsdf::plastic(const Color& kd, float eta, float alpha, const PlasticCoat& coat) {
    requireColor("plastic", "kd", kd);
    requirePositive("plastic", "eta", eta);
    requireNonNegative("plastic", "alpha", alpha);
    if (coat.rough && coat.rough->eta() != eta)
        fail("plastic: the rough coat's tables were made for another index of refraction");
    const Color base = clamp01(kd);
    const MicrofacetDistribution microfacets(alpha, alpha, coat.microfacets);
    // Seen from inside the coat the relative index is 1 / eta.
    const float internal = coat.rough && !microfacets.smooth()
                               ? coat.rough->internalReflectance(microfacets.alphaX())
                               : fresnelDiffuseReflectance(1.0f / eta);
    return Bsdf(PlasticModel{microfacets, base, eta, internal, coat.nonlinear, coat.rough}, base);
}

Bsdf Bsdf::coatedConductor(const CoatedBase& layers, float metalAlpha, float coatAlpha) {
    requireNonNegative("coated conductor", "metal alpha", metalAlpha);
    requireNonNegative("coated conductor", "coat alpha", coatAlpha);
    const MicrofacetModel& model = layers.microfacets();
    const CoatedConductorModel coated{MicrofacetDistribution(coatAlpha, coatAlpha, model),
                                      MicrofacetDistribution(metalAlpha, metalAlpha, model), &layers};
    // albedo: what the smooth layers reflect at normal incidence.
    const Vec3 normal(0.0f, 0.0f, 1.0f);
    const Color albedo = Color(fresnelDielectric(1.0f, layers.coatEta())) + coated.mirrorThroughCoat(normal);
    return Bsdf(coated, albedo);
}

Bsdf Bsdf::metallicRoughness(const Color& base, float metallic, float alpha, float eta) {
    requireColor("metallicRoughness", "base", base);
    requireNonNegative("metallicRoughness", "metallic", metallic);
    requireNonNegative("metallicRoughness", "alpha", alpha);
    requirePositive("metallicRoughness", "eta", eta);
    const Color b = clamp01(base);
    const float a = std::min(alpha, 1.0f);
    // albedo: the diffuse colour of the dielectric and the F0 of the metal.
    return Bsdf(MetallicRoughnessModel{MicrofacetDistribution(a, a), b, std::min(metallic, 1.0f),
                                       dielectricF0(eta)},
                b);
}

Bsdf Bsdf::principled(const PrincipledParameters& parameters) {
    requireColor("principled", "base colour", parameters.base);
    const PrincipledParameters& p = parameters;
    for (const float x : {p.roughness, p.anisotropic, p.metallic, p.specularTint, p.sheen,
                          p.sheenTint, p.clearcoat, p.clearcoatGloss, p.transmission, p.flatness,
                          p.diffuseTransmission})
        if (std::isnan(x)) fail("principled: a parameter is NaN");
    if (!(p.eta > 1.0f && p.eta <= 4.0f))
        fail("principled: the index of refraction must be in (1, 4], got ", p.eta);
    auto lobes = std::make_shared<const PrincipledLobes>(p);
    // albedo: the diffuse colour of the dielectric and the F0 of the metal.
    const Color albedo = lobes->p.base;
    return Bsdf(PrincipledModel{std::move(lobes)}, albedo);
}

Bsdf::Sum Bsdf::terms() const {
    return sum_ ? *sum_ : Sum{{model_, 1.0f}};
}

Bsdf Bsdf::blend(const Bsdf& a, const Bsdf& b, float weight) {
    if (std::isnan(weight)) fail("blend: the weight must be a number, got NaN");
    weight = std::clamp(weight, 0.0f, 1.0f);
    if (weight == 0.0f) return a;
    if (weight == 1.0f) return b;
    auto sum = std::make_shared<Sum>();
    for (const WeightedModel& term : a.terms()) sum->push_back({term.model, (1.0f - weight) * term.weight});
    for (const WeightedModel& term : b.terms()) sum->push_back({term.model, weight * term.weight});
    Bsdf blended;
    blended.sum_ = std::move(sum);
    blended.albedo_ = (1.0f - weight) * a.albedo_ + weight * b.albedo_;
    return blended;
}

// ---- Roughening (filter glossy) ------------------------------------------------

namespace {

MicrofacetDistribution atLeast(const MicrofacetDistribution& m, float alpha) {
    if (m.alphaX() >= alpha && m.alphaY() >= alpha) return m;
    return MicrofacetDistribution(std::max(m.alphaX(), alpha), std::max(m.alphaY(), alpha),
                                  m.model());
}

BsdfModel roughenedModel(const BsdfModel& model, float alpha) {
    return std::visit(
        [alpha](const auto& m) -> BsdfModel {
            using Model = std::decay_t<decltype(m)>;
            Model out = m;
            if constexpr (std::is_same_v<Model, ConductorModel> ||
                          std::is_same_v<Model, DielectricModel>) {
                out.microfacets = atLeast(m.microfacets, alpha);
            } else if constexpr (std::is_same_v<Model, PlasticModel>) {
                // A rough coat's tables hold its own alpha: only a coat without
                // them (smooth, or the 1 - F approximation) can change alpha.
                if (!m.roughCoat) out.microfacets = atLeast(m.microfacets, alpha);
            } else if constexpr (std::is_same_v<Model, CoatedConductorModel>) {
                out.coat = atLeast(m.coat, alpha);
                out.metal = atLeast(m.metal, alpha);
            } else if constexpr (std::is_same_v<Model, MetallicRoughnessModel>) {
                out.ggx = atLeast(m.ggx, alpha);
            } else if constexpr (std::is_same_v<Model, PhongModel>) {
                // The Phong exponent of the same width as Beckmann alpha:
                // n = 2 / alpha^2 - 2 (Walter et al. 2007, sec. 5.2).
                out.exponent = std::min(m.exponent, 2.0f / (alpha * alpha) - 2.0f);
            }
            return out;  // Lambert, black, thin dielectric, principled: as they are
        },
        model);
}

}  // namespace

Bsdf Bsdf::roughened(float alpha) const {
    if (!(alpha > 0.0f)) return *this;
    Bsdf out = *this;
    if (sum_) {
        auto sum = std::make_shared<Sum>(*sum_);
        for (WeightedModel& term : *sum) term.model = roughenedModel(term.model, alpha);
        out.sum_ = std::move(sum);
    } else {
        out.model_ = roughenedModel(model_, alpha);
    }
    return out;
}

// ---- Evaluation ----------------------------------------------------------------

namespace {

// Whether a model is opaque: its kOpaque, or its opaque() where that depends
// on its parameters.
template <typename Model>
bool isOpaqueModel(const Model& model) {
    if constexpr (requires { model.opaque(); })
        return model.opaque();
    else
        return Model::kOpaque;
}

// fn(model, wo, wi) under the mirror-image rule: an opaque model sees both
// directions flipped into the upper hemisphere, and scatters nothing (`none`)
// when they are on opposite sides or wo lies on the horizon.
template <typename Result, typename Fn>
Result evaluate(const BsdfModel& bsdf, Vec3 wo, Vec3 wi, Result none, Fn&& fn) {
    return std::visit(
        [&](const auto& model) -> Result {
            if (isOpaqueModel(model) && !toUpperHemisphere(wo, wi)) return none;
            return fn(model, wo, wi);
        },
        bsdf);
}

}  // namespace

Color Bsdf::f(const Vec3& wo, const Vec3& wi) const {
    const auto fn = [](const auto& model, const Vec3& o, const Vec3& i) { return model.f(o, i); };
    if (!sum_) return evaluate(model_, wo, wi, Color(0.0f), fn);
    Color total(0.0f);
    for (const WeightedModel& term : *sum_)
        total += term.weight * evaluate(term.model, wo, wi, Color(0.0f), fn);
    return total;
}

float Bsdf::pdf(const Vec3& wo, const Vec3& wi) const {
    const auto fn = [](const auto& model, const Vec3& o, const Vec3& i) { return model.pdf(o, i); };
    if (!sum_) return evaluate(model_, wo, wi, 0.0f, fn);
    float total = 0.0f;
    for (const WeightedModel& term : *sum_) total += term.weight * evaluate(term.model, wo, wi, 0.0f, fn);
    return total;
}

namespace {

std::optional<BsdfSample> sampleModel(const BsdfModel& bsdf, const Vec3& wo, float uLobe,
                                      const Vec2& u) {
    return std::visit(
        [&](const auto& model) -> std::optional<BsdfSample> {
            if (!isOpaqueModel(model)) return model.sample(wo, uLobe, u);
            const bool flip = wo.z < 0.0f;
            const Vec3 o(wo.x, wo.y, std::abs(wo.z));
            auto s = model.sample(o, uLobe, u);
            if (s && flip) s->wi.z = -s->wi.z;
            return s;
        },
        bsdf);
}

}  // namespace

std::optional<BsdfSample> Bsdf::sample(const Vec3& wo, float uLobe, const Vec2& u) const {
    if (wo.z == 0.0f) return std::nullopt;
    if (!sum_) return sampleModel(model_, wo, uLobe, u);
    // Pick term i with probability weight_i and reuse uLobe's position within
    // its interval (rescaled to [0, 1)) for the model's own lobe choice.
    const Sum& terms = *sum_;
    size_t picked = terms.size() - 1;
    float below = 0.0f;
    for (size_t i = 0; i + 1 < terms.size(); ++i) {
        if (uLobe < below + terms[i].weight) {
            picked = i;
            break;
        }
        below += terms[i].weight;
    }
    const float w = terms[picked].weight;
    const float uModel = std::clamp((uLobe - below) / w, 0.0f, 0x1.fffffep-1f);
    std::optional<BsdfSample> s = sampleModel(terms[picked].model, wo, uModel, u);
    if (!s) return s;
    if (s->specular) {
        // A delta lobe belongs to the picked model alone.
        s->pdf *= w;
        s->f *= w;
        return s;
    }
    // A direction every model could have produced: the mixture's f and density.
    s->f = f(wo, s->wi);
    s->pdf = pdf(wo, s->wi);
    if (!(s->pdf > 0.0f)) return std::nullopt;
    return s;
}

bool Bsdf::isSpecular() const {
    const auto specular = [](const BsdfModel& m) {
        return std::visit([](const auto& model) { return model.specular(); }, m);
    };
    if (!sum_) return specular(model_);
    return std::all_of(sum_->begin(), sum_->end(), [&](const WeightedModel& t) { return specular(t.model); });
}

bool Bsdf::isOpaque() const {
    const auto opaque = [](const BsdfModel& m) {
        return std::visit([](const auto& model) { return isOpaqueModel(model); }, m);
    };
    if (!sum_) return opaque(model_);
    return std::all_of(sum_->begin(), sum_->end(), [&](const WeightedModel& t) { return opaque(t.model); });
}

bool Bsdf::isFibre() const {
    const auto fibre = [](const BsdfModel& m) { return std::holds_alternative<HairModel>(m); };
    if (!sum_) return fibre(model_);
    return std::any_of(sum_->begin(), sum_->end(), [&](const WeightedModel& t) { return fibre(t.model); });
}

Color Bsdf::albedo() const {
    return albedo_;
}

}  // namespace strahl
