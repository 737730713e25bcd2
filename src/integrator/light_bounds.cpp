#include "strahl/integrator/light_bounds.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "strahl/integrator/light.h"

namespace strahl {

namespace {

float safeAcos(float c) {
    return std::acos(std::clamp(c, -1.0f, 1.0f));
}

// The angle between two unit vectors, accurate also near 0 and pi (acos of
// the dot product loses half the digits there).
float angleBetween(const Vec3& a, const Vec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// Widening of merged cones against rounding (radians): the bounds must hold.
constexpr float kConeSlack = 1e-4f;

}  // namespace

float LightBounds::importance(const Vec3& p, const Vec3& n) const {
    const Vec3 toP = p - box.center();
    const float radius = 0.5f * glm::length(box.diagonal());
    const float dist2 = glm::dot(toP, toP);
    // From inside the box's bounding sphere the group may lie in any
    // direction: every angle below is then 0, and the distance the radius.
    float emitted = 1.0f, received = 1.0f;
    if (dist2 > radius * radius) {
        const float dist = std::sqrt(dist2);
        const Vec3 v = toP / dist;  // from the group to p
        // Half the angle the bounding sphere subtends from p: every point of
        // the box is within it of the direction to the centre.
        const float thetaB = std::asin(std::min(radius / dist, 1.0f));
        float cosW = glm::dot(axis, v);
        if (twoSided) cosW = std::abs(cosW);
        // The smallest angle between an emitted direction and one towards p:
        // the axis-to-p angle, less the normals' spread and the box's extent.
        const float thetaPrime = std::max(safeAcos(cosW) - thetaO - thetaB, 0.0f);
        if (thetaPrime >= thetaE) return 0.0f;  // p is outside every emitted direction
        emitted = std::cos(thetaPrime);
        if (n != Vec3(0.0f)) {
            // Either side of the receiver counts (transmission), so the
            // cosine of the line of n; the box's extent brings it closer.
            const float thetaI = safeAcos(std::abs(glm::dot(n, v)));
            received = std::cos(std::max(thetaI - thetaB, 0.0f));
        }
    }
    // The distance to the box's centre, not to its nearest point: only the
    // angular bounds above must hold (they decide which lights can be
    // chosen at all); within them the importance only steers the choice, and
    // the nearest point would make every group around p look alike. With
    // the floor at a tenth of the radius, the many-lamp test scene's variance
    // is 1/9 of power selection's, against 1/3 with the floor at the radius
    // (a bound). The absolute floor keeps a receiver on a point light finite.
    const float d2 = std::max({dist2, 0.01f * radius * radius, 1e-12f});
    return std::max(power * emitted * received / d2, 0.0f);
}

ImportanceBounds::ImportanceBounds(const LightBounds& b)
    : center(b.box.center()),
      radius(0.5f * glm::length(b.box.diagonal())),
      axis(b.axis),
      cosThetaO(std::cos(b.thetaO)),
      sinThetaO(std::sin(b.thetaO)),
      cosThetaE(std::cos(b.thetaE)),
      power(b.power),
      twoSided(b.twoSided) {}

float ImportanceBounds::importance(const Vec3& p, const Vec3& n) const {
    // LightBounds::importance step by step, each angle as its cosine (and
    // sine where a difference needs it); angles in [0, pi], so the sines are
    // the non-negative square roots.
    const Vec3 toP = p - center;
    const float dist2 = glm::dot(toP, toP);
    float emitted = 1.0f, received = 1.0f;
    if (dist2 > radius * radius) {
        const float dist = std::sqrt(dist2);
        const Vec3 v = toP / dist;
        const float sinB = std::min(radius / dist, 1.0f);
        const float cosB = std::sqrt(std::max(0.0f, 1.0f - sinB * sinB));
        float cosW = std::clamp(glm::dot(axis, v), -1.0f, 1.0f);
        if (twoSided) cosW = std::abs(cosW);
        const float sinW = std::sqrt(std::max(0.0f, 1.0f - cosW * cosW));
        // thetaX = max(thetaW - thetaO, 0)
        float cosX = 1.0f, sinX = 0.0f;
        if (cosW < cosThetaO) {
            cosX = cosW * cosThetaO + sinW * sinThetaO;
            sinX = std::max(0.0f, sinW * cosThetaO - cosW * sinThetaO);
        }
        // thetaPrime = max(thetaX - thetaB, 0); none of the group's light
        // reaches p once thetaPrime >= thetaE.
        const float cosPrime = cosX < cosB ? cosX * cosB + sinX * sinB : 1.0f;
        if (cosPrime <= cosThetaE) return 0.0f;
        emitted = cosPrime;
        if (n != Vec3(0.0f)) {
            const float cosI = std::min(std::abs(glm::dot(n, v)), 1.0f);
            const float sinI = std::sqrt(std::max(0.0f, 1.0f - cosI * cosI));
            received = cosI < cosB ? cosI * cosB + sinI * sinB : 1.0f;
        }
    }
    const float d2 = std::max({dist2, 0.01f * radius * radius, 1e-12f});
    return std::max(power * emitted * received / d2, 0.0f);
}

LightBounds unite(const LightBounds& first, const LightBounds& second) {
    if (first.power <= 0.0f) return second;
    if (second.power <= 0.0f) return first;
    LightBounds u;
    u.box = first.box;
    u.box.expand(second.box);
    u.power = first.power + second.power;
    u.twoSided = first.twoSided || second.twoSided;
    u.thetaE = std::max(first.thetaE, second.thetaE);
    // The cone around both cones: a the wider, b the other.
    const LightBounds& a = first.thetaO >= second.thetaO ? first : second;
    const LightBounds& b = first.thetaO >= second.thetaO ? second : first;
    const float cosD = glm::dot(a.axis, b.axis);
    const float thetaD = angleBetween(a.axis, b.axis);
    u.axis = a.axis;
    if (std::min(thetaD + b.thetaO, kPi) <= a.thetaO) {
        u.thetaO = a.thetaO;  // a holds b
        return u;
    }
    const float thetaO = 0.5f * (a.thetaO + thetaD + b.thetaO) + kConeSlack;
    const Vec3 across = b.axis - cosD * a.axis;  // towards b, orthogonal to a's axis
    const float acrossLength = glm::length(across);
    if (thetaO >= kPi || acrossLength < 1e-6f) {
        u.thetaO = kPi;  // every direction (or opposite axes: no rotation plane)
        return u;
    }
    // Turn a's axis towards b's by the angle the cone grew on b's side.
    const float thetaR = thetaO - kConeSlack - a.thetaO;
    u.axis = glm::normalize(std::cos(thetaR) * a.axis + std::sin(thetaR) * (across / acrossLength));
    u.thetaO = thetaO;
    return u;
}

float orientationMeasure(const LightBounds& b) {
    const float thetaW = std::min(b.thetaO + b.thetaE, kPi);
    const float sinO = std::sin(b.thetaO), cosO = std::cos(b.thetaO);
    return 2.0f * kPi * (1.0f - cosO) +
           0.5f * kPi *
               (2.0f * thetaW * sinO - std::cos(b.thetaO - 2.0f * thetaW) - 2.0f * b.thetaO * sinO +
                cosO);
}

std::optional<LightBounds> boundsOf(const Light& light, float power) {
    if (!(power > 0.0f)) return std::nullopt;
    return std::visit(
        [&](const auto& k) -> std::optional<LightBounds> {
            using Kind = std::decay_t<decltype(k)>;
            LightBounds b;
            b.power = power;
            if constexpr (std::is_same_v<Kind, PointLight>) {
                b.box.expand(k.position);
                b.thetaO = kPi;  // every direction
                b.thetaE = 0.5f * kPi;
                return b;
            } else if constexpr (std::is_same_v<Kind, SpotLight>) {
                b.box.expand(k.position);
                b.axis = k.direction;
                b.thetaO = 0.0f;
                b.thetaE = safeAcos(k.cosTotalWidth);  // nothing outside the cone
                return b;
            } else if constexpr (std::is_same_v<Kind, ProjectorLight>) {
                b.box.expand(k.position);
                b.axis = k.axis;
                b.thetaO = 0.0f;
                // The frustum's corners are the farthest from its axis.
                b.thetaE = std::atan(std::sqrt(k.tanX * k.tanX + k.tanY * k.tanY));
                return b;
            } else if constexpr (std::is_same_v<Kind, TriangleLight>) {
                const Vec3 c = k.cross();
                const float length = glm::length(c);
                if (!(length > 0.0f)) return std::nullopt;  // no area, no light
                b.box.expand(k.p0);
                b.box.expand(k.p1);
                b.box.expand(k.p2);
                b.axis = c / length;
                b.thetaO = 0.0f;
                b.thetaE = 0.5f * kPi;  // a diffuse surface emits over its hemisphere
                b.twoSided = k.twoSided;
                return b;
            } else {
                return std::nullopt;  // infinite lights are chosen apart from the BVH
            }
        },
        light.kind);
}

}  // namespace strahl
