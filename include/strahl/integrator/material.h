#pragma once
// Surface materials. For now: Lambertian reflection plus optional emission.

#include <string>

#include "strahl/core/math.h"

namespace strahl {

struct Material {
    std::string name;
    Color diffuse{0.8f};    // reflectance in [0, 1] per channel; BRDF = diffuse / pi
    Color emission{0.0f};   // emitted radiance, W/(m^2 sr), seen directly by the camera
};

}  // namespace strahl
