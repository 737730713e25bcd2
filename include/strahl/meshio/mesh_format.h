#pragma once
// The mesh file formats strahl reads, a closed family: each loader file
// (obj_loader.cpp, ply_loader.cpp, gltf_loader.cpp) defines its MeshFormat
// next to its code, and src/meshio/mesh_formats.cpp lists them, one line
// each. Everything that depends on which formats exist (loadMeshFile, the
// scene parser's check of a mesh file's extension, the messages listing the
// extensions) asks this list. docs/architecture.md, "How to add a mesh file
// format".

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "strahl/meshio/mesh_file.h"

namespace strahl {

struct MeshFormat {
    std::string_view name;                         // "OBJ", "PLY", "glTF 2.0"
    std::span<const std::string_view> extensions;  // lower case, with the dot
    LoadedMesh (*load)(const std::filesystem::path& file);
    // The same on bytes already in memory (mesh_file.h); `file` names them.
    LoadedMesh (*loadFromMemory)(std::string_view data, const std::filesystem::path& file);
};

std::span<const MeshFormat* const> meshFormats();

// The format of `file` by its extension (case-insensitive); null if none.
const MeshFormat* findMeshFormat(const std::filesystem::path& file);

// Every extension, in list order, joined by `separator`, the last two by
// `lastSeparator`: meshExtensionList(", ", " or ") is ".obj, .ply, .gltf or .glb".
std::string meshExtensionList(std::string_view separator, std::string_view lastSeparator);

}  // namespace strahl
