#pragma once
// Internal to the scene module: a parsed scene document (JSON with its
// comments already gone) to SceneDesc. SceneDocument::parse calls it after
// the command line's patches are applied.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

// `file` is the scene file (absolute; relative paths in it are relative to its
// folder), `label` how errors name it.
SceneDesc parseSceneJson(const nlohmann::json& document, const std::filesystem::path& file,
                         const std::string& label);

}  // namespace strahl::scene_detail
