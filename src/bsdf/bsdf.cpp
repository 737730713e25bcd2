// Bsdf: parameter validation, the mirror-image rule of the opaque BSDFs and the
// dispatch to the models of bsdf_models.h.
//
// Parameter layout per kind:
//   Diffuse            a_ = reflectance
//   Phong, BlinnPhong  a_ = kd, b_ = ks, exponent_
//   Conductor          a_ = eta, b_ = k, alphaX_, alphaY_
//   Dielectric         a_ = tint, eta_, alphaX_ = alphaY_ = alpha
//   Plastic            a_ = kd, eta_, alphaX_ = alphaY_, internalReflectance_
//   MetallicRoughness  a_ = base, metallic_, alphaX_ = alphaY_, eta_
// and c_ = albedo() for every kind.

#include "strahl/bsdf/bsdf.h"

#include <cmath>

#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/local_frame.h"
#include "strahl/core/error.h"

namespace strahl {

namespace {

using namespace bsdf_models;

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

template <typename Fn>
auto Bsdf::visit(Fn&& fn) const {
    const GgxDistribution ggx(alphaX_, alphaY_);
    switch (kind_) {
        case Kind::Phong:
        case Kind::BlinnPhong:
            return fn(PhongModel{a_, b_, exponent_, kind_ == Kind::BlinnPhong});
        case Kind::Conductor:
            return fn(ConductorModel{ggx, a_, b_});
        case Kind::Dielectric:
            return fn(DielectricModel{ggx, eta_, a_});
        case Kind::Plastic:
            return fn(PlasticModel{ggx, a_, eta_, internalReflectance_});
        case Kind::MetallicRoughness:
            return fn(MetallicRoughnessModel{ggx, a_, metallic_, dielectricF0(eta_)});
        case Kind::Black:
        case Kind::Diffuse:
            break;
    }
    return fn(LambertModel{kind_ == Kind::Diffuse ? a_ : Color(0.0f)});
}

// ---- Factories -----------------------------------------------------------------

Bsdf Bsdf::black() {
    return Bsdf();
}

Bsdf Bsdf::diffuse(const Color& reflectance) {
    requireColor("diffuse", "reflectance", reflectance);
    Bsdf b;
    b.kind_ = Kind::Diffuse;
    b.a_ = reflectance;
    b.c_ = reflectance;
    return b;
}

Bsdf Bsdf::phong(const Color& kd, const Color& ks, float exponent) {
    requireColor("phong", "kd", kd);
    requireColor("phong", "ks", ks);
    requireNonNegative("phong", "exponent", exponent);
    Bsdf b;
    b.kind_ = Kind::Phong;
    b.a_ = kd;
    b.b_ = ks;
    b.exponent_ = exponent;
    b.c_ = glm::min(kd + ks, Color(1.0f));
    return b;
}

Bsdf Bsdf::blinnPhong(const Color& kd, const Color& ks, float exponent) {
    Bsdf b = phong(kd, ks, exponent);
    b.kind_ = Kind::BlinnPhong;
    return b;
}

Bsdf Bsdf::conductor(const Color& eta, const Color& k, float alphaX, float alphaY) {
    requireColor("conductor", "eta", eta);
    requireColor("conductor", "k", k);
    requireNonNegative("conductor", "alphaX", alphaX);
    requireNonNegative("conductor", "alphaY", alphaY);
    Bsdf b;
    b.kind_ = Kind::Conductor;
    b.a_ = eta;
    b.b_ = k;
    b.alphaX_ = alphaX;
    b.alphaY_ = alphaY;
    b.c_ = fresnelConductor(1.0f, eta, k);  // normal-incidence reflectance F0
    return b;
}

Bsdf Bsdf::dielectric(float eta, float alpha, const Color& tint) {
    requirePositive("dielectric", "eta", eta);
    requireNonNegative("dielectric", "alpha", alpha);
    requireColor("dielectric", "tint", tint);
    Bsdf b;
    b.kind_ = Kind::Dielectric;
    b.eta_ = eta;
    b.alphaX_ = b.alphaY_ = alpha;
    b.a_ = tint;
    b.c_ = tint;  // glass passes everything (R + T = 1) up to the tint
    return b;
}

Bsdf Bsdf::plastic(const Color& kd, float eta, float alpha) {
    requireColor("plastic", "kd", kd);
    requirePositive("plastic", "eta", eta);
    requireNonNegative("plastic", "alpha", alpha);
    Bsdf b;
    b.kind_ = Kind::Plastic;
    b.a_ = clamp01(kd);
    b.eta_ = eta;
    b.alphaX_ = b.alphaY_ = alpha;
    // Seen from inside the coat the relative index is 1 / eta.
    b.internalReflectance_ = fresnelDiffuseReflectance(1.0f / eta);
    b.c_ = b.a_;
    return b;
}

Bsdf Bsdf::metallicRoughness(const Color& base, float metallic, float alpha, float eta) {
    requireColor("metallicRoughness", "base", base);
    requireNonNegative("metallicRoughness", "metallic", metallic);
    requireNonNegative("metallicRoughness", "alpha", alpha);
    requirePositive("metallicRoughness", "eta", eta);
    Bsdf b;
    b.kind_ = Kind::MetallicRoughness;
    b.a_ = clamp01(base);
    b.metallic_ = std::min(metallic, 1.0f);
    b.alphaX_ = b.alphaY_ = std::min(alpha, 1.0f);
    b.eta_ = eta;
    b.c_ = b.a_;  // the diffuse colour of the dielectric and the F0 of the metal
    return b;
}

// ---- Evaluation ----------------------------------------------------------------

Color Bsdf::f(const Vec3& wo, const Vec3& wi) const {
    if (kind_ == Kind::Black) return Color(0.0f);
    if (!isOpaque()) return visit([&](const auto& model) { return model.f(wo, wi); });
    Vec3 o = wo, i = wi;
    if (!toUpperHemisphere(o, i)) return Color(0.0f);
    return visit([&](const auto& model) { return model.f(o, i); });
}

float Bsdf::pdf(const Vec3& wo, const Vec3& wi) const {
    if (kind_ == Kind::Black) return 0.0f;
    if (!isOpaque()) return visit([&](const auto& model) { return model.pdf(wo, wi); });
    Vec3 o = wo, i = wi;
    if (!toUpperHemisphere(o, i)) return 0.0f;
    return visit([&](const auto& model) { return model.pdf(o, i); });
}

std::optional<BsdfSample> Bsdf::sample(const Vec3& wo, float uLobe, const Vec2& u) const {
    if (kind_ == Kind::Black || wo.z == 0.0f) return std::nullopt;
    if (!isOpaque()) return visit([&](const auto& model) { return model.sample(wo, uLobe, u); });
    const bool flip = wo.z < 0.0f;
    const Vec3 o(wo.x, wo.y, std::abs(wo.z));
    auto s = visit([&](const auto& model) { return model.sample(o, uLobe, u); });
    if (s && flip) s->wi.z = -s->wi.z;
    return s;
}

bool Bsdf::isSpecular() const {
    const bool smooth = GgxDistribution(alphaX_, alphaY_).smooth();
    switch (kind_) {
        case Kind::Black:
            return true;  // no lobe at all: nothing for light sampling
        case Kind::Diffuse:
        case Kind::Phong:
        case Kind::BlinnPhong:
            return false;
        case Kind::Conductor:
            return smooth;
        case Kind::Dielectric:
            return smooth || eta_ == 1.0f;
        case Kind::Plastic:
            return smooth && maxComponent(a_) == 0.0f;
        case Kind::MetallicRoughness:
            return smooth && (metallic_ >= 1.0f || maxComponent(a_) == 0.0f);
    }
    return false;
}

Color Bsdf::albedo() const {
    return c_;
}

}  // namespace strahl
