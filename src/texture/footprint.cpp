// World-space footprints into uv units (see footprint.h).

#include "strahl/texture/footprint.h"

#include <cmath>

namespace strahl {

float uvFootprint(float worldWidth, const Vec3& dpdu, const Vec3& dpdv) {
    if (!(worldWidth > 0.0f) || !isFinite(dpdu) || !isFinite(dpdv)) return 0.0f;
    // World area of one uv unit square.
    const float area = glm::length(glm::cross(dpdu, dpdv));
    if (!(area > 0.0f) || !std::isfinite(area)) return 0.0f;
    return worldWidth / std::sqrt(area);
}

}  // namespace strahl
