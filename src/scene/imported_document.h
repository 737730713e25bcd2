#pragma once
// Internal to the scene module: pieces both importers (mitsuba_plugins.cpp,
// pbrt_mapping.cpp) use to write a strahl scene document.

#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace strahl::scene_detail {

// strahl's [{"matrix": [16 numbers]}] transform, row by row (the last row of
// an affine map is written 0 0 0 1).
nlohmann::json matrixTransform(const glm::dmat4& m);

// Whether a material object (or any value in it) reads an image texture, a
// checkerboard or a mesh attribute: what depends on a shape's (u, v).
bool readsTextures(const nlohmann::json& value);

// The material named `name` in a document's "materials" array; throws
// strahl::Error (an importer's bug) when there is none.
const nlohmann::json& materialNamed(const nlohmann::json& materials, const std::string& name);

}  // namespace strahl::scene_detail
