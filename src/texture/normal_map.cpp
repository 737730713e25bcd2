// Tangent-space normal mapping (see normal_map.h).

#include "strahl/texture/normal_map.h"

namespace strahl {

namespace {

// Below this sine of the angle between dpdu and ns, the Gram-Schmidt tangent
// is mostly the rounding error of the cancellation (about 1e-7 absolute): its
// direction would be off by more than 0.1%, so an arbitrary tangent is used.
constexpr float kMinTangentSine = 1e-4f;

}  // namespace

Vec3 applyNormalMap(const Vec3& encoded, const Vec3& ns, const Vec3& dpdu) {
    if (!isFinite(ns) || maxComponent(glm::abs(ns)) == 0.0f) return ns;
    const Vec3 n = unitVector(ns);

    // Tangent: dpdu without its component along n, if there is enough left.
    Vec3 t(0.0f);
    bool haveTangent = false;
    if (isFinite(dpdu) && maxComponent(glm::abs(dpdu)) > 0.0f) {
        const Vec3 d = unitVector(dpdu);
        t = d - n * glm::dot(n, d);
        const float sine = glm::length(t);
        if (sine > kMinTangentSine) {
            t /= sine;
            haveTangent = true;
        }
    }
    if (!haveTangent) {
        Vec3 unused;
        orthonormalBasis(n, t, unused);
    }
    const Vec3 b = glm::cross(n, t);  // +v for a right-handed (non-mirrored) mapping

    const Vec3 m = 2.0f * encoded - 1.0f;
    const Vec3 perturbed = m.x * t + m.y * b + m.z * n;
    if (!isFinite(perturbed) || maxComponent(glm::abs(perturbed)) == 0.0f) return n;
    return unitVector(perturbed);
}

}  // namespace strahl
