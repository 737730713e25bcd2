#pragma once
// Internal to the scene module: a Mitsuba 3 scene (mitsuba_xml.h) as a strahl
// scene document (the JSON of docs/scene-format.md). Each plugin maps to the
// strahl keys that render the same expected image; docs/mitsuba.md has the
// table, plugin by plugin and parameter by parameter. A plugin or parameter
// that strahl cannot render the same is one error naming the file, the line
// and the element ("scene.xml:42: <medium type=\"homogeneous\">: participating
// media are not supported"), never dropped.

#include <nlohmann/json.hpp>

#include "mitsuba_xml.h"

namespace strahl::scene_detail::mitsuba {

// `sceneFolder` is the folder of the scene file: file names in the document
// are relative to it where they can be.
nlohmann::json toStrahlDocument(const Scene& scene, const std::filesystem::path& sceneFolder);

}  // namespace strahl::scene_detail::mitsuba
