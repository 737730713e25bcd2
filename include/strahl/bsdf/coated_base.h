#pragma once
// What a coated conductor (bsdf_models.h, CoatedConductorModel) computes once
// per material: the metal's index relative to the coat, and what follows the
// light that does not leave the coat after one bounce off a rough metal (total
// internal reflection beyond the critical angle, the coat's reflection from
// inside, masking), so that the layered BSDF keeps the energy a random walk
// through the layers would. Derivation: docs/materials.md, "Coated conductor".

#include <array>
#include <memory>
#include <mutex>

#include "strahl/bsdf/microfacet.h"
#include "strahl/core/math.h"

namespace strahl {

// A conductor under a dielectric coat, as a material describes it.
struct CoatedLayers {
    Color eta{0.0f}, k{1.0f};  // the metal's complex index in vacuum
    float coatEta = 1.5f;      // the coat's index (outside: 1); at least 1
    float thickness = 0.0f;    // optical thickness of the layer between them (extinction 1)
    MicrofacetModel microfacets;  // of the coat and the metal
};

class CoatedBase {
public:
    // Validates (strahl::Error for a negative or NaN colour, a coat index
    // below 1 or a negative thickness). The tables are integrated row by row
    // (one roughness, about 14 ms) the first time a row is asked for, and
    // shared by every coated conductor of the same coat index and microfacet
    // model; thread-safe.
    explicit CoatedBase(const CoatedLayers& layers);
    CoatedBase(const CoatedBase&) = delete;
    CoatedBase& operator=(const CoatedBase&) = delete;

    const Color& eta() const { return eta_; }  // the metal's index divided by the coat's
    const Color& k() const { return k_; }
    float coatEta() const { return coatEta_; }
    float thickness() const { return thickness_; }
    const MicrofacetModel& microfacets() const { return microfacets_; }

    // Beer-Lambert through the layer, crossed at cos theta' (pbrt-v4's Tr).
    float attenuation(float cosInside) const;
    // Of the light a white metal (|r| = 1) of GGX alpha receives through the
    // coat from the direction at cos theta outside, the fraction that does
    // not leave through the coat after that one bounce.
    float trapped(float alpha, float cosOutside) const;
    // Of that light, the fraction that leaves in the end, per channel: the
    // metal's first bounce, then rounds of the layer (attenuation), the
    // metal again (its cosine-weighted mean reflectance) and a chance to leave.
    Color trappedEscape(float alpha) const;
    // The integral over outside directions w of T(w) trapped(w) a(w') cos:
    // what normalises the trapped light's exit lobe.
    float trappedNorm(float alpha) const;

    // The tables' resolution: outside cosines evenly spaced on [0, 1], perceptual
    // roughness r = sqrt(alpha) at 0, 1/16, ..., 1 (linear between; at
    // 1/8 steps a white metal of alpha 0.05 under a coat of 2.5 gained 1.4 %).
    static constexpr int kCosines = 48;
    static constexpr int kRoughnesses = 17;

    struct EscapeTable;  // coated_base.cpp

private:
    struct Bracket {
        int lo, hi;
        float t;
    };
    static Bracket bracket(float alpha);
    // This material's quantities at the table's roughness j.
    struct MaterialRow {
        std::once_flag once;
        float norm = 0.0f;
        Color escape{0.0f};
    };
    const MaterialRow& materialRow(int j) const;
    float trappedInRow(int j, float cosOutside) const;

    Color eta_, k_;
    float coatEta_, thickness_;
    MicrofacetModel microfacets_;
    std::shared_ptr<const EscapeTable> table_;
    Color metalMean_{0.0f};  // the metal's cosine-weighted mean reflectance inside
    float layerMean_ = 1.0f;  // the layer's cosine-weighted mean round-trip transmittance
    mutable std::array<MaterialRow, kRoughnesses> rows_;
};

}  // namespace strahl
