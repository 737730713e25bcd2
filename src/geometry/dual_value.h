#pragma once
// Internal to the geometry module: the value of a double or of a Dual2 without
// its derivatives, for the parametric surfaces whose eval<T>() picks a cell or
// a segment by value (height_field.cpp, revolution_surface.cpp).

#include "strahl/geometry/parametric_surface.h"

namespace strahl::geometry_detail {

inline double valueOf(double x) {
    return x;
}
inline double valueOf(const Dual2& x) {
    return x.v;
}

}  // namespace strahl::geometry_detail
