#pragma once
// Delta lights: point and directional. Both are sampled deterministically (one
// direction, no randomness), so direct lighting from them is noise-free.

#include "strahl/core/math.h"

namespace strahl {

struct Light {
    enum class Type { Point, Directional };
    Type type = Type::Point;
    Vec3 position{0.0f};                // point lights
    Vec3 direction{0.0f, -1.0f, 0.0f};  // directional: unit direction the light travels
    Color intensity{1.0f};              // point: radiant intensity I, W/sr
    Color irradiance{1.0f};             // directional: irradiance E on a facing surface, W/m^2
};

// Incident light at a point from one light.
struct LightSample {
    Vec3 wi{0.0f};      // unit direction from the point towards the light
    Color Li{0.0f};     // irradiance on a surface facing wi (W/m^2): I/r^2 or E
    bool atInfinity = false;
    Vec3 position{0.0f};  // the light's position (point lights)
};

LightSample sampleLight(const Light& light, const Vec3& p);

}  // namespace strahl
