#pragma once
// Internal to the scene module: the scene file's "film" (size, outputs, AOVs,
// EXR precision, pixel filter) and "render" (integrator, samples, seed, path
// depth, Russian roulette, ambient occlusion) objects
// (docs/scene-format.md#film, #render).

#include <filesystem>

#include "json_reader.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

FilmDesc parseFilm(const JsonValue& v, const std::filesystem::path& folder);
RenderDesc parseRender(const JsonValue& v);

}  // namespace strahl::scene_detail
