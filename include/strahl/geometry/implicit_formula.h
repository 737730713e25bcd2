#pragma once
// An implicit surface written as a formula in x, y, z in the scene file, e.g.
// "(x^2 + y^2 + z^2 + R^2 - r^2)^2 - 4*R^2*(x^2 + y^2)". The text is compiled
// once (geometry/formula.h) and evaluated by the same tape in double, interval
// and dual arithmetic, so gradients are automatic and exact. A formula has no
// bounds of its own: its shape needs a box.

#include <map>
#include <string>

#include "strahl/geometry/implicit_surface.h"

namespace strahl {

// Throws strahl::Error "column N: ..." for a malformed formula.
ImplicitSurfacePtr makeFormulaSurface(const std::string& text,
                                      const std::map<std::string, double>& parameters);

}  // namespace strahl
