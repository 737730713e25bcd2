#pragma once
// The rough dielectric coat of a plastic: the fraction of light a rough
// interface lets through at each incidence, and the cosine-weighted average of
// what it reflects back from inside. Both are integrals over the microfacets
// (single scattering, masked as the distribution masks), computed once per
// material and tabulated; the derivation is in docs/materials.md, "Plastic".

#include <span>
#include <vector>

#include "strahl/bsdf/microfacet.h"

namespace strahl {

// Directional albedos of a rough dielectric interface with relative index eta
// (n on the -z side / n on the +z side) for light arriving at cos(theta) from
// the +z side: R = integral of the reflection lobe f cos, T = that of the
// transmission lobe without the 1 / eta^2 radiance compression. R + T < 1 by
// the energy the masking loses. Evaluated by Gauss-Legendre quadrature with
// nodes x nodes points over the distribution's normal sampling.
struct InterfaceAlbedo {
    float reflectance = 0.0f, transmittance = 0.0f;
};
InterfaceAlbedo roughInterfaceAlbedo(const MicrofacetDistribution& dist, float cosTheta,
                                     float eta, int nodes);

class RoughCoat {
public:
    // Tables at the given alphas (increasing; one for a constant roughness,
    // which is then exact, several for a textured one, interpolated linearly
    // between them). A smooth alpha (below kSmoothAlpha) takes the smooth
    // interface's values, 1 - F and F's internal average by the same rule.
    RoughCoat(MicrofacetModel model, float eta, std::span<const float> alphas);

    float eta() const { return eta_; }
    // The fraction of light arriving at cos(theta) from outside that enters the coat.
    float transmittance(float alpha, float cosTheta) const;
    // What the coat sends back down of the diffuse light that meets it from
    // below, 2 integral_0^1 R_inside(mu) mu dmu, by Mitsuba's rule (a plain
    // mean over the table's cosines, ~1.5 % below the integral; rough_coat.cpp).
    float internalReflectance(float alpha) const;

    // Resolution of the transmittance table in cos(theta), evenly spaced on [0, 1].
    static constexpr int kCosines = 64;

private:
    struct Bracket {
        int lo, hi;
        float t;
    };
    Bracket bracket(float alpha) const;

    float eta_;
    std::vector<float> alphas_;
    std::vector<float> transmittance_;  // alphas_.size() rows of kCosines
    std::vector<float> internalReflectance_;
};

}  // namespace strahl
