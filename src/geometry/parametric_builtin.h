#pragma once
// Internal to the geometry module: what the built-in parametric surfaces
// (parametric_<kind>.cpp) share.

#include <cmath>
#include <memory>

#include "strahl/core/error.h"
#include "strahl/geometry/parametric_builtins.h"
#include "strahl/geometry/parametric_kinds.h"

namespace strahl::parametric_detail {

using num::cos;
using num::sin;

constexpr double kTwoPi = 2.0 * num::kPiD;

inline void requirePositive(const char* name, double value) {
    if (!(std::isfinite(value) && value > 0.0))
        fail(name, " must be a positive finite number, got ", value);
}

}  // namespace strahl::parametric_detail
