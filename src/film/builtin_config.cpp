#include "builtin_config.h"

#include <cmath>

namespace OCIO = OCIO_NAMESPACE;

namespace strahl::detail {
namespace {

constexpr const char* kLinear = "Linear Rec.709";
constexpr const char* kSrgb = "sRGB Encoded Rec.709";
constexpr const char* kFilmic = "Filmic sRGB";
constexpr const char* kRaw = "Raw";
constexpr const char* kDisplay = "sRGB";

// IEC 61966-2-1: decoding is ((V + 0.055) / 1.055)^2.4 above a linear toe whose
// break point and slope OCIO derives from gamma and offset so the pieces meet.
constexpr double kSrgbGamma = 2.4;
constexpr double kSrgbOffset = 0.055;

// Filmic tone curve, a logistic function of log exposure:
//     f(x) = 1 / (1 + (pivot / x)^contrast),
// a toe below the pivot and a shoulder above it that approaches display white
// without reaching it. contrast and pivot are solved from two anchors:
constexpr double kMidGrey = 0.18;           // scene-linear 18% grey is shown at
constexpr double kMidGreyDisplay = 0.16;    // display-linear 0.16 (sRGB code 0.437,
                                            // a little under Standard's 0.461)
constexpr double kHighlight = 16.0;         // 6.5 stops over mid grey is shown at
constexpr double kHighlightDisplay = 0.97;  // 0.97 (code 0.987): rolled off, not clipped

// The log2 shaper in front of the LUT spans 12 stops below mid grey to 10 above,
// [0.18 / 4096, 0.18 * 1024] = [4.4e-5, 184]. Below it the curve is under 2e-5
// (code 0.0002, 0 in 8 bits); above it it is within 0.2% of white.
constexpr double kStopsBelow = 12.0;
constexpr double kStopsAbove = 10.0;
// 4096 entries over 22 stops, 186 per stop: linear interpolation between them
// is within 1e-6 of the smooth curve.
constexpr unsigned long kLutSize = 4096;

OCIO::TransformRcPtr srgbEncoding() {
    OCIO::ExponentWithLinearTransformRcPtr encode = OCIO::ExponentWithLinearTransform::Create();
    const double gamma[4] = {kSrgbGamma, kSrgbGamma, kSrgbGamma, 1.0};
    const double offset[4] = {kSrgbOffset, kSrgbOffset, kSrgbOffset, 0.0};
    encode->setGamma(gamma);
    encode->setOffset(offset);
    // The forward direction decodes (code value to linear); encoding is its inverse.
    encode->setDirection(OCIO::TRANSFORM_DIR_INVERSE);
    return encode;
}

class FilmicCurve {
  public:
    FilmicCurve() {
        // With A = 1/m - 1 at mid grey and B = 1/h - 1 at the highlight anchor,
        // (pivot/G)^c = A and (pivot/H)^c = B, so (H/G)^c = A/B.
        const double a = 1.0 / kMidGreyDisplay - 1.0;
        const double b = 1.0 / kHighlightDisplay - 1.0;
        contrast_ = std::log(a / b) / std::log(kHighlight / kMidGrey);
        pivot_ = kMidGrey * std::pow(a, 1.0 / contrast_);
        // Rescaled so that the shaper's lowest input, and so scene black, maps
        // to exactly 0; the anchors move by less than 1e-4.
        floor_ = logistic(shaperMin());
    }

    static double shaperMinLog2() { return std::log2(kMidGrey) - kStopsBelow; }
    static double shaperMaxLog2() { return std::log2(kMidGrey) + kStopsAbove; }
    static double shaperMin() { return std::exp2(shaperMinLog2()); }

    double operator()(double x) const { return (logistic(x) - floor_) / (1.0 - floor_); }

  private:
    double logistic(double x) const { return 1.0 / (1.0 + std::pow(pivot_ / x, contrast_)); }

    double contrast_ = 1.0;
    double pivot_ = 1.0;
    double floor_ = 0.0;
};

// Scene-linear to Filmic sRGB code values: log2 shaper onto [0, 1], the tone
// curve sampled uniformly in that log domain, then the sRGB encoding.
OCIO::TransformRcPtr filmicEncoding() {
    OCIO::AllocationTransformRcPtr shaper = OCIO::AllocationTransform::Create();
    shaper->setAllocation(OCIO::ALLOCATION_LG2);
    const float range[2] = {static_cast<float>(FilmicCurve::shaperMinLog2()),
                            static_cast<float>(FilmicCurve::shaperMaxLog2())};
    shaper->setVars(2, range);

    const FilmicCurve curve;
    OCIO::Lut1DTransformRcPtr lut = OCIO::Lut1DTransform::Create(kLutSize, false);
    lut->setInterpolation(OCIO::INTERP_LINEAR);
    const double lo = FilmicCurve::shaperMinLog2();
    const double hi = FilmicCurve::shaperMaxLog2();
    for (unsigned long i = 0; i < kLutSize; ++i) {
        const double t = static_cast<double>(i) / static_cast<double>(kLutSize - 1);
        const float v = static_cast<float>(curve(std::exp2(lo + t * (hi - lo))));
        lut->setValue(i, v, v, v);
    }

    OCIO::GroupTransformRcPtr group = OCIO::GroupTransform::Create();
    group->appendTransform(shaper);
    group->appendTransform(lut);
    group->appendTransform(srgbEncoding());
    return group;
}

OCIO::ColorSpaceRcPtr colorSpace(const char* name, const char* family, const char* encoding,
                                 const char* description) {
    OCIO::ColorSpaceRcPtr space = OCIO::ColorSpace::Create();
    space->setName(name);
    space->setFamily(family);
    space->setEncoding(encoding);
    space->setDescription(description);
    return space;
}

OCIO::ConstConfigRcPtr buildConfig() {
    OCIO::ConfigRcPtr config = OCIO::Config::Create();
    config->setName("strahl-builtin");
    config->setDescription(
        "strahl's built-in config: linear Rec.709 rendering space, sRGB display");

    config->addColorSpace(colorSpace(kLinear, "Linear", "scene-linear",
                                     "Scene-linear Rec.709 primaries, D65 white: strahl's "
                                     "rendering space and the reference space"));

    OCIO::ColorSpaceRcPtr srgb =
        colorSpace(kSrgb, "Display", "sdr-video", "Rec.709 primaries, piecewise sRGB encoding");
    srgb->setTransform(srgbEncoding(), OCIO::COLORSPACE_DIR_FROM_REFERENCE);
    config->addColorSpace(srgb);

    OCIO::ColorSpaceRcPtr filmic =
        colorSpace(kFilmic, "Display", "sdr-video",
                   "Soft-shoulder tone curve (scene-linear 16 stays below white), sRGB encoded");
    filmic->setTransform(filmicEncoding(), OCIO::COLORSPACE_DIR_FROM_REFERENCE);
    config->addColorSpace(filmic);

    OCIO::ColorSpaceRcPtr raw = colorSpace(kRaw, "Utility", "data", "Values passed unchanged");
    raw->setIsData(true);
    config->addColorSpace(raw);

    for (const char* role :
         {OCIO::ROLE_REFERENCE, OCIO::ROLE_SCENE_LINEAR, OCIO::ROLE_DEFAULT, OCIO::ROLE_RENDERING})
        config->setRole(role, kLinear);
    config->setRole(OCIO::ROLE_DATA, kRaw);
    config->setRole(OCIO::ROLE_COLOR_PICKING, kSrgb);

    config->addDisplayView(kDisplay, "Standard", kSrgb, "");
    config->addDisplayView(kDisplay, "Filmic", kFilmic, "");
    config->addDisplayView(kDisplay, "Raw", kRaw, "");
    config->setActiveDisplays(kDisplay);
    config->setActiveViews("Standard, Filmic, Raw");  // the first is the default view

    config->validate();
    return config;
}

}  // namespace

OCIO::ConstConfigRcPtr builtinColorConfig() {
    static const OCIO::ConstConfigRcPtr config = buildConfig();
    return config;
}

}  // namespace strahl::detail
