#pragma once
// A parametric surface written as three formulas in u and v in the scene file,
// e.g. x = "(R + r*cos(v))*cos(u)". Each is compiled once (geometry/formula.h)
// and evaluated in double, interval and dual arithmetic, so the partials ∂u f
// and ∂v f are automatic and exact. The domain and its seams come with it.

#include <map>
#include <string>

#include "strahl/geometry/parametric_surface.h"

namespace strahl {

struct ParametricFormulaText {
    std::string x, y, z;
};

// Throws strahl::Error "x: column N: ..." for a malformed formula (naming
// which of x, y, z), and for a bad parameter or domain.
ParametricSurfacePtr makeParametricFormula(const ParametricFormulaText& text,
                                           const ParamDomain& domain,
                                           const std::map<std::string, double>& parameters);

}  // namespace strahl
