#pragma once
// Internal to the scene module: the "materials" array of a scene file. Every
// material type, key and default is documented in docs/materials.md and
// docs/scene-format.md. Texture files are checked for existence here, so a
// missing file is reported with its place; they are opened (and checked to be
// images) when the world is built.

#include <filesystem>
#include <vector>

#include "json_reader.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

std::vector<MaterialDesc> parseMaterials(const JsonValue& materials,
                                         const std::filesystem::path& folder);

}  // namespace strahl::scene_detail
