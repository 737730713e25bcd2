#pragma once
// Math vocabulary of strahl: GLM types under short names, single precision
// throughout (Embree traces float rays), plus the few helpers every module needs.

#include <glm/glm.hpp>

#include <cmath>
#include <limits>

namespace strahl {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Vec4 = glm::vec4;
using Mat3 = glm::mat3;
using Mat4 = glm::mat4;
using Color = glm::vec3;  // linear Rec.709 RGB

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

inline bool isFinite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline float maxComponent(const Vec3& v) { return glm::max(v.x, glm::max(v.y, v.z)); }

// The direction of a non-zero finite vector, exact also for components whose
// squares over- or underflow (glm::normalize of 1e20 or 1e-30 is not).
inline Vec3 unitVector(const Vec3& v) { return glm::normalize(v / maxComponent(glm::abs(v))); }

// Right-handed orthonormal basis around a unit vector n (Duff et al. 2017,
// "Building an Orthonormal Basis, Revisited": branch-free, no singularity).
inline void orthonormalBasis(const Vec3& n, Vec3& b1, Vec3& b2) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    b1 = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    b2 = Vec3(b, sign + n.y * n.y * a, -n.y);
}

}  // namespace strahl
