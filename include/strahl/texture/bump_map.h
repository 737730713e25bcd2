#pragma once
// Bump maps: a height field h over the texture coordinates displaces the
// surface along its normal, p' = p + h n, and shading takes the normal of the
// displaced surface without moving it (Blinn 1978). With the texture
// coordinates (s, t) = (u, 1 - v) of image lookups, dropping the term h dn/ds
// (small for small heights, as every renderer does) and the tangents'
// components along n (Mitsuba's choice, so a bump map of 0 slope returns ns):
//
//   dp'/ds = dp/ds - n (n . dp/ds) + n dh/ds,   dp/ds =  dp/du,
//   dp'/dt = dp/dt - n (n . dp/dt) + n dh/dt,   dp/dt = -dp/dv,
//   n' = normalise(dp'/ds x dp'/dt), turned to ns's side.

#include "strahl/core/math.h"

namespace strahl {

// `slope` = (dh/ds, dh/dt), already scaled by the map's height scale; ns the
// unit shading normal; dpdu, dpdv the surface tangents. Returns the bumped unit
// normal on ns's side, or ns when a tangent is zero, non-finite or the
// result degenerates.
Vec3 applyBumpMap(const Vec2& slope, const Vec3& ns, const Vec3& dpdu, const Vec3& dpdv);

}  // namespace strahl
