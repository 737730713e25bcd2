#pragma once
// Internal entry points of the PLY and OBJ loaders, for tests/meshio and
// bench/load_meshes.cpp: the sequential PLY path (the loader before parallel
// decoding, kept as the fallback) and the OBJ parser with a chosen chunk size.

#include <cstddef>
#include <filesystem>
#include <string_view>

#include "strahl/meshio/mesh_file.h"

namespace strahl::meshio {

// loadPlyFromMemory with the parallel decoder on or off (off: every element
// through the generic one-value-at-a-time reader).
LoadedMesh decodePly(std::string_view data, const std::filesystem::path& file, bool parallel);

// The file read with fread (readWholeFile) and decoded sequentially: the PLY
// loader as it was before memory mapping and parallel decoding.
LoadedMesh loadPlySequential(const std::filesystem::path& file);

// loadObjFromMemory with the text split into chunks of about `chunkBytes`
// (each ends at a line end; at least one line per chunk).
LoadedMesh decodeObj(std::string_view data, const std::filesystem::path& file, size_t chunkBytes);

}  // namespace strahl::meshio
