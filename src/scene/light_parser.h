#pragma once
// Internal to the scene module: one element of the scene file's "lights": its
// "type" chooses the kind (strahl/integrator/light.h), which parses the rest
// (docs/lights.md, docs/scene-format.md#lights).

#include <filesystem>

#include "json_reader.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

LightDesc parseLight(const JsonValue& v, const std::filesystem::path& folder);

}  // namespace strahl::scene_detail
