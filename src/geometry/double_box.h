#pragma once
// Internal to the geometry module: double-precision boxes for the user shapes
// that intersect in double (implicit cells, parametric sub-patches) — clipping
// a ray to a box, and rounding a double box outwards to the float Bounds3 an
// accelerator takes — and the finiteness test of a DVec3 the module shares.

#include <algorithm>
#include <cmath>
#include <utility>

#include "strahl/core/bounds.h"
#include "strahl/core/point3.h"

namespace strahl::geometry_detail {

// Per component, the largest float <= v (down) or the smallest float >= v (up).
inline Vec3 roundDown(const DVec3& v) {
    auto down = [](double x) {
        const float f = static_cast<float>(x);
        return static_cast<double>(f) > x ? std::nextafter(f, -kInfinity) : f;
    };
    return Vec3(down(v.x), down(v.y), down(v.z));
}
inline Vec3 roundUp(const DVec3& v) {
    auto up = [](double x) {
        const float f = static_cast<float>(x);
        return static_cast<double>(f) < x ? std::nextafter(f, kInfinity) : f;
    };
    return Vec3(up(v.x), up(v.y), up(v.z));
}

inline bool isFiniteD(const DVec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Narrows [t0, t1] to the parameters of o + t·d inside the box [lo, hi] (slab
// method); false if nothing is left. An axis the ray runs parallel to
// constrains nothing if o lies in its slab and rejects the ray otherwise
// (which avoids 0·inf = NaN).
inline bool clipToBox(const DVec3& o, const DVec3& d, const DVec3& lo, const DVec3& hi, double& t0,
                      double& t1) {
    for (int axis = 0; axis < 3; ++axis) {
        if (d[axis] == 0.0) {
            if (o[axis] < lo[axis] || o[axis] > hi[axis]) return false;
            continue;
        }
        const double inv = 1.0 / d[axis];
        double a = (lo[axis] - o[axis]) * inv, b = (hi[axis] - o[axis]) * inv;
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    return t0 <= t1;
}

}  // namespace strahl::geometry_detail
