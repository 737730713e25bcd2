#pragma once
// Internal to the scene module: a "curves" shape of the scene file — strands
// of hair, fur or grass (geometry/curve_set.h) given inline ("points" and
// "strands") or as a strand file ("file", meshio/curve_file.h, read when the
// world is built). Documented in docs/scene-format.md and docs/geometry.md.

#include <filesystem>

#include "json_reader.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

// Fills shape.curves (and shape.file for a strand file) from the shape object.
void parseCurvesShape(const JsonValue& v, const std::filesystem::path& folder, ShapeDesc& shape);

// A curves shape's CurveSetDesc placed in world space: points moved by
// `transform`, radii scaled by its mean scale (the cube root of |det|) when
// `scaleRadius`, else kept (Mitsuba's curves keep their radii).
CurveSetDesc placeCurves(CurveSetDesc curves, const Mat4& transform, bool scaleRadius);

}  // namespace strahl::scene_detail
