#pragma once
// Mesh file loaders. Each returns one TriangleMesh (polygons fan-triangulated)
// plus the materials its faces refer to, and throws strahl::Error with
// "file:line: what" (text) or "file: byte offset N: what" (binary) on any
// malformed, truncated or out-of-range input.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "strahl/core/math.h"
#include "strahl/geometry/triangle_mesh.h"

namespace strahl {

// A surface description found in a mesh file (.mtl for OBJ).
struct MeshMaterial {
    std::string name;
    Color diffuse{0.8f};
    Color emission{0.0f};
    std::filesystem::path diffuseTexture;  // resolved on disk (case-insensitive), or empty
};

struct LoadedMesh {
    TriangleMesh mesh;  // faceMaterials index into `materials` (empty if none)
    std::vector<MeshMaterial> materials;
};

LoadedMesh loadObj(const std::filesystem::path& file);
LoadedMesh loadPly(const std::filesystem::path& file);

// Recoverable problems (a missing .mtl, an unknown material, an attribute only
// some corners have) are warnings, not errors. They go to the handler set here,
// from any loader thread but one at a time; with no handler (the default) each
// is printed as "strahl: warning: <message>" on stderr. The CLI's --quiet
// installs a handler that drops them.
using MeshWarningHandler = std::function<void(const std::string& message)>;
void setMeshWarningHandler(MeshWarningHandler handler);

// Dispatches on the extension (.obj, .ply; case-insensitive).
LoadedMesh loadMeshFile(const std::filesystem::path& file);

// Finds `name` (which may contain sub-folders) below `dir`, matching each path
// component case-insensitively when the exact spelling does not exist (Sponza's
// .mtl names textures in the wrong case). Returns an empty path if not found.
std::filesystem::path findFileCaseInsensitive(const std::filesystem::path& dir,
                                              const std::string& name);

}  // namespace strahl
