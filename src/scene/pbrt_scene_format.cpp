// pbrt-v4 scene files (.pbrt): read by pbrt_parser.cpp, mapped onto strahl's
// scene document by pbrt_mapping.cpp. docs/pbrt.md.

#include "pbrt_mapping.h"
#include "pbrt_parser.h"
#include "scene_formats.h"
#include "strahl/core/error.h"

namespace strahl::scene_detail {

namespace {

constexpr std::string_view kPbrtExtensions[] = {".pbrt"};

nlohmann::json pbrtToDocument(const std::string& text, const std::filesystem::path& file,
                              const std::string& label,
                              const std::map<std::string, std::string>& defines) {
    if (!defines.empty())
        fail(label, ": -D ", defines.begin()->first, ": pbrt scenes have no parameters to define");
    const pbrt::Scene scene = pbrt::readScene(text, file, label);
    return pbrt::toStrahlDocument(scene, std::filesystem::current_path());
}

}  // namespace

extern const SceneFormat kPbrtSceneFormat{"pbrt-v4", kPbrtExtensions, &pbrtToDocument};

}  // namespace strahl::scene_detail
