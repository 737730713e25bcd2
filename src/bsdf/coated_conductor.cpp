// Coated conductor: a conductor under a smooth or rough dielectric coat, the
// metal seen through the coat's mean surface, plus the light trapped in the
// coat (coated_base.h). Derivation in docs/materials.md,
// "Coated conductor".

#include <cmath>

#include "lobe_sampling.h"
#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/local_frame.h"

namespace strahl::bsdf_models {

namespace {

// The inverse of CoatedConductorModel::inside: an upward direction inside the
// coat refracted out, or nullopt beyond the critical angle (total internal
// reflection: that light is the trapped lobe's).
std::optional<Vec3> outside(const Vec3& wInside, float eta) {
    const float x = wInside.x * eta, y = wInside.y * eta;
    const float sin2 = x * x + y * y;
    if (!(sin2 < 1.0f)) return std::nullopt;
    return Vec3(x, y, std::sqrt(1.0f - sin2));
}

}  // namespace

Vec3 CoatedConductorModel::inside(const Vec3& w) const {
    // Snell: sin theta' = sin theta / eta with the azimuth kept; eta >= 1, so
    // every outside direction has one inside.
    const float eta = layers->coatEta();
    const float x = w.x / eta, y = w.y / eta;
    return Vec3(x, y, std::sqrt(std::max(0.0f, 1.0f - (x * x + y * y))));
}

float CoatedConductorModel::coatTransmittance(float cosTheta) const {
    return 1.0f - fresnelDielectric(cosTheta, layers->coatEta());
}

Color CoatedConductorModel::mirrorThroughCoat(const Vec3& wo) const {
    // Light enters (1 - F), crosses the layer (a), reflects off the metal (R
    // at the angle inside), crosses back (a) and leaves (1 - F), or is
    // reflected back down by the coat from inside (F again: from inside the
    // same Fresnel reflectance as from outside at the matching angle) and
    // goes round again; every round multiplies by F a^2 R:
    //   (1 - F)^2 a^2 R (1 + F a^2 R + (F a^2 R)^2 + ...) = (1 - F)^2 a^2 R / (1 - F a^2 R).
    // The mirror direction inside always lies within the critical angle.
    const Vec3 w = inside(wo);
    const float fresnel = fresnelDielectric(wo.z, layers->coatEta());
    const float a = layers->attenuation(w.z);
    const Color r = fresnelConductor(w.z, layers->eta(), layers->k()) * (a * a);
    const float t = 1.0f - fresnel;
    return t * t * r / (Color(1.0f) - fresnel * r);
}

float CoatedConductorModel::trappedLobe(const Vec3& w) const {
    if (metal.smooth()) return 0.0f;
    return coatTransmittance(w.z) * layers->trapped(metal.alphaX(), w.z) * layers->attenuation(inside(w).z);
}

CoatedConductorModel::LobeProbabilities CoatedConductorModel::lobeProbabilities(const Vec3& wo) const {
    // About the lobes' albedos at wo: the coat's F; what the metal returns
    // directly; what leaves after being trapped.
    const float coatWeight = fresnelDielectric(wo.z, layers->coatEta());
    if (metal.smooth()) {
        const float direct = mean(mirrorThroughCoat(wo));
        const float coatP = coatWeight + direct > 0.0f ? coatWeight / (coatWeight + direct) : 1.0f;
        return {coatP, 1.0f - coatP};
    }
    const Vec3 o = inside(wo);
    const float a = layers->attenuation(o.z);
    const float direct = coatTransmittance(wo.z) * a * a * mean(fresnelConductor(o.z, layers->eta(), layers->k())) *
                         (1.0f - layers->trapped(metal.alphaX(), wo.z));
    const float trapped = mean(layers->trappedEscape(metal.alphaX())) * trappedLobe(wo);
    const float sum = coatWeight + direct + trapped;
    if (!(sum > 0.0f)) return {1.0f, 0.0f};
    return {coatWeight / sum, direct / sum};
}

Color CoatedConductorModel::directF(const Vec3& wo, const Vec3& wi) const {
    if (metal.smooth()) return Color(0.0f);
    const Vec3 o = inside(wo), i = inside(wi);
    // The rough metal inside: Torrance-Sparrow at (o, i), ...
    const Vec3 m = glm::normalize(o + i);
    const Color fm = fresnelConductor(glm::dot(o, m), layers->eta(), layers->k()) *
                     (metal.d(m) * metal.g(o, i) / (4.0f * o.z * i.z));
    // ... times the coat's transmission in and out, the layer's attenuation
    // both ways and the radiance compression 1 / eta^2 of the way out (the
    // 1 / eta^2 of the solid angles and the eta^2 of the radiance on the way
    // in cancel: docs/materials.md).
    const float eta = layers->coatEta();
    const float through = coatTransmittance(wo.z) * coatTransmittance(wi.z) * layers->attenuation(o.z) *
                          layers->attenuation(i.z) / (eta * eta);
    return fm * through;
}

Color CoatedConductorModel::trappedF(const Vec3& wo, const Vec3& wi) const {
    if (metal.smooth()) return Color(0.0f);
    const float norm = layers->trappedNorm(metal.alphaX());
    if (!(norm > 0.0f)) return Color(0.0f);
    // Separable and symmetric (reciprocal): E A(wo) A(wi) / N, whose albedo is
    // E A(wo), the trapped part of what entered times what of it leaves.
    return layers->trappedEscape(metal.alphaX()) * (trappedLobe(wo) * trappedLobe(wi) / norm);
}

Color CoatedConductorModel::f(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return Color(0.0f);
    Color result = directF(wo, wi) + trappedF(wo, wi);
    if (!coat.smooth()) {
        const Vec3 m = glm::normalize(wo + wi);
        const float fresnel = fresnelDielectric(glm::dot(wo, m), layers->coatEta());
        result += Color(fresnel * coat.d(m) * coat.g(wo, wi) / (4.0f * wo.z * wi.z));
    }
    return result;
}

float CoatedConductorModel::pdf(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    const LobeProbabilities p = lobeProbabilities(wo);
    float result = 0.0f;
    if (!coat.smooth()) {
        const Vec3 m = glm::normalize(wo + wi);
        result += p.coat * coat.normalPdf(wo, m) / (4.0f * glm::dot(wo, m));
    }
    if (!metal.smooth()) {
        const Vec3 o = inside(wo), i = inside(wi);
        const Vec3 m = glm::normalize(o + i);
        const float pdfInside = metal.normalPdf(o, m) / (4.0f * glm::dot(o, m));
        // dw_i' / dw_i = cos theta_i / (eta^2 cos theta_i') (Snell's law
        // differentiated: cos theta dtheta = eta cos theta' dtheta').
        const float eta = layers->coatEta();
        result += p.direct * pdfInside * wi.z / (eta * eta * i.z);
        result += std::max(0.0f, 1.0f - p.coat - p.direct) * cosineHemispherePdf(wi.z);
    }
    return result;
}

std::optional<BsdfSample> CoatedConductorModel::sample(const Vec3& wo, float uLobe, const Vec2& u) const {
    if (wo.z <= 0.0f) return std::nullopt;
    const float coatF = fresnelDielectric(wo.z, layers->coatEta());
    if (specular())  // both deltas point the same way: one mirror, everything summed
        return deltaReflection(wo, Color(coatF) + mirrorThroughCoat(wo), 1.0f);
    const LobeProbabilities p = lobeProbabilities(wo);
    if (uLobe < p.coat) {
        if (coat.smooth()) return deltaReflection(wo, Color(coatF / p.coat), p.coat);
        const Vec3 m = coat.sampleNormal(wo, u);
        if (glm::dot(wo, m) <= 0.0f) return std::nullopt;
        return completeSample(*this, wo, reflectDir(wo, m));
    }
    if (uLobe < p.coat + p.direct || metal.smooth()) {
        if (metal.smooth()) return deltaReflection(wo, mirrorThroughCoat(wo) / p.direct, p.direct);
        const Vec3 o = inside(wo);
        const Vec3 m = metal.sampleNormal(o, u);
        if (glm::dot(o, m) <= 0.0f) return std::nullopt;
        const Vec3 i = reflectDir(o, m);
        if (i.z <= 0.0f) return std::nullopt;
        const std::optional<Vec3> wi = outside(i, layers->coatEta());
        if (!wi) return std::nullopt;
        return completeSample(*this, wo, *wi);
    }
    return completeSample(*this, wo, sampleCosineHemisphere(u));
}

}  // namespace strahl::bsdf_models
