#pragma once
// Internal to the scene module: a pbrt-v4 scene (pbrt_parser.h) as a strahl
// scene document (the JSON of docs/scene-format.md). Each directive maps to
// the strahl keys that render the same expected image; docs/pbrt.md has the
// tables. A directive, type or parameter strahl cannot render the same is
// one error naming the file, the line and the directive
// ("scene.pbrt:42: Shape \"curve\": curves are not supported yet"), never
// dropped; a parameter the mapping does not read is an error too.
//
// pbrt's space is left-handed (its camera looks along +z with +x to the
// right of the image), strahl's right-handed: the document is pbrt's world
// mirrored in x, camera included, which shows the same image.

#include <nlohmann/json.hpp>

#include "pbrt_parser.h"

namespace strahl::scene_detail::pbrt {

// `cwd` anchors the film's output file name, as pbrt writes it.
nlohmann::json toStrahlDocument(const Scene& scene, const std::filesystem::path& cwd);

}  // namespace strahl::scene_detail::pbrt
