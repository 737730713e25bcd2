#pragma once
// Internal to meshio: a zlib or gzip stream inflated into memory (the
// .serialized format's meshes, .ply.gz files).

#include <string>
#include <string_view>

namespace strahl::meshio {

enum class Compression { Zlib, Gzip };

// The stream starting at `data`, inflated until its end or the input's.
// Throws strahl::Error naming `name` for corrupt data, or when the result
// would exceed 8 GiB (a corrupt or hostile file, not a mesh).
std::string inflateAll(std::string_view data, const std::string& name, Compression compression);

}  // namespace strahl::meshio
