#pragma once
// The sRGB EOTF (IEC 61966-2-1): an encoded code value in [0, 1] to linear.
// One definition for every reader of 8- and 16-bit colour (textures, PLY
// vertex colours, the pbrt importer's image means), in float and in double.

#include <cmath>

namespace strahl {

inline float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

inline double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

}  // namespace strahl
