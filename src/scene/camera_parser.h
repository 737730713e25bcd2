#pragma once
// Internal to the scene module: the scene file's "camera" (docs/camera.md,
// docs/scene-format.md#camera): the frame, the projection and its window,
// the thin lens, or the choice of a camera a glTF file places (the file is
// read when the world is built).

#include <filesystem>

#include "json_reader.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

// `v` may be an empty object (no "camera": every default).
CameraDesc parseCamera(const JsonValue& v, const std::filesystem::path& folder);

}  // namespace strahl::scene_detail
