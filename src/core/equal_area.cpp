// The equal-area octahedral map (equal_area.h).

#include "strahl/core/equal_area.h"

#include <algorithm>
#include <cmath>

namespace strahl {

namespace {
constexpr double kPiDouble = 3.14159265358979323846;
}  // namespace

Vec2 equalAreaSphereToSquare(const Vec3& d) {
    const double x = std::abs(double(d.x)), y = std::abs(double(d.y)), z = std::abs(double(d.z));
    const double r = std::sqrt(std::max(0.0, 1.0 - z));
    const double a = std::max(x, y), b = std::min(x, y);
    // φ ∈ [0, 1]: the angle from the larger axis as a fraction of 90°.
    double phi = a == 0.0 ? 0.0 : std::atan(b / a) * (2.0 / kPiDouble);
    if (x < y) phi = 1.0 - phi;
    double v = phi * r;
    double u = r - v;
    if (d.z < 0.0f) {
        // The lower hemisphere folds out to the corners.
        std::swap(u, v);
        u = 1.0 - u;
        v = 1.0 - v;
    }
    u = std::copysign(u, double(d.x));
    v = std::copysign(v, double(d.y));
    return Vec2(static_cast<float>(0.5 * (u + 1.0)), static_cast<float>(0.5 * (v + 1.0)));
}

Vec3 equalAreaSquareToSphere(const Vec2& p) {
    const double u = 2.0 * p.x - 1.0, v = 2.0 * p.y - 1.0;
    const double up = std::abs(u), vp = std::abs(v);
    // The signed distance from the diagonal |u| + |v| = 1: the radius r.
    const double signedDistance = 1.0 - (up + vp);
    const double d = std::abs(signedDistance);
    const double r = 1.0 - d;
    // φ within the octant, from the larger axis.
    const double phi = (r == 0.0 ? 1.0 : (vp - up) / r + 1.0) * kPiDouble / 4.0;
    const double z = std::copysign(1.0 - r * r, signedDistance);
    const double cosPhi = std::copysign(std::cos(phi), u), sinPhi = std::copysign(std::sin(phi), v);
    const double s = r * std::sqrt(std::max(0.0, 2.0 - r * r));
    return Vec3(static_cast<float>(cosPhi * s), static_cast<float>(sinPhi * s), static_cast<float>(z));
}

}  // namespace strahl
