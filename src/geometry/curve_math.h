#pragma once
// Curve segments as cubic Béziers in (x, y, z, r), and the three reference
// intersectors of curve_set.h (round cubic, round linear, flat), all in
// double. Internal to the geometry module.

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "strahl/core/point3.h"

namespace strahl::curve {

using DVec4 = glm::dvec4;

struct Eval {
    DVec4 p, dp, ddp;  // the point (x, y, z, r) and its first two derivatives in u
};

// A cubic Bézier b at u.
Eval evalBezier(const DVec4 b[4], double u);

// De Casteljau: the halves [0, 1/2] and [1/2, 1] of b.
void splitBezier(const DVec4 b[4], DVec4 left[4], DVec4 right[4]);

// A ray in double; dir need not be unit length.
struct DRay {
    DVec3 origin, dir;
    double tnear = 0.0, tfar = 0.0;
};

struct RefHit {
    double t = 0.0, u = 0.0, v = 0.0;
    DVec3 Ng{0.0};
};

// Round cubic: the circle of radius r(u) around C(u) normal to C'(u), open
// at u = 0 and 1. Nearest root in (tnear, tfar).
bool intersectRoundCubic(const DRay& ray, const DVec4 b[4], RefHit& hit);

// Round linear: the convex hull of the spheres (p0, r0) and (p1, r1).
bool intersectRoundLinear(const DRay& ray, const DVec4& p0, const DVec4& p1, RefHit& hit);
// The distance of x from that hull (negative inside) and the parameter s in
// [0, 1] of the sphere of the linear family that is nearest.
double roundLinearDistance(const DVec3& x, const DVec4& p0, const DVec4& p1, double& s);

// Flat cubic: `pieces` ray-facing quads.
bool intersectFlatCubic(const DRay& ray, const DVec4 b[4], int pieces, RefHit& hit);
// Flat linear: the ray passes within r(u) of the segment, as seen along the
// ray; t is the depth of the nearest point of the centre line.
bool intersectFlatLinear(const DRay& ray, const DVec4& p0, const DVec4& p1, RefHit& hit);

}  // namespace strahl::curve
