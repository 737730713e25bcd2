#include "strahl/core/spherical_triangle.h"

#include <algorithm>
#include <cmath>

namespace strahl {

namespace {

using DVec3 = glm::dvec3;

constexpr double kPiD = 3.14159265358979323846;

// Angle between unit vectors, accurate near 0 and pi (acos of the dot product
// loses half the digits there): 2 asin(|v1 -+ v2| / 2).
double angleBetween(const DVec3& v1, const DVec3& v2) {
    if (glm::dot(v1, v2) < 0.0)
        return kPiD - 2.0 * std::asin(std::min(1.0, glm::length(v1 + v2) / 2.0));
    return 2.0 * std::asin(std::min(1.0, glm::length(v2 - v1) / 2.0));
}

// The unit component of v orthogonal to the unit vector w; zero if v is parallel to w.
DVec3 orthogonalUnit(const DVec3& v, const DVec3& w) {
    const DVec3 o = v - glm::dot(v, w) * w;
    const double len = glm::length(o);
    return len > 0.0 ? o / len : DVec3(0.0);
}

}  // namespace

float triangleSolidAngle(const Vec3& p, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
    const DVec3 r0 = DVec3(p0) - DVec3(p), r1 = DVec3(p1) - DVec3(p), r2 = DVec3(p2) - DVec3(p);
    const double l0 = glm::length(r0), l1 = glm::length(r1), l2 = glm::length(r2);
    const double numerator = std::abs(glm::dot(r0, glm::cross(r1, r2)));
    const double denominator =
        l0 * l1 * l2 + glm::dot(r0, r1) * l2 + glm::dot(r0, r2) * l1 + glm::dot(r1, r2) * l0;
    // atan2 keeps the quadrant: a negative denominator means omega / 2 > pi / 2.
    return static_cast<float>(2.0 * std::atan2(numerator, denominator));
}

// Arvo 1995. On the unit sphere around p let a, b, c be the vertex directions,
// alpha, beta, gamma the interior angles and cos(c_len) = a.b the cosine of the
// arc ab. The area is alpha + beta + gamma - pi (Girard). u.x picks the area
// A' = u.x * area of a sub-triangle a b c' with c' on the arc ac: by the
// spherical law of cosines that fixes cos|ac'| = q below. u.y then picks a point
// on the arc b c' at cos(distance from b) = 1 - u.y (1 - c'.b), which is uniform
// in area within the sub-triangle strip (docs/lights.md derives both steps).
// Everything runs in double: for small triangles the angle sum exceeds pi by
// little, and float would lose the area to cancellation.
std::optional<SphericalTriangleSample> sampleSphericalTriangle(const Vec3& p, const Vec3& p0,
                                                               const Vec3& p1, const Vec3& p2,
                                                               const Vec2& u) {
    return sampleSphericalTriangle(p, p0, p1, p2, u, triangleSolidAngle(p, p0, p1, p2));
}

std::optional<SphericalTriangleSample> sampleSphericalTriangle(const Vec3& p, const Vec3& p0,
                                                               const Vec3& p1, const Vec3& p2,
                                                               const Vec2& u, float solidAngle) {
    if (!(solidAngle > 0.0f)) return std::nullopt;
    const DVec3 origin(p), v0(p0), v1(p1), v2(p2);
    const DVec3 a = glm::normalize(v0 - origin), b = glm::normalize(v1 - origin),
                c = glm::normalize(v2 - origin);

    // Normals of the great circles through the edges; zero for collinear directions.
    DVec3 nab = glm::cross(a, b), nbc = glm::cross(b, c), nca = glm::cross(c, a);
    if (glm::dot(nab, nab) == 0.0 || glm::dot(nbc, nbc) == 0.0 || glm::dot(nca, nca) == 0.0)
        return std::nullopt;
    nab = glm::normalize(nab);
    nbc = glm::normalize(nbc);
    nca = glm::normalize(nca);
    // The interior angle at a is the angle between the planes (a, b) and (a, c),
    // i.e. between a x b and a x c = -nca (likewise at b and c).
    const double alpha = angleBetween(nab, -nca);
    const double beta = angleBetween(nbc, -nab);
    const double gamma = angleBetween(nca, -nbc);
    const double area = alpha + beta + gamma - kPiD;
    if (!(area > 0.0)) return std::nullopt;

    // Step 1: the point c' on arc ac such that triangle a b c' has area A'.
    const double areaPrime = static_cast<double>(u.x) * area;
    const double s = std::sin(areaPrime - alpha), t = std::cos(areaPrime - alpha);
    const double cosAlpha = std::cos(alpha), sinAlpha = std::sin(alpha);
    const double uu = t - cosAlpha;
    const double vv = s + sinAlpha * glm::dot(a, b);
    const double denominator = (vv * s + uu * t) * sinAlpha;
    // denominator -> 0 only as A' -> 0 (then c' = a) for a non-degenerate triangle.
    double q = denominator != 0.0 ? ((vv * t - uu * s) * cosAlpha - vv) / denominator : 1.0;
    q = std::clamp(q, -1.0, 1.0);
    const DVec3 cPrime = q * a + std::sqrt(std::max(0.0, 1.0 - q * q)) * orthogonalUnit(c, a);

    // Step 2: the point on arc b c' at the sampled distance from b.
    const double z = 1.0 - static_cast<double>(u.y) * (1.0 - glm::dot(cPrime, b));
    const DVec3 w =
        glm::normalize(z * b + std::sqrt(std::max(0.0, 1.0 - z * z)) * orthogonalUnit(cPrime, b));

    // Barycentrics of the ray p + t w on the triangle's plane (Moller-Trumbore).
    const DVec3 e1 = v1 - v0, e2 = v2 - v0;
    const DVec3 s1 = glm::cross(w, e2);
    const double divisor = glm::dot(s1, e1);
    if (divisor == 0.0) return std::nullopt;  // w parallel to the plane: cannot happen inside
    const DVec3 d = origin - v0;
    double b1 = glm::dot(d, s1) / divisor;
    double b2 = glm::dot(w, glm::cross(d, e1)) / divisor;
    // Rounding can put a sample on an edge a hair outside; pull it back in.
    b1 = std::clamp(b1, 0.0, 1.0);
    b2 = std::clamp(b2, 0.0, 1.0);
    if (b1 + b2 > 1.0) {
        const double sum = b1 + b2;
        b1 /= sum;
        b2 /= sum;
    }
    SphericalTriangleSample sample;
    sample.barycentrics =
        Vec3(static_cast<float>(1.0 - b1 - b2), static_cast<float>(b1), static_cast<float>(b2));
    sample.dir = Vec3(w);
    sample.pdf = 1.0f / solidAngle;
    return sample;
}

}  // namespace strahl
