#pragma once
// Axis-aligned bounding box; an empty box has min > max.

#include "strahl/core/math.h"

namespace strahl {

struct Bounds3 {
    Vec3 min{kInfinity};
    Vec3 max{-kInfinity};

    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    void expand(const Vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void expand(const Bounds3& b) {
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }
    Vec3 diagonal() const { return empty() ? Vec3(0.0f) : max - min; }
    Vec3 center() const { return 0.5f * (min + max); }
};

}  // namespace strahl
