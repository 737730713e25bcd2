#pragma once
// Internal to the scene module: a "parametric" shape — its "surface" (a
// built-in, Bézier patches from a file, a height field from an image, or three
// formulas in u and v), its "mode" (tessellated or direct) and that mode's
// settings. A surface of formulas or a built-in is built here, at parse time,
// so a bad formula is reported with its place in the scene file before any
// loading starts; Bézier patch files and height images are named here and
// read when the world is built (parametric_files.h). Documented in
// docs/scene-format.md and docs/parametric-surfaces.md.

#include <filesystem>

#include "json_reader.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

// `shape` is the shape object; files are resolved against `folder`.
ParametricDesc parseParametricShape(const JsonValue& shape, const std::filesystem::path& folder);

}  // namespace strahl::scene_detail
