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

// Oriented cubic, Embree's normal-oriented ribbon. It is meant to follow the
// edges l(u), r(u) = C(u) -+ r(u) k(u), k(u) = normalize(n(u) x C'(u)), with
// n the normal curve; Embree makes it a tensor-product surface whose edges
// are the cubic Béziers with l's and r's values and derivatives at u = 0 and
// 1 (Hermite). Their mean is C itself (a cubic is its own Hermite
// interpolant), so
//   S(u, s) = C(u) + s W(u),  s in [-1, 1],
// with W the cubic Bézier of control points
//   w0 = r0 k0,  w1 = w0 + (r k)'(0)/3,  w2 = w3 - (r k)'(1)/3,  w3 = r1 k1,
// where (r k)' = r' k + r k', k' = (b' - k (k . b'))/|b|, b = n x C' and
// b' = n' x C' (Embree takes C'' as zero there: "otherwise very large
// curvatures ... can thicken the constructed curve"). Exact at the ends in
// position, half width and orientation; in between the direction across
// turns smoothly.
struct OrientedFrame {
    DVec3 w[4];  // W's Bézier control points
};
// False when a normal is parallel to the curve at an end (no direction
// across). nb: the normal curve as a (degree-3) Bézier.
bool orientedFrame(const DVec4 b[4], const DVec4 nb[4], OrientedFrame& frame);
// W(u) and, if wanted, W'(u).
DVec3 orientedWidth(const OrientedFrame& frame, double u, DVec3* derivative = nullptr);
// The ray meets the line {C(u) + s W(u)} where (C(u) - o) . (W(u) x d) = 0, a
// polynomial of degree 6 in u: its sign changes on 128 intervals of [0, 1],
// refined by bisection, then s and t from the two remaining equations. The
// nearest root with |s| <= 1 in (tnear, tfar); v = s, Ng = S_u x S_s.
bool intersectOrientedCubic(const DRay& ray, const DVec4 b[4], const OrientedFrame& frame, RefHit& hit);

}  // namespace strahl::curve
