#pragma once
// Internal to the scene module: a "subdivision" shape of the scene file — a
// Catmull-Clark control cage (inline "positions" and "faces", or an OBJ
// "file"), its creases, corners, holes and boundary mode, the levels and an
// optional displacement — and its surface placed in world space when the
// world is built. Documented in docs/scene-format.md and docs/geometry.md.

#include <filesystem>
#include <memory>

#include "json_reader.h"
#include "strahl/geometry/subdivision_surface.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

// Fills shape.subdivision (and its kind and name) from the shape object.
void parseSubdivisionShape(const JsonValue& v, const std::filesystem::path& folder, ShapeDesc& shape);

// The surface in world space: the cage read (from its file, if any), moved by
// shape.transform, refined, displaced. `source` names the shape in errors.
std::shared_ptr<const SubdivisionSurface> makeSubdivisionSurface(const ShapeDesc& shape, const std::string& source);

}  // namespace strahl::scene_detail
