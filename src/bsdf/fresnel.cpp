// Fresnel equations (Born & Wolf, Principles of Optics, 1.5; pbrt-v4 9.3).
// Derivations in docs/materials.md, "Fresnel reflectance".

#include "strahl/bsdf/fresnel.h"

#include <algorithm>
#include <cmath>
#include <complex>

namespace strahl {

namespace {

// The dielectric equation in double precision, for light arriving from the
// outside (cosI in [0, 1]) of an interface with relative index eta.
double fresnelDielectricOutside(double cosI, double eta) {
    const double sin2T = (1.0 - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0) return 1.0;
    const double cosT = std::sqrt(1.0 - sin2T);
    const double rPar = (eta * cosI - cosT) / (eta * cosI + cosT);
    const double rPerp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return 0.5 * (rPar * rPar + rPerp * rPerp);
}

}  // namespace

float fresnelDielectric(float cosThetaI, float eta) {
    float cosI = std::clamp(cosThetaI, -1.0f, 1.0f);
    if (cosI < 0.0f) {  // arriving from inside: the relative index inverts
        eta = 1.0f / eta;
        cosI = -cosI;
    }
    const float sin2T = (1.0f - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0f) return 1.0f;  // total internal reflection
    const float cosT = std::sqrt(std::max(0.0f, 1.0f - sin2T));
    // Both denominators are positive: cosT > 0 whenever sin2T < 1.
    const float rPar = (eta * cosI - cosT) / (eta * cosI + cosT);
    const float rPerp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return 0.5f * (rPar * rPar + rPerp * rPerp);
}

float fresnelConductor(float cosThetaI, float eta, float k) {
    if (k <= 0.0f) return eta > 0.0f ? fresnelDielectric(std::abs(cosThetaI), eta) : 1.0f;
    using Complex = std::complex<float>;
    const float cosI = std::clamp(cosThetaI, 0.0f, 1.0f);
    const Complex n(eta, k);
    // Snell's law with a complex index: sin^2 t = sin^2 i / n^2 and the complex
    // cosine of the "transmitted" angle (principal root, Re >= 0).
    const Complex sin2T = (1.0f - cosI * cosI) / (n * n);
    const Complex cosT = std::sqrt(Complex(1.0f) - sin2T);
    const Complex rPar = (n * cosI - cosT) / (n * cosI + cosT);
    const Complex rPerp = (cosI - n * cosT) / (cosI + n * cosT);
    const float r = 0.5f * (std::norm(rPar) + std::norm(rPerp));
    // |r| <= 1 analytically; the clamp only absorbs rounding.
    return std::isfinite(r) ? std::clamp(r, 0.0f, 1.0f) : 1.0f;
}

Color fresnelConductor(float cosThetaI, const Color& eta, const Color& k) {
    return Color(fresnelConductor(cosThetaI, eta.r, k.r), fresnelConductor(cosThetaI, eta.g, k.g),
                 fresnelConductor(cosThetaI, eta.b, k.b));
}

namespace {

float integrateDiffuseReflectance(float eta) {
    if (!(eta > 0.0f) || eta == 1.0f) return 0.0f;
    if (eta < 1.0f) {
        // From the optically thinner side the integrand has a total-internal-
        // reflection kink; use the smooth side and the etendue relation
        // 1 - Fbar(eta) = eta^2 (1 - Fbar(1 / eta)).
        return 1.0f - eta * eta * (1.0f - integrateDiffuseReflectance(1.0f / eta));
    }
    // Composite Simpson on 2 F(mu) mu over [0, 1]. F is analytic there for
    // eta > 1 (its only near-singularity sits at mu^2 = 1 - eta^2 < 0), so 128
    // intervals give ~1e-7 absolute error down to eta = 1.01.
    constexpr int kIntervals = 128;
    const double h = 1.0 / kIntervals;
    double sum = 0.0;
    for (int i = 0; i <= kIntervals; ++i) {
        const double mu = i * h;
        const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
        sum += weight * 2.0 * mu * fresnelDielectricOutside(mu, eta);
    }
    return static_cast<float>(sum * h / 3.0);
}

}  // namespace

float fresnelDiffuseReflectance(float eta) {
    // Materials are rebuilt at every shading point (textured parameters), almost
    // always with the same index: remember the last one per thread (0.7 us saved
    // per plastic BSDF).
    thread_local float lastEta = 1.0f, lastValue = 0.0f;
    if (eta != lastEta) {
        lastValue = integrateDiffuseReflectance(eta);
        lastEta = eta;
    }
    return lastValue;
}

}  // namespace strahl
