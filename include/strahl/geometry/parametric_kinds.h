#pragma once
// The built-in parametric surfaces a scene file names by "type", a closed
// family: one file per kind, src/geometry/parametric_<kind>.cpp, holding its
// surface class, its factory (parametric_builtins.h), its keys and defaults
// and its parsing through SurfaceParameters (surface_parameters.h);
// parametricKinds() (parametric_kinds.cpp) lists them. Revolution, Bézier
// patches, height fields and formulas are not kinds: they read profiles,
// files or formulas, and the scene parser builds them itself.

#include <span>
#include <string_view>

#include "strahl/geometry/parametric_surface.h"
#include "strahl/geometry/surface_parameters.h"

namespace strahl {

using ParametricKind = SurfaceKind<ParametricSurfacePtr>;

// Every built-in kind, in the order `type` errors list their names.
std::span<const ParametricKind* const> parametricKinds();
// The kind answering to `name`, or null.
const ParametricKind* findParametricKind(std::string_view name);

}  // namespace strahl
