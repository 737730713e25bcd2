// Mitsuba 3's named materials.
//
// Indices of refraction: the table of Mitsuba's dielectric plugins (its
// documentation, "IOR values"), standard values at 589 nm.
//
// Conductors: Mitsuba's RGB variants read the measured spectra eta(lambda),
// k(lambda) of its data/ior/<name>.{eta,k}.spd files (the same Palik / Luxpop
// data as Mitsuba 0.6) and reduce each to linear sRGB without weighting by an
// illuminant: the values times 1 / 106.75 (the CIE Y integral of a constant 1)
// integrated against the CIE 1931 curves at 1000 wavelengths over 360-830 nm
// (wavelengths outside the data skipped), then XYZ -> Rec. 709, negatives
// clamped to 0. The table below holds the results of that conversion, computed
// once from the data files with the CIE tables of Debian's colord-data.
// Materials whose data ends before 830 nm (AlSb, d-C, MgO) come out with
// channels near 0, as they do in Mitsuba. Mitsuba also names AlAs, HgTe, K,
// Li, Se, Se-e, SnTe, Te, Te-e and ThF4; their data was not at hand, so they
// are refused (docs/mitsuba.md).

#include "mitsuba_named_materials.h"

#include <algorithm>
#include <array>
#include <cctype>

namespace strahl::scene_detail::mitsuba {

namespace {

struct NamedIor {
    std::string_view name;
    double ior;
};

constexpr std::array<NamedIor, 23> kIors = {{
    {"vacuum", 1.0},
    {"helium", 1.000036},
    {"hydrogen", 1.000132},
    {"air", 1.000277},
    {"carbon dioxide", 1.00045},
    {"water", 1.3330},
    {"acetone", 1.36},
    {"ethanol", 1.361},
    {"carbon tetrachloride", 1.461},
    {"glycerol", 1.4729},
    {"benzene", 1.501},
    {"silicone oil", 1.52045},
    {"bromine", 1.661},
    {"water ice", 1.31},
    {"fused quartz", 1.458},
    {"pyrex", 1.470},
    {"acrylic glass", 1.49},
    {"polypropylene", 1.49},
    {"bk7", 1.5046},
    {"sodium chloride", 1.544},
    {"amber", 1.55},
    {"pet", 1.5750},
    {"diamond", 2.419},
}};

const std::array<NamedConductor, 31> kConductors = {{
    {"none", {0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}},
    {"a-C", {2.94405, 2.22714, 1.96816}, {0.887465, 0.799298, 0.81529}},
    {"Ag", {0.155276, 0.116728, 0.138388}, {4.82835, 3.12222, 2.1469}},
    {"Al", {1.6575, 0.880405, 0.521244}, {9.22381, 6.2695, 4.837}},
    {"AlSb", {0.0, 4.13937, 4.66925}, {0.0, 0.0940091, 1.30057}},
    {"Au", {0.143036, 0.375307, 1.44205}, {3.983, 2.38556, 1.60336}},
    {"Be", {4.18501, 3.18503, 2.78406}, {3.83547, 3.01012, 2.86899}},
    {"Cr", {4.36967, 2.91651, 1.6549}, {5.20655, 4.23131, 3.7547}},
    {"CsI", {2.1449, 1.70232, 1.66243}, {0.0, 0.0, 0.0}},
    {"Cu", {0.201006, 0.923749, 1.10222}, {3.91326, 2.45305, 2.14209}},
    {"Cu2O", {3.55177, 2.94987, 2.75188}, {0.114207, 0.193897, 0.606134}},
    {"CuO", {3.24754, 2.44781, 2.21022}, {0.52109, 0.570031, 0.722179}},
    {"d-C", {2.70872, 2.31883, 2.2289}, {0.0, 0.0, 0.0}},
    {"Hg", {2.39894, 1.44003, 0.90957}, {6.32759, 4.37192, 3.42176}},
    {"Ir", {3.0863, 2.08219, 1.61791}, {5.59215, 4.06709, 3.26731}},
    {"MgO", {2.08958, 1.65072, 1.59488}, {0.0, 0.0, 0.0}},
    {"Mo", {4.48397, 3.52513, 2.77631}, {4.11144, 3.42083, 3.15061}},
    {"Na_palik", {0.0602694, 0.0561409, 0.0619884}, {3.17927, 2.11249, 1.57904}},
    {"Nb", {3.42007, 2.79009, 2.39563}, {3.44139, 2.73767, 2.57975}},
    {"Ni_palik", {2.3673, 1.66337, 1.46708}, {4.49881, 3.05015, 2.34544}},
    {"Rh", {2.58579, 1.86022, 1.55426}, {6.78226, 4.70299, 3.97607}},
    {"SiC", {3.17234, 2.52597, 2.47937}, {0.0, 0.0, 1.01925e-05}},
    {"Ta", {2.06272, 2.39294, 2.62793}, {2.40836, 1.74149, 1.94703}},
    {"TiC", {3.70053, 2.83742, 2.58229}, {3.26564, 2.35159, 2.17279}},
    {"TiN", {1.64845, 1.15052, 1.37982}, {3.36833, 1.9435, 1.10207}},
    {"TiO2-e", {3.10656, 2.51317, 2.58244}, {2.97516e-05, 0.0, 0.000182698}},
    {"TiO2", {3.45661, 2.80174, 2.90517}, {0.000105265, 0.0, 0.000652886}},
    {"VC", {3.65757, 2.75274, 2.53267}, {3.0683, 2.19869, 1.96319}},
    {"V_palik", {4.27758, 3.51295, 2.76107}, {3.4913, 2.88945, 3.11152}},
    {"VN", {2.8656, 2.11919, 1.94009}, {3.03224, 2.05612, 1.61631}},
    {"W", {4.37082, 3.30025, 2.99841}, {3.50064, 2.60487, 2.27323}},
}};

std::string lower(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return out;
}

}  // namespace

std::optional<double> namedIor(std::string_view name) {
    const std::string key = lower(name);
    for (const NamedIor& n : kIors)
        if (n.name == key) return n.ior;
    return std::nullopt;
}

std::string namedIorList() {
    std::string list;
    for (const NamedIor& n : kIors) list += (list.empty() ? "" : ", ") + std::string(n.name);
    return list;
}

std::optional<NamedConductor> namedConductor(std::string_view name) {
    for (const NamedConductor& c : kConductors)
        if (c.name == name) return c;
    return std::nullopt;
}

std::span<const NamedConductor> namedConductors() {
    return kConductors;
}

}  // namespace strahl::scene_detail::mitsuba
