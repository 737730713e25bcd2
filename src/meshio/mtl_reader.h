#pragma once
// Wavefront .mtl material libraries, read for the OBJ loader.

#include <filesystem>
#include <string>
#include <unordered_map>

#include "strahl/meshio/mesh_file.h"

namespace strahl::meshio {

// Materials by name; the first definition of a name wins.
using MaterialLibrary = std::unordered_map<std::string, MeshMaterial>;

// Adds the materials of `mtlFile` to `library`. Throws "file.mtl:line: what" on
// malformed statements; textures that cannot be found are warnings.
void readMaterialLibrary(const std::filesystem::path& mtlFile, MaterialLibrary& library);

}  // namespace strahl::meshio
