// Burley's principled BSDF as Mitsuba 3 defines it: the solid model
// ("principled") and the thin sheet ("principledthin"). Written from the
// definitions in docs/materials.md, "Principled"; the directions follow
// strahl's convention (wo towards the viewer, wi towards the light), which
// are Mitsuba's si.wi and wo.
//
// Sampling: the solid model picks its specular lobe, the clearcoat or the
// diffuse with weights 1 : clearcoat / 4 : (1 - metallic)(1 - transmission)
// and splits the specular lobe between reflection and refraction by the
// Fresnel reflectance at the sampled visible normal (inside the object only
// the specular lobe exists); the thin model picks reflection and
// transmission, each specular and diffuse, by their weights. pdf() is the
// density of that whole procedure, and a sample reports f() and pdf().

#include <algorithm>
#include <cmath>

#include "lobe_sampling.h"
#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/local_frame.h"
#include "strahl/bsdf/principled.h"
#include "strahl/core/sampling.h"

namespace strahl {

namespace {

// Rec. 709 luminance, Mitsuba's luminance() of an RGB colour.
float luminance(const Color& c) {
    return 0.212671f * c.r + 0.715160f * c.g + 0.072169f * c.b;
}

// Mitsuba's calc_dist_params: alpha = roughness^2 stretched by the aspect
// sqrt(1 - 0.9 anisotropic) (Burley 2012), each axis at least 0.001.
MicrofacetDistribution principledGgx(float roughness, float anisotropic) {
    const float r2 = roughness * roughness;
    const float aspect = std::sqrt(1.0f - 0.9f * anisotropic);
    return MicrofacetDistribution(std::max(0.001f, r2 / aspect), std::max(0.001f, r2 * aspect),
                                  {MicrofacetType::Ggx, MicrofacetMasking::Separable});
}

float clamp01(float x) {
    return std::clamp(x, 0.0f, 1.0f);
}

}  // namespace

Color principledSchlick(const Color& f0, float cosThetaM, float eta) {
    const float etaIt = cosThetaM >= 0.0f ? eta : 1.0f / eta;
    if (etaIt > 1.0f) return fresnelSchlick(f0, std::abs(cosThetaM));
    // Inside the denser medium: Schlick's curve of the transmitted angle.
    const float etaTi = 1.0f / etaIt;
    const float cos2T = 1.0f - (1.0f - cosThetaM * cosThetaM) * etaTi * etaTi;
    return fresnelSchlick(f0, std::sqrt(std::max(cos2T, 0.0f)));
}

float gtr1D(float cosThetaM, float alpha) {
    const float a2 = alpha * alpha;
    return (a2 - 1.0f) / (kPi * std::log(a2) * (1.0f + (a2 - 1.0f) * cosThetaM * cosThetaM));
}

Vec3 sampleGtr1(float alpha, const Vec2& u) {
    // Inverting the CDF of cos theta_m under D cos: cos^2 = (1 - a^(2 (1 - u))) / (1 - a^2).
    const float a2 = alpha * alpha;
    const float cos2 = (1.0f - std::pow(a2, 1.0f - u.x)) / (1.0f - a2);
    const float cosTheta = std::sqrt(std::clamp(cos2, 0.0f, 1.0f));
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const float phi = 2.0f * kPi * u.y;
    return Vec3(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
}

PrincipledLobes::PrincipledLobes(const PrincipledParameters& given) : p(given) {
    p.base = glm::clamp(p.base, Color(0.0f), Color(1.0f));
    for (float* x : {&p.roughness, &p.anisotropic, &p.metallic, &p.specularTint, &p.sheen,
                     &p.sheenTint, &p.clearcoat, &p.clearcoatGloss, &p.transmission, &p.flatness})
        *x = clamp01(*x);
    p.diffuseTransmission = std::clamp(p.diffuseTransmission, 0.0f, 2.0f);
    if (p.thin) p.metallic = p.clearcoat = 0.0f;  // the thin model has neither
    specular = principledGgx(p.roughness, p.anisotropic);
    // Burley 2015, figure 15: a thin sheet's transmission is as rough as a
    // solid's would be after two refractions.
    thinTransmission = principledGgx((0.65f * p.eta - 0.35f) * p.roughness, p.anisotropic);
    const float lum = luminance(p.base);
    cTint = lum > 0.0f ? p.base / lum : Color(1.0f);
    sheenColor = glm::mix(Color(1.0f), cTint, p.sheenTint);
    brdfWeight = (1.0f - p.metallic) * (1.0f - p.transmission);
    btdfWeight = (1.0f - p.metallic) * p.transmission;
    clearcoatAlpha = 0.1f + (0.001f - 0.1f) * p.clearcoatGloss;
    diffuseTransmission = p.diffuseTransmission / 2.0f;
}

namespace bsdf_models {

namespace {

// Burley's diffuse with retro-reflection, blended towards the fake
// subsurface term by flatness, per unit base colour (without 1/pi); cosO and
// cosI are the (positive) cosines of the view and light directions and
// cosD = wi . h.
float disneyDiffuse(const PrincipledParameters& p, float cosO, float cosI, float cosD) {
    const float fo = schlickWeight(cosI), fi = schlickWeight(cosO);
    const float diffuse = (1.0f - 0.5f * fi) * (1.0f - 0.5f * fo);
    const float rr = 2.0f * p.roughness * cosD * cosD;
    const float retro = rr * (fo + fi + fo * fi * (rr - 1.0f));
    if (p.flatness <= 0.0f) return diffuse + retro;
    // Hanrahan-Krueger-like fake subsurface, with Fss90 flattening the
    // retro-reflection by roughness.
    const float fss90 = 0.5f * rr;
    const float fss = (1.0f + (fss90 - 1.0f) * fo) * (1.0f + (fss90 - 1.0f) * fi);
    const float subsurface = 1.25f * (fss * (1.0f / (cosO + cosI) - 0.5f) + 0.5f);
    return diffuse + retro + p.flatness * (subsurface - diffuse - retro);
}

// The sheen: sheen Fd(cos_d) c_sheen, Fd Schlick's weight.
Color sheenTerm(const PrincipledLobes& l, float cosD) {
    return l.p.sheen * schlickWeight(std::abs(cosD)) * l.sheenColor;
}

// ---- The solid model -------------------------------------------------------

// The half vector of (wo, wi) facing +z, with the relative index etaPath
// along the light path (1 for reflection); false where no microfacet facing
// both directions from their own sides connects them.
bool solidHalfVector(const Vec3& wo, const Vec3& wi, float eta, Vec3& h, float& etaPath) {
    const bool reflect = wo.z * wi.z > 0.0f;
    etaPath = reflect ? 1.0f : (wo.z > 0.0f ? eta : 1.0f / eta);
    h = wo + wi * etaPath;
    if (glm::dot(h, h) == 0.0f) return false;
    h = glm::normalize(h);
    if (h.z < 0.0f) h = -h;
    return glm::dot(wo, h) * wo.z > 0.0f && glm::dot(wi, h) * wi.z > 0.0f;
}

// Mitsuba's principled_fresnel: from the front, the dielectric's F for the
// undyed, untinted share, Schlick's of the base colour for the metal and of
// the tinted dielectric for the tint; from inside only the refracting share's F.
Color solidFresnel(const PrincipledLobes& l, float f, float cosWoH, bool front) {
    const PrincipledParameters& p = l.p;
    if (!front) return Color(l.btdfWeight * f);
    Color fresnel((1.0f - p.metallic) * (1.0f - p.specularTint) * f);
    if (p.metallic > 0.0f) fresnel += p.metallic * principledSchlick(p.base, cosWoH, p.eta);
    if (p.specularTint > 0.0f)
        fresnel += (1.0f - p.metallic) * p.specularTint *
                   principledSchlick(l.cTint * dielectricF0(p.eta), cosWoH, p.eta);
    return fresnel;
}

// The lobe choice of the solid model from the front: specular 1 (split into
// reflection 1 - btdf (1 - F) and refraction btdf (1 - F)), clearcoat a
// quarter of its weight (its share of the energy), diffuse the brdf weight.
struct SolidLobeProbabilities {
    float reflection, refraction, clearcoat, diffuse;
};

SolidLobeProbabilities solidProbabilities(const PrincipledLobes& l, float fresnel, bool front) {
    if (!front) return {fresnel, 1.0f - fresnel, 0.0f, 0.0f};
    const float clearcoat = 0.25f * l.p.clearcoat, diffuse = l.brdfWeight;
    const float norm = 1.0f / (1.0f + clearcoat + diffuse);
    const float refraction = l.btdfWeight * (1.0f - fresnel);
    return {(1.0f - refraction) * norm, refraction * norm, clearcoat * norm, diffuse * norm};
}

// The clearcoat's masking: Smith GGX with alpha 0.25 (Burley 2012).
const MicrofacetDistribution& clearcoatMasking() {
    static const MicrofacetDistribution masking(0.25f, 0.25f,
                                                {MicrofacetType::Ggx, MicrofacetMasking::Separable});
    return masking;
}

Color solidF(const PrincipledLobes& l, const Vec3& wo, const Vec3& wi) {
    const PrincipledParameters& p = l.p;
    if (wo.z == 0.0f || wi.z == 0.0f) return Color(0.0f);
    const bool front = wo.z > 0.0f, reflect = wo.z * wi.z > 0.0f;
    Vec3 h;
    float etaPath;
    const bool connected = solidHalfVector(wo, wi, p.eta, h, etaPath);
    Color f(0.0f);
    const float cosOH = glm::dot(wo, h), cosIH = glm::dot(wi, h);
    const float fresnel = fresnelDielectric(cosOH, p.eta);
    const float cosCos = std::abs(wo.z * wi.z);
    if (connected) {
        const float dg = l.specular.d(h) * l.specular.g(wo, wi);
        if (reflect) {
            f += solidFresnel(l, fresnel, cosOH, front) * (dg / (4.0f * cosCos));
        } else if (l.btdfWeight > 0.0f) {
            // Walter et al. 2007, eq. 21, in radiance: the 1 / etaPath^2 of the
            // radiance compression cancels the etaPath^2 of the Jacobian.
            const float denom = cosOH + etaPath * cosIH;
            f += glm::sqrt(p.base) * (l.btdfWeight * (1.0f - fresnel) * dg *
                                      std::abs(cosOH * cosIH) / (cosCos * denom * denom));
        }
    }
    if (!front || !reflect) return f;
    if (p.clearcoat > 0.0f && cosOH > 0.0f) {
        // A fixed index 1.5 coat (F0 = 0.04) with the GTR1 distribution.
        const float fcc = fresnelSchlick(0.04f, cosOH);
        const float dcc = gtr1D(h.z, l.clearcoatAlpha);
        const float gcc = clearcoatMasking().g(wo, wi);
        f += Color(0.25f * p.clearcoat * fcc * dcc * gcc / (4.0f * cosCos));
    }
    f += l.brdfWeight * p.base * (kInvPi * disneyDiffuse(p, wo.z, wi.z, cosIH));
    if (p.sheen > 0.0f) f += (1.0f - p.metallic) * sheenTerm(l, cosIH);
    return f;
}

float solidPdf(const PrincipledLobes& l, const Vec3& wo, const Vec3& wi) {
    const PrincipledParameters& p = l.p;
    if (wo.z == 0.0f || wi.z == 0.0f) return 0.0f;
    const bool front = wo.z > 0.0f, reflect = wo.z * wi.z > 0.0f;
    Vec3 h;
    float etaPath;
    if (!solidHalfVector(wo, wi, p.eta, h, etaPath)) {
        // No microfacet connects them; only the diffuse lobe can.
        if (!front || !reflect) return 0.0f;
        return solidProbabilities(l, 0.0f, true).diffuse * cosineHemispherePdf(wi.z);
    }
    const float cosOH = glm::dot(wo, h), cosIH = glm::dot(wi, h);
    const SolidLobeProbabilities prob = solidProbabilities(l, fresnelDielectric(cosOH, p.eta), front);
    const float visible = l.specular.normalPdf(wo, h);
    float pdf = 0.0f;
    if (reflect) {
        pdf += prob.reflection * visible / (4.0f * std::abs(cosIH));
    } else {
        const float denom = cosOH + etaPath * cosIH;
        pdf += prob.refraction * visible * etaPath * etaPath * std::abs(cosIH) / (denom * denom);
    }
    if (front && reflect) {
        if (prob.clearcoat > 0.0f && cosOH > 0.0f)
            pdf += prob.clearcoat * gtr1D(h.z, l.clearcoatAlpha) * h.z / (4.0f * std::abs(cosIH));
        pdf += prob.diffuse * cosineHemispherePdf(wi.z);
    }
    return pdf;
}

std::optional<BsdfSample> solidSample(const PrincipledLobes& l, const Vec3& wo, float uLobe,
                                      const Vec2& u) {
    const PrincipledParameters& p = l.p;
    const bool front = wo.z > 0.0f;
    if (!front && l.btdfWeight <= 0.0f) return std::nullopt;  // nothing inside to scatter
    const Vec3 m = l.specular.sampleNormal(wo, u);
    const SolidLobeProbabilities prob =
        solidProbabilities(l, fresnelDielectric(glm::dot(wo, m), p.eta), front);
    Vec3 wi;
    BsdfSample s;
    if (uLobe < prob.diffuse) {
        wi = sampleCosineHemisphere(u);
    } else if (uLobe < prob.diffuse + prob.clearcoat) {
        const Vec3 mcc = sampleGtr1(l.clearcoatAlpha, u);
        if (glm::dot(wo, mcc) <= 0.0f) return std::nullopt;
        wi = reflectDir(wo, mcc);
    } else if (uLobe < prob.diffuse + prob.clearcoat + prob.refraction) {
        float etap;
        if (!refractDir(wo, m, p.eta, wi, etap)) return std::nullopt;
        s.transmission = true;
        s.eta = etap;
    } else {
        wi = reflectDir(wo, m);
    }
    if (s.transmission == sameHemisphere(wo, wi) || wi.z == 0.0f) return std::nullopt;
    s.wi = wi;
    s.pdf = solidPdf(l, wo, wi);
    if (!(s.pdf > 0.0f)) return std::nullopt;
    s.f = solidF(l, wo, wi);
    return s;
}

// ---- The thin model ----------------------------------------------------------

// The thin sheet is the same from both sides: both directions are turned so
// that wo is above. Transmission leaves straight through, so its half vector
// is that of the reflection mirrored back up.
struct ThinGeometry {
    Vec3 wo, wi, h;
    bool reflect;
};

std::optional<ThinGeometry> thinGeometry(const Vec3& wo, const Vec3& wi) {
    if (wo.z == 0.0f || wi.z == 0.0f) return std::nullopt;
    const float side = wo.z > 0.0f ? 1.0f : -1.0f;
    ThinGeometry g{wo * side, wi * side, Vec3(0.0f), false};
    g.reflect = g.wi.z > 0.0f;
    const Vec3 mirrored(g.wi.x, g.wi.y, std::abs(g.wi.z));
    g.h = g.wo + mirrored;
    if (glm::dot(g.h, g.h) == 0.0f) return std::nullopt;
    g.h = glm::normalize(g.h);
    return g;
}

struct ThinLobeProbabilities {
    float reflection, transmission, diffuse, diffuseTransmission;
};

ThinLobeProbabilities thinProbabilities(const PrincipledLobes& l) {
    const float st = l.p.transmission, dt = l.diffuseTransmission;
    ThinLobeProbabilities prob{0.5f * st, 0.5f * st, (1.0f - st) * (1.0f - dt), (1.0f - st) * dt};
    const float norm = 1.0f / (prob.reflection + prob.transmission + prob.diffuse + prob.diffuseTransmission);
    return {prob.reflection * norm, prob.transmission * norm, prob.diffuse * norm,
            prob.diffuseTransmission * norm};
}

Color thinF(const PrincipledLobes& l, const Vec3& wo, const Vec3& wi) {
    const PrincipledParameters& p = l.p;
    const std::optional<ThinGeometry> g = thinGeometry(wo, wi);
    if (!g) return Color(0.0f);
    const float st = p.transmission, dt = l.diffuseTransmission;
    const float cosO = g->wo.z, cosI = std::abs(g->wi.z);
    const float cosOH = glm::dot(g->wo, g->h), cosIH = glm::dot(g->wi, g->h);
    Color f(0.0f);
    if (st > 0.0f && cosOH > 0.0f) {
        const float fresnel = fresnelDielectric(cosOH, p.eta);
        if (g->reflect && cosIH > 0.0f) {
            const Color tinted = principledSchlick(l.cTint * dielectricF0(p.eta), cosOH, p.eta);
            const Color thinFresnel = glm::mix(Color(fresnel), tinted, p.specularTint);
            f += st * thinFresnel *
                 (l.specular.d(g->h) * l.specular.g(g->wo, g->wi) / (4.0f * cosO * cosI));
        } else if (!g->reflect && cosIH < 0.0f) {
            const MicrofacetDistribution& t = l.thinTransmission;
            f += st * p.base * ((1.0f - fresnel) * t.d(g->h) * t.g(g->wo, g->wi) / (4.0f * cosO * cosI));
        }
    }
    if (st >= 1.0f) return f;
    if (g->reflect && dt < 1.0f) {
        const float weight = (1.0f - st) * (1.0f - dt);
        f += weight * p.base * (kInvPi * disneyDiffuse(p, cosO, cosI, cosIH));
        if (p.sheen > 0.0f) f += weight * sheenTerm(l, cosIH);
    } else if (!g->reflect && dt > 0.0f) {
        f += (1.0f - st) * dt * p.base * kInvPi;
    }
    return f;
}

float thinPdf(const PrincipledLobes& l, const Vec3& wo, const Vec3& wi) {
    const std::optional<ThinGeometry> g = thinGeometry(wo, wi);
    if (!g) return 0.0f;
    const ThinLobeProbabilities prob = thinProbabilities(l);
    const float cosOH = glm::dot(g->wo, g->h), cosIH = glm::dot(g->wi, g->h);
    float pdf = 0.0f;
    if (cosOH > 0.0f) {
        // dh/dwi of the reflection that wi is (or, transmitted, mirrors):
        // 1 / (4 wr . h), with wr = wi turned above; wr . h = wo . h > 0.
        const float jacobian = 1.0f / (4.0f * cosOH);
        if (g->reflect && cosIH > 0.0f)
            pdf += prob.reflection * l.specular.normalPdf(g->wo, g->h) * jacobian;
        if (!g->reflect && cosIH < 0.0f)
            pdf += prob.transmission * l.thinTransmission.normalPdf(g->wo, g->h) * jacobian;
    }
    pdf += (g->reflect ? prob.diffuse : prob.diffuseTransmission) * cosineHemispherePdf(std::abs(g->wi.z));
    return pdf;
}

std::optional<BsdfSample> thinSample(const PrincipledLobes& l, const Vec3& wo, float uLobe,
                                     const Vec2& u) {
    const float side = wo.z > 0.0f ? 1.0f : -1.0f;
    const Vec3 up = wo * side;
    const ThinLobeProbabilities prob = thinProbabilities(l);
    Vec3 wi;
    if (uLobe < prob.reflection) {
        wi = reflectDir(up, l.specular.sampleNormal(up, u));
        if (wi.z <= 0.0f) return std::nullopt;
    } else if (uLobe < prob.reflection + prob.transmission) {
        const Vec3 m = l.thinTransmission.sampleNormal(up, u);
        wi = reflectDir(up, m);
        if (wi.z <= 0.0f) return std::nullopt;
        wi.z = -wi.z;  // straight through: no bending in a thin sheet
        // The microfacet must face away from the light it lets through (as
        // thinF and thinPdf require): Mitsuba rejects the others too.
        if (glm::dot(wi, m) >= 0.0f) return std::nullopt;
    } else if (uLobe < prob.reflection + prob.transmission + prob.diffuse) {
        wi = sampleCosineHemisphere(u);
    } else {
        wi = -sampleCosineHemisphere(u);
    }
    BsdfSample s;
    s.wi = wi * side;
    s.transmission = wi.z < 0.0f;
    s.pdf = thinPdf(l, wo, s.wi);
    if (!(s.pdf > 0.0f)) return std::nullopt;
    s.f = thinF(l, wo, s.wi);
    return s;
}

}  // namespace

bool PrincipledModel::opaque() const {
    return !lobes->p.thin && lobes->btdfWeight <= 0.0f;
}

Color PrincipledModel::f(const Vec3& wo, const Vec3& wi) const {
    return lobes->p.thin ? thinF(*lobes, wo, wi) : solidF(*lobes, wo, wi);
}

float PrincipledModel::pdf(const Vec3& wo, const Vec3& wi) const {
    return lobes->p.thin ? thinPdf(*lobes, wo, wi) : solidPdf(*lobes, wo, wi);
}

std::optional<BsdfSample> PrincipledModel::sample(const Vec3& wo, float uLobe, const Vec2& u) const {
    if (wo.z == 0.0f) return std::nullopt;
    return lobes->p.thin ? thinSample(*lobes, wo, uLobe, u) : solidSample(*lobes, wo, uLobe, u);
}

}  // namespace bsdf_models

}  // namespace strahl
