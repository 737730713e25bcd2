#pragma once
// The solid angle a triangle subtends at a point, and uniform sampling of it:
// the projection of the triangle onto the unit sphere around the point is a
// spherical triangle, and Arvo's algorithm (1995, "Stratified Sampling of
// Spherical Triangles") maps [0, 1)^2 onto it with constant density 1 / area.
// The derivation is in docs/lights.md ("Spherical triangles").

#include <optional>

#include "strahl/core/math.h"

namespace strahl {

// Solid angle (sr, in [0, 2 pi]) subtended at p by the triangle p0 p1 p2, by
// Van Oosterom & Strackee (1983):
//     tan(omega / 2) = |r0 . (r1 x r2)| /
//                      (|r0||r1||r2| + (r0.r1)|r2| + (r0.r2)|r1| + (r1.r2)|r0|)
// with ri = pi - p; evaluated in double, so it is accurate for triangles from
// ~1e-12 sr to the full hemisphere. 0 for a degenerate triangle or p in its plane.
float triangleSolidAngle(const Vec3& p, const Vec3& p0, const Vec3& p1, const Vec3& p2);

struct SphericalTriangleSample {
    Vec3 barycentrics{0.0f};  // of the sampled triangle point: b0 p0 + b1 p1 + b2 p2
    Vec3 dir{0.0f};           // unit direction from p towards that point
    float pdf = 0.0f;         // 1 / triangleSolidAngle(p, p0, p1, p2)
};

// A direction from p distributed uniformly in the solid angle of the triangle
// p0 p1 p2, returned as the barycentrics of the point it reaches (clamped into
// the triangle against rounding). nullopt for a degenerate spherical triangle
// (p in the triangle's plane, collinear vertices). u in [0, 1)^2.
std::optional<SphericalTriangleSample> sampleSphericalTriangle(const Vec3& p, const Vec3& p0,
                                                               const Vec3& p1, const Vec3& p2,
                                                               const Vec2& u);
// The same for a caller that already has triangleSolidAngle(p, p0, p1, p2)
// (light sampling decides on it first), so it is not computed twice.
std::optional<SphericalTriangleSample> sampleSphericalTriangle(const Vec3& p, const Vec3& p0,
                                                               const Vec3& p1, const Vec3& p2,
                                                               const Vec2& u, float solidAngle);

}  // namespace strahl
