#include "spectrum_to_rgb.h"

#include <algorithm>
#include <array>

namespace strahl::scene_detail {

namespace {

#include "strahl_generated/cie_tables.inc"

// XYZ → linear Rec. 709 (sRGB primaries, D65 white), the matrix Mitsuba 3
// uses (IEC 61966-2-1 to 6 digits).
constexpr double kXyzToRgb[3][3] = {{3.240479, -1.537150, -0.498535},
                                    {-0.969256, 1.875991, 0.041556},
                                    {0.055648, -0.204043, 1.057311}};

glm::dvec3 xyzToRgb(const glm::dvec3& xyz) {
    glm::dvec3 rgb;
    for (int r = 0; r < 3; ++r)
        rgb[r] = kXyzToRgb[r][0] * xyz.x + kXyzToRgb[r][1] * xyz.y + kXyzToRgb[r][2] * xyz.z;
    return rgb;
}

// A CIE table at λ, linear between its 5 nm samples, 0 outside [360, 830].
double tableAt(const double (&table)[kCieSamples], double nm) {
    if (nm < kCieFirstNm || nm > kCieLastNm) return 0.0;
    const double t = (nm - kCieFirstNm) * (kCieSamples - 1) / (kCieLastNm - kCieFirstNm);
    const int i = std::min(static_cast<int>(t), kCieSamples - 2);
    const double f = t - i;
    return (1.0 - f) * table[i] + f * table[i + 1];
}

// The 1000 wavelengths of the integration rule: Mitsuba's, end points
// included, each standing for Δ = 470/1000 nm.
constexpr int kSteps = 1000;
constexpr double kStepNm = (kCieLastNm - kCieFirstNm) / kSteps;
double stepWavelength(int i) {
    return kCieFirstNm + (kCieLastNm - kCieFirstNm) * i / double(kSteps - 1);
}

// Σ s(λ_i) · ȳ(λ_i) · Δ for the rule above, s given as a function.
template <typename Spectrum>
double luminanceIntegral(const Spectrum& s) {
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i) sum += s(stepWavelength(i)) * tableAt(kCieY, stepWavelength(i));
    return sum * kStepNm;
}

// N: the ȳ integral (≈ 106.75), and the D65 integral against ȳ, so that
// both a constant 1 and D65 / (that integral / N) have luminance 1.
const double kYNormalisation = luminanceIntegral([](double) { return 1.0; });
const double kD65Luminance = luminanceIntegral([](double nm) { return tableAt(kCieD65, nm); });

double d65Weight(double nm) { return tableAt(kCieD65, nm) * kYNormalisation / kD65Luminance; }

}  // namespace

glm::dvec3 spectrumToLinearSrgb(const std::vector<double>& wavelengths,
                                const std::vector<double>& values, SpectrumUse use) {
    glm::dvec3 xyz(0.0);
    for (int i = 0; i < kSteps; ++i) {
        const double nm = stepWavelength(i);
        if (nm < wavelengths.front() || nm > wavelengths.back()) continue;
        // The last sample at or below nm (the one before the last at the end).
        const size_t k = std::min<size_t>(
            std::upper_bound(wavelengths.begin(), wavelengths.end(), nm) - wavelengths.begin() - 1,
            wavelengths.size() - 2);
        const double f = (nm - wavelengths[k]) / (wavelengths[k + 1] - wavelengths[k]);
        double s = (1.0 - f) * values[k] + f * values[k + 1];
        if (use == SpectrumUse::Reflectance) s *= d65Weight(nm);
        xyz += s * glm::dvec3(tableAt(kCieX, nm), tableAt(kCieY, nm), tableAt(kCieZ, nm));
    }
    return xyzToRgb(xyz * kStepNm / kYNormalisation);
}

glm::dvec3 equalEnergyWhiteInLinearSrgb() { return xyzToRgb(glm::dvec3(1.0)); }

glm::dvec3 chromaticityToLinearSrgb(double x, double y) {
    return xyzToRgb(glm::dvec3(x / y, 1.0, (1.0 - x - y) / y));
}

}  // namespace strahl::scene_detail
