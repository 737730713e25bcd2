// Rough-interface albedos by Gauss-Legendre quadrature over the sampled
// microfacet normals, and the plastic coat's tables. Derivation in
// docs/materials.md, "Plastic".

#include "strahl/bsdf/rough_coat.h"

#include <algorithm>
#include <cmath>

#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/local_frame.h"
#include "strahl/core/error.h"
#include "quadrature.h"

namespace strahl {

namespace {

// Quadrature resolution: the transmittance from outside is smooth in the
// sampling coordinates (32 x 32, Mitsuba's choice); from inside, total internal
// reflection puts a kink in the integrand, which needs more points (64 x 64
// agrees with 128 x 128 to 1e-5 in the average).
constexpr int kOutsideNodes = 32;
constexpr int kInsideNodes = 64;

// The table's i-th cosine, i / (kCosines - 1), kept off the horizon.
float tableCosine(int i) {
    return std::max(1e-6f, float(i) / float(RoughCoat::kCosines - 1));
}

// Mitsuba's rule for the internal reflectance: 2 x the plain mean of
// R(mu) mu over the table's cosines. It counts the end points fully and so
// sits about 1.5 % below the integral 2 int_0^1 R(mu) mu dmu (0.587 instead
// of 0.596 for a smooth coat of index 1.5); kept, because this coat is
// Mitsuba's roughplastic and should render as Mitsuba renders it.
template <typename InsideReflectance>
float internalReflectanceByMitsubasRule(InsideReflectance&& reflectance) {
    double sum = 0.0;
    for (int i = 0; i < RoughCoat::kCosines; ++i) {
        const float mu = tableCosine(i);
        sum += double(reflectance(mu)) * mu;
    }
    return float(2.0 * sum / RoughCoat::kCosines);
}

}  // namespace

InterfaceAlbedo roughInterfaceAlbedo(const MicrofacetDistribution& dist, float cosTheta,
                                     float eta, int nodes) {
    const float mu = std::clamp(cosTheta, 1e-4f, 1.0f);
    const Vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
    // For wi = reflect or refract(wo, m) the lobes' albedos are integrals over m:
    //   R = integral D(m) G(wo, wi) F(wo.m) |wo.m| / cos(theta_o) dm,
    //   T = the same with 1 - F and wi refracted (the Jacobians of both maps
    //       cancel against the lobes' denominators, docs/materials.md),
    // and m is drawn with density normalPdf(wo, m).
    const std::vector<QuadratureNode> q = gaussLegendre01(nodes);
    double r = 0.0, t = 0.0;
    forVisibleNormals(dist, wo, q, [&](const Vec3& m, float cosOm, double weight) {
        const float fresnel = fresnelDielectric(cosOm, eta);
        const Vec3 reflected = reflectDir(wo, m);
        if (reflected.z > 0.0f) r += weight * fresnel * dist.g(wo, reflected);
        Vec3 refracted;
        float etap;
        if (fresnel < 1.0f && refractDir(wo, m, eta, refracted, etap) && refracted.z < 0.0f)
            t += weight * (1.0f - fresnel) * dist.g(wo, refracted);
    });
    return {float(r), float(t)};
}

RoughCoat::RoughCoat(MicrofacetModel model, float eta, std::span<const float> alphas)
    : eta_(eta), alphas_(alphas.begin(), alphas.end()) {
    if (alphas_.empty() || !std::is_sorted(alphas_.begin(), alphas_.end()))
        fail("rough coat: the roughness nodes must be given in increasing order");
    for (const float alpha : alphas_) {
        const MicrofacetDistribution dist(alpha, alpha, model);
        if (dist.smooth()) {
            for (int i = 0; i < kCosines; ++i)
                transmittance_.push_back(1.0f - fresnelDielectric(tableCosine(i), eta));
            internalReflectance_.push_back(internalReflectanceByMitsubasRule(
                [&](float mu) { return fresnelDielectric(mu, 1.0f / eta); }));
            continue;
        }
        for (int i = 0; i < kCosines; ++i)
            transmittance_.push_back(
                roughInterfaceAlbedo(dist, tableCosine(i), eta, kOutsideNodes).transmittance);
        internalReflectance_.push_back(internalReflectanceByMitsubasRule([&](float mu) {
            return roughInterfaceAlbedo(dist, mu, 1.0f / eta, kInsideNodes).reflectance;
        }));
    }
}

RoughCoat::Bracket RoughCoat::bracket(float alpha) const {
    const auto above = std::upper_bound(alphas_.begin(), alphas_.end(), alpha);
    if (above == alphas_.begin()) return {0, 0, 0.0f};
    if (above == alphas_.end()) {
        const int last = int(alphas_.size()) - 1;
        return {last, last, 0.0f};
    }
    const int hi = int(above - alphas_.begin()), lo = hi - 1;
    return {lo, hi, (alpha - alphas_[lo]) / (alphas_[hi] - alphas_[lo])};
}

float RoughCoat::transmittance(float alpha, float cosTheta) const {
    const Bracket b = bracket(alpha);
    // Linear in cos(theta) between the table's evenly spaced entries.
    const float x = std::clamp(cosTheta, 0.0f, 1.0f) * (kCosines - 1);
    const int i = std::min(int(x), kCosines - 2);
    const float f = x - float(i);
    const auto row = [&](int a) {
        const float* t = &transmittance_[size_t(a) * kCosines];
        return t[i] + f * (t[i + 1] - t[i]);
    };
    return row(b.lo) + b.t * (row(b.hi) - row(b.lo));
}

float RoughCoat::internalReflectance(float alpha) const {
    const Bracket b = bracket(alpha);
    return internalReflectance_[b.lo] +
           b.t * (internalReflectance_[b.hi] - internalReflectance_[b.lo]);
}

}  // namespace strahl
