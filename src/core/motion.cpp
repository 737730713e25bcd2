// Keyframed motion (motion.h): the segment arithmetic follows Embree's
// getTimeSegment, so both split frame time alike.

#include "strahl/core/motion.h"

#include <algorithm>
#include <cmath>

#include "strahl/core/transform.h"

namespace strahl {

Mat4 keyframeAt(std::span<const Mat4> keys, float time) {
    if (keys.size() == 1) return keys[0];
    const float segments = float(keys.size() - 1);
    const float scaled = std::clamp(time, 0.0f, 1.0f) * segments;
    const float k = std::clamp(std::floor(scaled), 0.0f, segments - 1.0f);
    const float f = scaled - k;
    const size_t i = static_cast<size_t>(k);
    return (1.0f - f) * keys[i] + f * keys[i + 1];
}

Bounds3 keyframeBounds(std::span<const Mat4> keys, const Bounds3& bounds) {
    Bounds3 out;
    for (const Mat4& m : keys) out.expand(transformBounds(m, bounds));
    return out;
}

}  // namespace strahl
