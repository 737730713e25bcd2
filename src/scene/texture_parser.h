#pragma once
// Internal to the scene module: what an image texture object of the scene
// file says besides its file — how the image is sampled and placed
// (docs/materials.md): "wrap", "filter" and "uv_transform". Materials and
// lights (a spot's projected image) read them alike.

#include <filesystem>
#include <initializer_list>
#include <string_view>

#include "json_reader.h"
#include "strahl/material/textured.h"

namespace strahl::scene_detail {

constexpr std::string_view kTextureSamplingKeys[] = {"wrap", "filter", "uv_transform"};

// Checks that v (an object) has no keys but `own` and the sampling keys.
void requireTextureKeys(const JsonValue& v, std::initializer_list<std::string_view> own);

// Reads the sampling keys of v into out.sampling and out.stTransform.
void parseTextureSampling(const JsonValue& v, TextureRef& out);

// {"texture": file, sampling keys}: the file resolved against `folder` and
// checked to exist.
TextureRef parseImageTexture(const JsonValue& v, const std::filesystem::path& folder);

}  // namespace strahl::scene_detail
