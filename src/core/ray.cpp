#include "strahl/core/ray.h"

#include <cmath>

namespace strahl {

Vec3 offsetRayOrigin(const Vec3& p, const Vec3& pError, const Vec3& n, const Vec3& w) {
    const Vec3 nUnit = glm::normalize(n);
    // Distance along n that leaves the error box: the box's support in direction n.
    const float d = glm::dot(glm::abs(nUnit), pError);
    Vec3 offset = d * nUnit;
    if (glm::dot(w, nUnit) < 0.0f) offset = -offset;
    Vec3 po = p + offset;
    // The addition itself rounds; step one ulp further away so the rounded origin
    // is guaranteed to lie on the chosen side of the surface.
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0.0f)
            po[i] = std::nextafter(po[i], kInfinity);
        else if (offset[i] < 0.0f)
            po[i] = std::nextafter(po[i], -kInfinity);
    }
    return po;
}

Ray spawnRay(const Vec3& p, const Vec3& pError, const Vec3& n, const Vec3& dir) {
    Ray r;
    r.origin = offsetRayOrigin(p, pError, n, dir);
    r.dir = dir;
    r.tnear = 0.0f;
    r.tfar = kInfinity;
    return r;
}

Ray spawnRayTo(const Vec3& p, const Vec3& pError, const Vec3& n, const Vec3& target) {
    Ray r;
    r.origin = offsetRayOrigin(p, pError, n, target - p);
    r.dir = target - r.origin;  // unnormalised: t = 1 is the target itself
    r.tnear = 0.0f;
    // Stop a relative 1e-4 of the segment short of the target so a light sitting
    // on a surface is not occluded by that surface (pbrt's ShadowEpsilon).
    r.tfar = 1.0f - 1e-4f;
    return r;
}

}  // namespace strahl
