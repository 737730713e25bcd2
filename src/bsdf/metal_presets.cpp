// Complex refractive indices of common metals at 650 / 550 / 450 nm (R, G, B),
// linearly interpolated in wavelength from the tabulated measurements in the
// refractiveindex.info database (public domain):
//   gold, silver, copper      Johnson & Christy, Phys. Rev. B 6, 4370 (1972)
//   chromium, iron, titanium,
//   nickel                    Johnson & Christy, Phys. Rev. B 9, 5056 (1974)
//   aluminium                 Rakic, Appl. Opt. 34, 4755 (1995)
//   platinum                  Rakic et al., Appl. Opt. 37, 5271 (1998), Lorentz-Drude fit
// Single-wavelength samples, not CIE-weighted averages: the colours are close to
// (but not identical with) those of a spectral renderer. docs/materials.md lists
// the resulting normal-incidence reflectances.

#include <algorithm>
#include <array>
#include <cctype>

#include "strahl/bsdf/bsdf.h"

namespace strahl {

namespace {

const std::array<MetalPreset, 9> kPresets = {{
    {"gold", Color(0.1556f, 0.4241f, 1.3831f), Color(3.6024f, 2.4721f, 1.9155f)},
    {"silver", Color(0.0522f, 0.0596f, 0.0400f), Color(4.4094f, 3.5974f, 2.6484f)},
    {"copper", Color(0.2378f, 1.0066f, 1.2404f), Color(3.6264f, 2.5823f, 2.3929f)},
    {"aluminium", Color(1.5580f, 1.0152f, 0.6332f), Color(7.7124f, 6.6273f, 5.4544f)},
    {"chromium", Color(3.1071f, 3.1812f, 2.3230f), Color(3.3314f, 3.3291f, 3.1350f)},
    {"iron", Color(2.9114f, 2.9497f, 2.5845f), Color(3.0893f, 2.9318f, 2.7670f)},
    {"titanium", Color(2.7407f, 2.5418f, 2.2670f), Color(3.8143f, 3.4345f, 3.0385f)},
    {"nickel", Color(1.9900f, 1.9212f, 1.7290f), Color(4.2086f, 3.6158f, 2.9435f)},
    {"platinum", Color(2.3699f, 2.0908f, 1.8511f), Color(4.2536f, 3.7036f, 3.1398f)},
}};

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

}  // namespace

std::span<const MetalPreset> metalPresets() {
    return kPresets;
}

std::optional<MetalPreset> findMetalPreset(std::string_view name) {
    // The American spelling is accepted as well.
    if (equalsIgnoreCase(name, "aluminum")) name = "aluminium";
    for (const MetalPreset& preset : kPresets) {
        if (equalsIgnoreCase(preset.name, name)) return preset;
    }
    return std::nullopt;
}

}  // namespace strahl
