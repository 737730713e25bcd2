// The hair fibre BSDF (bsdf_models.h, HairModel): Chiang et al. 2016 with the
// longitudinal term of d'Eon et al. 2011, written from the papers' equations
// (docs/materials.md, "Hair", has them with the conventions used here).

#include <algorithm>
#include <cmath>

#include "strahl/bsdf/bsdf.h"
#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/core/error.h"

namespace strahl {

namespace {

using bsdf_models::HairModel;

constexpr int kPMax = 3;  // R, TT, TRT, then the rest as one lobe
constexpr float kTwoPi = 2.0f * kPi;

float safeSqrt(float x) { return std::sqrt(std::max(0.0f, x)); }
float safeAsin(float x) { return std::asin(std::clamp(x, -1.0f, 1.0f)); }

// The modified Bessel function I0 by its series Σ (x²/4)^i / (i!)², ten terms
// (enough for x < 12, where logI0 switches to the asymptotic form).
float besselI0(float x) {
    float value = 0.0f, term = 1.0f;
    const float q = 0.25f * x * x;
    for (int i = 0; i < 10; ++i) {
        value += term;
        term *= q / float((i + 1) * (i + 1));
    }
    return value;
}

// log I0(x); for x > 12, I0(x) ≈ e^x / √(2πx) (1 + 1/(8x)).
float logBesselI0(float x) {
    if (x > 12.0f) return x + 0.5f * (-std::log(kTwoPi) + std::log(1.0f / x) + 1.0f / (8.0f * x));
    return std::log(besselI0(x));
}

// d'Eon's longitudinal scattering function, normalised so that
// ∫ M cos θi dθi = 1: M = csch(1/v) / (2v) · exp(−sin θi sin θo / v) · I0(cos θi cos θo / v),
// in the log domain for small variances, where the factors overflow.
float longitudinal(float cosThetaI, float cosThetaO, float sinThetaI, float sinThetaO, float v) {
    const float a = cosThetaI * cosThetaO / v, b = sinThetaI * sinThetaO / v;
    if (v <= 0.1f) return std::exp(logBesselI0(a) - b - 1.0f / v + 0.6931f + std::log(1.0f / (2.0f * v)));
    return std::exp(-b) * besselI0(a) / (std::sinh(1.0f / v) * 2.0f * v);
}

// The attenuation of each path: Fresnel at the cuticle for the angle between
// the ray and the fibre's normal at the entry (cos θo cos γo), the
// transmittance T of one crossing, and the rest summed as a geometric series.
void attenuation(float cosThetaO, float eta, float h, const Color& T, Color ap[kPMax + 1]) {
    const float cosGammaO = safeSqrt(1.0f - h * h);
    const float f = fresnelDielectric(cosThetaO * cosGammaO, eta);
    ap[0] = Color(f);
    ap[1] = (1.0f - f) * (1.0f - f) * T;
    for (int p = 2; p < kPMax; ++p) ap[p] = ap[p - 1] * T * f;
    // At a grazing entry (f = 1) nothing enters: the series is empty, not 0/0.
    const Color rest = Color(1.0f) - T * f;
    for (int c = 0; c < 3; ++c) ap[kPMax][c] = rest[c] > 0.0f ? ap[kPMax - 1][c] * f * T[c] / rest[c] : 0.0f;
}

// The azimuthal deflection of path p entering at γo and crossing at γt.
float deflection(int p, float gammaO, float gammaT) {
    const float fp = static_cast<float>(p);
    return 2.0f * fp * gammaT - 2.0f * gammaO + fp * kPi;
}

float logistic(float x, float s) {
    x = std::abs(x);
    const float e = std::exp(-x / s);
    return e / (s * (1.0f + e) * (1.0f + e));
}
float logisticCdf(float x, float s) { return 1.0f / (1.0f + std::exp(-x / s)); }
float trimmedLogistic(float x, float s, float a, float b) {
    return logistic(x, s) / (logisticCdf(b, s) - logisticCdf(a, s));
}
float sampleTrimmedLogistic(float u, float s, float a, float b) {
    const float k = logisticCdf(b, s) - logisticCdf(a, s);
    const float x = -s * std::log(1.0f / (u * k + logisticCdf(a, s)) - 1.0f);
    return std::clamp(x, a, b);
}

// The azimuthal lobe of path p: the trimmed logistic around Φ(p), with φ −
// Φ wrapped into [−π, π].
float azimuthal(float phi, int p, float s, float gammaO, float gammaT) {
    float dphi = phi - deflection(p, gammaO, gammaT);
    dphi = std::remainder(dphi, kTwoPi);  // into [−π, π]
    return trimmedLogistic(dphi, s, -kPi, kPi);
}

// Everything f, pdf and sample need about wo.
struct Outgoing {
    float sinThetaO, cosThetaO, phiO, h, gammaO, gammaT, cosThetaT;
};

Outgoing outgoing(const HairModel& m, const Vec3& wo) {
    Outgoing o;
    o.sinThetaO = std::clamp(wo.x, -1.0f, 1.0f);
    o.cosThetaO = safeSqrt(1.0f - o.sinThetaO * o.sinThetaO);
    o.phiO = std::atan2(wo.z, wo.y);
    if (m.hFixed >= -1.0f && m.hFixed <= 1.0f) {
        o.h = m.hFixed;
    } else {
        // The entry offset: the frame's z is the normal where the ray met the
        // fibre, so h = sin(angle from that normal to ŵ) = −ŵ_y.
        const float len = std::sqrt(wo.y * wo.y + wo.z * wo.z);
        o.h = len > 0.0f ? std::clamp(-wo.y / len, -1.0f, 1.0f) : 0.0f;
    }
    o.gammaO = safeAsin(o.h);
    // The refracted ray, by the modified index of Bravais for the
    // projection onto the normal plane.
    const float sinThetaT = o.sinThetaO / m.eta;
    o.cosThetaT = safeSqrt(1.0f - sinThetaT * sinThetaT);
    const float etaP = safeSqrt(m.eta * m.eta - o.sinThetaO * o.sinThetaO) / std::max(o.cosThetaO, 1e-6f);
    o.gammaT = safeAsin(o.h / etaP);
    return o;
}

// The transmittance of one crossing: the chord 2 cos γt of the unit circle,
// stretched by the inclination to 2 cos γt / cos θt, in units of the
// fibre's radius (the unit sigma_a is measured in).
Color crossing(const HairModel& m, const Outgoing& o) {
    const float cosGammaT = safeSqrt(1.0f - std::sin(o.gammaT) * std::sin(o.gammaT));
    return glm::exp(-m.sigmaA * (2.0f * cosGammaT / std::max(o.cosThetaT, 1e-6f)));
}

// θo tilted by the scales for path p: R by −2α, TT by α, TRT by 4α.
void tilted(const HairModel& m, const Outgoing& o, int p, float& sinT, float& cosT) {
    if (p == 0) {
        sinT = o.sinThetaO * m.cos2kAlpha[1] - o.cosThetaO * m.sin2kAlpha[1];
        cosT = o.cosThetaO * m.cos2kAlpha[1] + o.sinThetaO * m.sin2kAlpha[1];
    } else if (p == 1) {
        sinT = o.sinThetaO * m.cos2kAlpha[0] + o.cosThetaO * m.sin2kAlpha[0];
        cosT = o.cosThetaO * m.cos2kAlpha[0] - o.sinThetaO * m.sin2kAlpha[0];
    } else if (p == 2) {
        sinT = o.sinThetaO * m.cos2kAlpha[2] + o.cosThetaO * m.sin2kAlpha[2];
        cosT = o.cosThetaO * m.cos2kAlpha[2] - o.sinThetaO * m.sin2kAlpha[2];
    } else {
        sinT = o.sinThetaO;
        cosT = o.cosThetaO;
    }
    cosT = std::abs(cosT);
}

// The probability of sampling each path: its attenuation's mean over the
// channels, normalised.
void pathProbabilities(const Color ap[kPMax + 1], float pdf[kPMax + 1]) {
    float sum = 0.0f;
    for (int p = 0; p <= kPMax; ++p) sum += pdf[p] = (ap[p].r + ap[p].g + ap[p].b) / 3.0f;
    for (int p = 0; p <= kPMax; ++p) pdf[p] = sum > 0.0f ? pdf[p] / sum : (p == 0 ? 1.0f : 0.0f);
}

// What f and pdf share for one wo: the outgoing terms, the attenuation of
// each path and the probability of sampling it.
struct Paths {
    Outgoing o;
    Color ap[kPMax + 1];
    float probability[kPMax + 1];

    Paths(const HairModel& m, const Vec3& wo) : o(outgoing(m, wo)) {
        attenuation(o.cosThetaO, m.eta, o.h, crossing(m, o), ap);
        pathProbabilities(ap, probability);
    }
};

// The longitudinal lobe of every path towards wi and the azimuthal lobe of
// all but the last (whose azimuth is uniform, 1/2π).
void lobes(const HairModel& m, const Outgoing& o, const Vec3& wi, float M[kPMax + 1], float N[kPMax]) {
    const float sinThetaI = std::clamp(wi.x, -1.0f, 1.0f);
    const float cosThetaI = safeSqrt(1.0f - sinThetaI * sinThetaI);
    const float phi = std::atan2(wi.z, wi.y) - o.phiO;
    for (int p = 0; p < kPMax; ++p) {
        float sinT, cosT;
        tilted(m, o, p, sinT, cosT);
        M[p] = longitudinal(cosThetaI, cosT, sinThetaI, sinT, m.v[p]);
        N[p] = azimuthal(phi, p, m.s, o.gammaO, o.gammaT);
    }
    M[kPMax] = longitudinal(cosThetaI, o.cosThetaO, sinThetaI, o.sinThetaO, m.v[kPMax]);
}

Color evalF(const Paths& paths, const float M[kPMax + 1], const float N[kPMax], const Vec3& wi) {
    Color sum(0.0f);
    for (int p = 0; p < kPMax; ++p) sum += M[p] * paths.ap[p] * N[p];
    sum += M[kPMax] * paths.ap[kPMax] / kTwoPi;
    const float cosN = std::abs(wi.z);
    return cosN > 0.0f ? sum / cosN : Color(0.0f);
}

float evalPdf(const Paths& paths, const float M[kPMax + 1], const float N[kPMax]) {
    float pdf = 0.0f;
    for (int p = 0; p < kPMax; ++p) pdf += M[p] * paths.probability[p] * N[p];
    pdf += M[kPMax] * paths.probability[kPMax] / kTwoPi;
    return pdf;
}

}  // namespace

namespace bsdf_models {

Color HairModel::f(const Vec3& wo, const Vec3& wi) const {
    const Paths paths(*this, wo);
    float M[kPMax + 1], N[kPMax];
    lobes(*this, paths.o, wi, M, N);
    return evalF(paths, M, N, wi);
}

float HairModel::pdf(const Vec3& wo, const Vec3& wi) const {
    const Paths paths(*this, wo);
    float M[kPMax + 1], N[kPMax];
    lobes(*this, paths.o, wi, M, N);
    return evalPdf(paths, M, N);
}

std::optional<BsdfSample> HairModel::sample(const Vec3& wo, float uLobe, const Vec2& u) const {
    const Paths paths(*this, wo);
    const Outgoing& o = paths.o;
    const float* probability = paths.probability;
    // Choose the path with uLobe, then reuse what is left of it (rescaled
    // to [0, 1)) for the azimuth.
    int p = 0;
    float uAzimuth = uLobe;
    for (; p < kPMax; ++p) {
        if (uAzimuth < probability[p]) break;
        uAzimuth -= probability[p];
    }
    uAzimuth = std::min(probability[p] > 0.0f ? uAzimuth / probability[p] : 0.0f, 0.99999994f);

    float sinT, cosT;
    tilted(*this, o, p, sinT, cosT);
    // The longitudinal lobe sampled exactly (d'Eon et al. 2011): the cosine
    // of the angle to the tilted mirror direction is 1 + v ln(u + (1 − u) e^(−2/v)).
    const float u0 = std::max(u.x, 1e-5f);
    const float cosTheta = 1.0f + v[p] * std::log(u0 + (1.0f - u0) * std::exp(-2.0f / v[p]));
    const float sinTheta = safeSqrt(1.0f - cosTheta * cosTheta);
    const float cosPhi = std::cos(kTwoPi * u.y);
    const float sinThetaI = -cosTheta * sinT + sinTheta * cosPhi * cosT;
    const float cosThetaI = safeSqrt(1.0f - sinThetaI * sinThetaI);
    const float dphi = p < kPMax ? deflection(p, o.gammaO, o.gammaT) + sampleTrimmedLogistic(uAzimuth, s, -kPi, kPi)
                                 : kTwoPi * uAzimuth;
    const float phiI = o.phiO + dphi;
    BsdfSample sample;
    sample.wi = Vec3(sinThetaI, cosThetaI * std::cos(phiI), cosThetaI * std::sin(phiI));
    // f and pdf of the sampled direction from the same path terms.
    float M[kPMax + 1], N[kPMax];
    lobes(*this, o, sample.wi, M, N);
    sample.pdf = evalPdf(paths, M, N);
    if (!(sample.pdf > 0.0f)) return std::nullopt;
    sample.f = evalF(paths, M, N, sample.wi);
    sample.transmission = sample.wi.z * wo.z < 0.0f;
    return sample;
}

}  // namespace bsdf_models

Bsdf Bsdf::hair(const Color& sigmaA, float betaM, float betaN, float alphaDegrees, float eta, float h) {
    if (!isFinite(sigmaA) || sigmaA.r < 0.0f || sigmaA.g < 0.0f || sigmaA.b < 0.0f)
        fail("hair: sigma_a must be finite and non-negative, got (", sigmaA.r, ", ", sigmaA.g, ", ", sigmaA.b, ")");
    if (!(betaM >= 0.0f && betaM <= 1.0f)) fail("hair: beta_m must lie in [0, 1], got ", betaM);
    if (!(betaN >= 0.0f && betaN <= 1.0f)) fail("hair: beta_n must lie in [0, 1], got ", betaN);
    if (!(std::abs(alphaDegrees) <= 45.0f)) fail("hair: alpha must lie in [-45, 45] degrees, got ", alphaDegrees);
    if (!(eta > 1.0f && std::isfinite(eta))) fail("hair: eta must be > 1, got ", eta);
    HairModel m;
    m.sigmaA = sigmaA;
    m.eta = eta;
    m.hFixed = h;
    // Chiang et al.'s fits of the lobe widths to beta_m and beta_n; a
    // minimum keeps the lobes finite (beta 0 would be a delta).
    const float bm = std::max(betaM, 0.01f), bn = std::max(betaN, 0.01f);
    const float sdM = 0.726f * bm + 0.812f * bm * bm + 3.7f * std::pow(bm, 20.0f);
    m.v[0] = sdM * sdM;
    m.v[1] = 0.25f * m.v[0];
    m.v[2] = 4.0f * m.v[0];
    m.v[3] = m.v[2];
    m.s = 0.626657069f * (0.265f * bn + 1.194f * bn * bn + 5.372f * std::pow(bn, 22.0f));  // √(π/8) · fit
    m.sin2kAlpha[0] = std::sin(alphaDegrees * kPi / 180.0f);
    m.cos2kAlpha[0] = safeSqrt(1.0f - m.sin2kAlpha[0] * m.sin2kAlpha[0]);
    for (int i = 1; i < 3; ++i) {
        m.sin2kAlpha[i] = 2.0f * m.cos2kAlpha[i - 1] * m.sin2kAlpha[i - 1];
        m.cos2kAlpha[i] = m.cos2kAlpha[i - 1] * m.cos2kAlpha[i - 1] - m.sin2kAlpha[i - 1] * m.sin2kAlpha[i - 1];
    }
    return Bsdf(m, hairColorFromSigmaA(sigmaA, betaN));
}

namespace {
// Chiang et al. 2016, eq. 9: sigma_a = (ln c / D(beta_n))², with D a
// polynomial fit of the multiple-scattering albedo.
float hairAlbedoPolynomial(float bn) {
    return 5.969f - 0.215f * bn + 2.532f * bn * bn - 10.73f * std::pow(bn, 3.0f) + 5.574f * std::pow(bn, 4.0f) +
           0.245f * std::pow(bn, 5.0f);
}
}  // namespace

Color Bsdf::hairSigmaAFromColor(const Color& c, float betaN) {
    const float d = hairAlbedoPolynomial(betaN);
    Color sigma;
    for (int i = 0; i < 3; ++i) {
        const float l = std::log(std::clamp(c[i], 1e-4f, 1.0f)) / d;
        sigma[i] = l * l;
    }
    return sigma;
}

Color Bsdf::hairColorFromSigmaA(const Color& sigmaA, float betaN) {
    const float d = hairAlbedoPolynomial(betaN);
    return glm::exp(-glm::sqrt(glm::max(sigmaA, Color(0.0f))) * d);
}

}  // namespace strahl
