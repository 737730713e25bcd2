#pragma once
// The built-in parametric surfaces, in object space (place them with a shape's
// transform). Parameters are checked: a non-finite or out-of-range value throws
// strahl::Error naming the parameter (the scene builder adds the shape).
// docs/parametric-surfaces.md gives every formula with its partials; each
// surface gives its partials by hand and the tests check them against
// automatic differentiation.

#include <vector>

#include "strahl/geometry/parametric_surface.h"

namespace strahl {

// f(ϱ, φ) = r (sin ϱ cos φ, sin ϱ sin φ, cos ϱ) on [0, π] × [0, 2π), periodic
// in φ; poles at ϱ = 0 and π. ∂ϱf × ∂φf = r² sin ϱ · f/r points outwards.
ParametricSurfacePtr makeParametricSphere(double radius);

// f(u, v) = ((R + r cos v) cos u, (R + r cos v) sin u, r sin v) on [0, 2π)²,
// periodic in both: the torus around the z axis.
ParametricSurfacePtr makeParametricTorus(double majorRadius, double minorRadius);

// f(φ, z) = (r cos φ, r sin φ, z) on [0, 2π) × [zMin, zMax]: an open cylinder.
ParametricSurfacePtr makeParametricCylinder(double radius, double zMin, double zMax);

// f(φ, s) = ((1 − s) r cos φ, (1 − s) r sin φ, s h) on [0, 2π) × [0, 1]: an open
// cone with base radius r at z = 0 and its apex at z = h (a pole at s = 1).
ParametricSurfacePtr makeParametricCone(double radius, double height);

// f(u, s) = ((R + s cos(u/2)) cos u, (R + s cos(u/2)) sin u, s sin(u/2)) on
// [0, 2π) × [−w, w]: a Möbius strip of radius R and half-width w. Its seam is
// twisted: f(2π, s) = f(0, −s).
ParametricSurfacePtr makeMobiusStrip(double radius, double halfWidth);

}  // namespace strahl
