#pragma once
// Internal to the scene module: the "surface" of an implicit shape — a
// built-in, a formula, or a CSG tree of these — and the shape's "box", "cells"
// and "tolerance". The surface is built here, at parse time, so that a formula
// with a syntax error is reported with its place in the scene file before any
// loading starts. Documented in docs/scene-format.md and docs/implicit-surfaces.md.

#include "json_reader.h"
#include "strahl/geometry/implicit_shape.h"

namespace strahl::scene_detail {

// `shape` is the shape object (its "surface", "box", "cells", "tolerance" keys).
void parseImplicitShape(const JsonValue& shape, ImplicitSurfacePtr& surface,
                        ImplicitShapeOptions& options);

}  // namespace strahl::scene_detail
