// Bump mapping (see bump_map.h for the derivation).

#include "strahl/texture/bump_map.h"

#include <cmath>

namespace strahl {

Vec3 applyBumpMap(const Vec2& slope, const Vec3& ns, const Vec3& dpdu, const Vec3& dpdv) {
    if (!isFinite(dpdu) || !isFinite(dpdv) || !std::isfinite(slope.x) || !std::isfinite(slope.y) || glm::dot(dpdu, dpdu) == 0.0f ||
        glm::dot(dpdv, dpdv) == 0.0f)
        return ns;
    const Vec3 dpds = dpdu, dpdt = -dpdv;
    const Vec3 bumpedS = dpds - ns * glm::dot(ns, dpds) + ns * slope.x;
    const Vec3 bumpedT = dpdt - ns * glm::dot(ns, dpdt) + ns * slope.y;
    Vec3 n = glm::cross(bumpedS, bumpedT);
    const float length = glm::length(n);
    if (!(length > 0.0f) || !std::isfinite(length)) return ns;
    n /= length;
    return glm::dot(n, ns) < 0.0f ? -n : n;
}

}  // namespace strahl
