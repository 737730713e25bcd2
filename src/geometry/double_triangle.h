#pragma once
// Internal to the geometry module: the ray–triangle test of the reference
// intersectors that work in double (flat curve pieces, refined subdivision
// surfaces).

#include <cmath>

#include <glm/glm.hpp>

#include "strahl/core/point3.h"

namespace strahl::geometry_detail {

// Möller–Trumbore for either facing: on a hit, t along o + t·d and the
// weights (b1, b2) of v1 and v2. A degenerate or NaN determinant misses.
inline bool rayTriangle(const DVec3& o, const DVec3& d, const DVec3& v0, const DVec3& v1, const DVec3& v2, double& t,
                        double& b1, double& b2) {
    const DVec3 e1 = v1 - v0, e2 = v2 - v0;
    const DVec3 pv = glm::cross(d, e2);
    const double det = glm::dot(e1, pv);
    if (!(std::abs(det) > 0.0)) return false;
    const DVec3 tv = o - v0;
    b1 = glm::dot(tv, pv) / det;
    if (b1 < 0.0 || b1 > 1.0) return false;
    const DVec3 qv = glm::cross(tv, e1);
    b2 = glm::dot(d, qv) / det;
    if (b2 < 0.0 || b1 + b2 > 1.0) return false;
    t = glm::dot(e2, qv) / det;
    return true;
}

}  // namespace strahl::geometry_detail
