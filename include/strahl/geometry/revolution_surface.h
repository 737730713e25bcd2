#pragma once
// A surface of revolution: a profile curve (r(s), z(s)) in the half-plane
// r ≥ 0 turned around the z axis,
//
//     f(φ, s) = (r(s) cos φ, r(s) sin φ, z(s)),   φ ∈ [0, 2π) (periodic),
//                                                  s ∈ [0, n − 1],
//
// where (r, z) is the uniform Catmull–Rom spline through the n profile points
// P_0..P_{n−1}: P_k at s = k exactly, and on segment k (s = k + t, t ∈ [0,1])
// the cubic Hermite curve from P_k to P_{k+1} with tangents
//     m_k = (P_{k+1} − P_{k−1}) / 2        inside,
//     m_0 = P_1 − P_0,  m_{n−1} = P_{n−1} − P_{n−2}   at the ends (the tangent
//                       a reflected phantom point 2P_0 − P_1 would give).
// The curve is C¹. Two points give a straight segment (a cone, a cylinder or
// an annulus); four or more give a smooth profile.
//
// Partials: ∂φ f = (−r sin φ, r cos φ, 0), ∂s f = (r' cos φ, r' sin φ, z').
//
// Orientation: ∂φ f × ∂s f = r · (z' cos φ, z' sin φ, −r'). In the (r, z)
// half-plane (r to the right, z up) that is r·(z', −r'), the profile's tangent
// turned clockwise: the normal lies to the RIGHT of the direction in which the
// profile runs. So it points away from the axis where z increases along the
// profile, and down where the profile moves away from the axis at constant z.
// A profile that runs counterclockwise around the solid it bounds — from the
// bottom pole outwards, up the side and back in to the top pole — has outward
// normals; list the points in the opposite order to flip them.
//
// Profile points with r = 0 are poles (∂φ f = 0; the normal there is the limit
// from inside the domain). The spline itself may dip below r = 0 between points
// near the axis, which mirrors that piece through the axis; keep the points
// near the axis dense enough (or with r = 0 only at the ends) to avoid it.

#include <vector>

#include <glm/vec2.hpp>

#include "strahl/geometry/parametric_surface.h"

namespace strahl {

// profile[k] = (r, z). Throws strahl::Error on fewer than 2 points, a
// non-finite value, a negative r, two consecutive equal points, or a profile
// that lies entirely on the axis (r = 0 everywhere).
ParametricSurfacePtr makeSurfaceOfRevolution(std::vector<glm::dvec2> profile);

}  // namespace strahl
