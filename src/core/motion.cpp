// Keyframed motion (motion.h): the segment arithmetic follows Embree's
// getTimeSegment, so both split frame time alike.

#include "strahl/core/motion.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "strahl/core/transform.h"

namespace strahl {

KeyframeSegment keyframeSegment(size_t count, float time) {
    const float segments = float(count - 1);
    const float scaled = std::clamp(time, 0.0f, 1.0f) * segments;
    const float k = std::clamp(std::floor(scaled), 0.0f, segments - 1.0f);
    return {static_cast<size_t>(k), scaled - k};
}

Mat4 keyframeAt(std::span<const Mat4> keys, float time) {
    if (keys.size() == 1) return keys[0];
    const KeyframeSegment s = keyframeSegment(keys.size(), time);
    return (1.0f - s.fraction) * keys[s.index] + s.fraction * keys[s.index + 1];
}

namespace {

struct Decomposed {
    glm::dvec3 translation;
    glm::dquat rotation;
    glm::dmat3 stretch;
};

// M = T R S with R the polar factor of M's linear part, found by averaging a
// matrix with its inverse transpose until it stops changing (Higham's
// iteration, as pbrt-v4 does). False for a mirror or a failed iteration.
bool decompose(const glm::dmat4& m, Decomposed& out) {
    out.translation = glm::dvec3(m[3]);
    const glm::dmat3 linear(m);
    glm::dmat3 r = linear;
    for (int i = 0; i < 100; ++i) {
        const glm::dmat3 next = 0.5 * (r + glm::inverse(glm::transpose(r)));
        double change = 0.0;
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) change = std::max(change, std::abs(next[c][k] - r[c][k]));
        r = next;
        if (change < 1e-13) break;
    }
    const double det = glm::determinant(r);
    if (!(std::abs(det - 1.0) < 1e-6)) return false;  // a mirror (-1) or no convergence
    out.rotation = glm::quat_cast(r);
    out.stretch = glm::transpose(r) * linear;
    return true;
}

glm::dmat4 compose(const Decomposed& d) {
    glm::dmat4 m(glm::mat3_cast(d.rotation) * d.stretch);
    m[3] = glm::dvec4(d.translation, 1.0);
    return m;
}

}  // namespace

std::vector<Mat4> rotationAwareKeyframes(const glm::dmat4& start, const glm::dmat4& end, double maxStepRadians) {
    Decomposed a, b;
    if (!decompose(start, a) || !decompose(end, b)) return {Mat4(start), Mat4(end)};
    // The angle between the two rotations, the short way round.
    const double cosHalf = std::min(1.0, std::abs(glm::dot(a.rotation, b.rotation)));
    const double angle = 2.0 * std::acos(cosHalf);
    const auto steps = static_cast<size_t>(std::ceil(angle / maxStepRadians));
    const size_t count = std::clamp<size_t>(steps + 1, 2, kMaxKeyframes);
    std::vector<Mat4> keys;
    keys.reserve(count);
    for (size_t k = 0; k < count; ++k) {
        const double f = double(k) / double(count - 1);
        if (k == 0) {
            keys.push_back(Mat4(start));
        } else if (k + 1 == count) {
            keys.push_back(Mat4(end));
        } else {
            const Decomposed d{glm::mix(a.translation, b.translation, f), glm::slerp(a.rotation, b.rotation, f),
                               (1.0 - f) * a.stretch + f * b.stretch};
            keys.push_back(Mat4(compose(d)));
        }
    }
    return keys;
}

Bounds3 keyframeBounds(std::span<const Mat4> keys, const Bounds3& bounds) {
    Bounds3 out;
    for (const Mat4& m : keys) out.expand(transformBounds(m, bounds));
    return out;
}

}  // namespace strahl
