#pragma once
// The benchmark mesh: a real scan subdivided to at least a million triangles.

#include <string>

#include "strahl/camera/camera.h"
#include "strahl/geometry/triangle_mesh.h"

namespace strahl::bench {

// Splits every triangle into four at its edge midpoints (shared midpoints, so
// the surface stays watertight); the shape is unchanged, the count grows 4x.
TriangleMesh subdivideMidpoints(const TriangleMesh& mesh);

// Loads `path` (or, if empty, ../shared/data's Armadillo, else a procedural
// sphere) and subdivides until it has at least minTriangles. `description`
// receives what was used.
TriangleMesh benchmarkMesh(const std::string& path, size_t minTriangles, std::string& description);

// A kSize x kSize perspective view (fov 40°, d = 1) of `bounds` from the front
// (+z) at 1.5 bounding radii: a mesh fills the frame, so the figure of merit
// is traversal of a dense mesh, not rays that miss it.
Camera frontCamera(const Bounds3& bounds, int size);

// Removes "NAME VALUE" (e.g. "--mesh PATH") from the command line, before
// Google Benchmark sees it, and returns VALUE, or "" if absent.
std::string takeOption(int& argc, char** argv, const char* name);

}  // namespace strahl::bench
