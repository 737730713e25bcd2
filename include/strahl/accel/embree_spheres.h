#pragma once
// Embree's own sphere primitive (RTC_GEOMETRY_TYPE_SPHERE_POINT): the baseline
// the implicit sphere is measured against (bench/implicit_surfaces.cpp). It is
// Embree's float ray–sphere test inside Embree's traversal, with no callback
// into strahl, so it bounds what user geometry can reach for the same shape.
//
// The spheres form one geometry, geomID 0; primID is the sphere's index in the
// span. A hit reports Embree's values: u = v = 0 and Ng = hit point − centre
// (unnormalised); a ray starting inside a sphere hits its far side.

#include <memory>
#include <span>

#include "strahl/accel/accel.h"
#include "strahl/core/math.h"

namespace strahl {

// `spheres` holds centre (x, y, z) and radius (w) per sphere; it is copied, so
// it need not outlive the Accel. Throws strahl::Error if a centre or radius is
// not finite, a radius is not > 0, or Embree reports an error.
std::unique_ptr<Accel> buildEmbreeSphereAccel(std::span<const Vec4> spheres,
                                              const AccelBuildOptions& options);

}  // namespace strahl
