#pragma once
// The built-in implicit surfaces a scene file names by "type", a closed
// family: one file per kind, src/geometry/implicit_<kind>.cpp, holding its
// surface class, its factory (implicit_builtins.h), its keys and defaults and
// its parsing; implicitKinds() (implicit_kinds.cpp) lists them. A kind parses
// its parameters through SurfaceParameters (surface_parameters.h).
// Formulas and CSG are not kinds: they are compositions the scene parser
// builds itself. docs/architecture.md: how to add one.

#include <span>
#include <string_view>

#include "strahl/geometry/implicit_surface.h"
#include "strahl/geometry/surface_parameters.h"

namespace strahl {

using ImplicitKind = SurfaceKind<ImplicitSurfacePtr>;

// Every built-in kind, in the order `type` errors list their names.
std::span<const ImplicitKind* const> implicitKinds();
// The kind answering to `name`, or null.
const ImplicitKind* findImplicitKind(std::string_view name);

}  // namespace strahl
