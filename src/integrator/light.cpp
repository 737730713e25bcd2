#include "strahl/integrator/light.h"

namespace strahl {

LightSample sampleLight(const Light& light, const Vec3& p) {
    LightSample s;
    if (light.type == Light::Type::Directional) {
        s.wi = -light.direction;
        s.Li = light.irradiance;
        s.atInfinity = true;
        return s;
    }
    const Vec3 toLight = light.position - p;
    const float dist2 = glm::dot(toLight, toLight);
    s.position = light.position;
    if (!(dist2 > 0.0f)) return s;  // shading point on the light itself: no defined direction
    s.wi = toLight / std::sqrt(dist2);
    s.Li = light.intensity / dist2;  // inverse-square law: E = I / r^2
    return s;
}

}  // namespace strahl
