#pragma once
// Internal to the scene module: a spectrum given as samples (wavelength in nm,
// value), linear between them and zero outside them, reduced to the linear
// sRGB (Rec. 709 primaries, D65 white) that strahl renders in, the way
// Mitsuba 3's RGB variants read a <spectrum> (docs/mitsuba.md):
//
//   XYZ = Δ Σ_i x̄ȳz̄(λ_i) · s(λ_i) · w(λ_i) / N,   rgb = M · XYZ
//
// over 1000 wavelengths λ_i evenly spaced on [360, 830] nm, Δ = 470/1000 nm,
// with the CIE 1931 2° matching functions x̄ȳz̄ (linear between the CIE's 5 nm
// samples), N = the ȳ integral by the same rule (so a constant spectrum 1
// has luminance Y = 1), M the XYZ → linear Rec. 709 matrix, and w = 1 for
// emission or, for a reflectance, the D65 illuminant scaled to luminance 1:
// a constant reflectance ρ then becomes the grey (ρ, ρ, ρ) up to the
// tables' rounding (w makes D65 the white of a reflectance, as in sRGB).

#include <vector>

#include <glm/glm.hpp>

namespace strahl::scene_detail {

enum class SpectrumUse { Reflectance, Emission };

// wavelengths strictly increasing, at least two, as many as values (the
// caller checks and says where).
glm::dvec3 spectrumToLinearSrgb(const std::vector<double>& wavelengths,
                                const std::vector<double>& values, SpectrumUse use);

// The linear sRGB of XYZ = (1, 1, 1): what Mitsuba's RGB variants make of a
// constant spectrum 1 that an emitter gives (not grey: sRGB's white is D65,
// not the equal-energy white).
glm::dvec3 equalEnergyWhiteInLinearSrgb();

// The linear sRGB of the light with CIE 1931 chromaticity (x, y) and
// luminance Y = 1: XYZ = (x / y, 1, (1 − x − y) / y). An emission spectrum
// enters a render in RGB only through its XYZ, so a named illuminant is
// exactly its chromaticity (which the CIE tabulates) at a luminance.
glm::dvec3 chromaticityToLinearSrgb(double x, double y);

}  // namespace strahl::scene_detail
