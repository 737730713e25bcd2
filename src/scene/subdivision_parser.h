#pragma once
// Internal to the scene module: a "subdivision" shape of the scene file — a
// Catmull-Clark control cage (inline "positions" and "faces", or an OBJ
// "file"), its creases, corners, holes and boundary mode, the levels and an
// optional displacement — and its surface placed in world space when the
// world is built. Documented in docs/scene-format.md and docs/geometry.md.

#include <filesystem>
#include <functional>
#include <memory>

#include "json_reader.h"
#include "strahl/geometry/subdivision_surface.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

// Fills shape.subdivision (and its kind and name) from the shape object.
void parseSubdivisionShape(const JsonValue& v, const std::filesystem::path& folder, ShapeDesc& shape);

// Bytes a refined quad costs: the surface's tables (about 100 B: refined
// points, corner normals, cells) and Embree's grids and BVH (about 40 B),
// measured by bench_subdivision (bench/RESULTS.md) at 3 to 5 levels.
inline constexpr size_t kBytesPerRefinedQuad = 150;

// Where the camera puts a subdivision's refinement: the longest edge allowed
// at a world-space point (edgeLengthFromCamera in scene_builder.cpp), and the
// process's memory limit (0: none).
struct SubdivisionBudget {
    std::function<double(const DVec3&)> maxEdgeLength;  // null: use shape.subdivision.levels
    size_t memoryLimitBytes = 0;
};

// The surface in world space: the cage read (from its file, if any), moved by
// shape.transform, refined, displaced. `source` names the shape in errors.
std::shared_ptr<const SubdivisionSurface> makeSubdivisionSurface(const ShapeDesc& shape, const std::string& source,
                                                                 const SubdivisionBudget& budget);

// The levels (1 … 8) at which every edge of `cage` (world space), split
// 2^levels times, is at most maxEdgeLength at its ends; then lowered until
// the refined quads fit in memoryLimitBytes (if not 0). `capped` says
// whether the limit lowered them.
int levelsForEdgeLength(const SubdivisionCage& cage, const std::function<double(const DVec3&)>& maxEdgeLength,
                        size_t memoryLimitBytes, bool& capped);

}  // namespace strahl::scene_detail
