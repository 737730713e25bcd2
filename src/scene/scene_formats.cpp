// The scene file formats (scene_formats.h): one line per format.

#include "scene_formats.h"

#include <algorithm>
#include <cctype>

namespace strahl::scene_detail {

extern const SceneFormat kJsonSceneFormat;     // json_scene_format.cpp: the default
extern const SceneFormat kMitsubaSceneFormat;  // mitsuba_scene_format.cpp
extern const SceneFormat kPbrtSceneFormat;     // pbrt_scene_format.cpp

namespace {

const SceneFormat* const kFormats[] = {
    &kJsonSceneFormat,
    &kMitsubaSceneFormat,
    &kPbrtSceneFormat,
};

}  // namespace

const SceneFormat& sceneFormatOf(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const SceneFormat* format : kFormats)
        if (std::find(format->extensions.begin(), format->extensions.end(), extension) !=
            format->extensions.end())
            return *format;
    return kJsonSceneFormat;
}

}  // namespace strahl::scene_detail
