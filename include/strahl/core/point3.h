#pragma once
// Double-precision points for the geometry that works in double (implicit and
// parametric surfaces), and Point3<T>: three coordinates in any arithmetic
// (double, num::Interval, num::Dual), so one templated formula serves them all.

#include <glm/vec3.hpp>

namespace strahl {

using DVec3 = glm::dvec3;

template <class T>
struct Point3 {
    T x, y, z;
};

}  // namespace strahl
