// strahl's own scene format: JSON with comments (docs/scene-format.md). The
// default for any extension no other format claims.

#include "json_reader.h"
#include "scene_formats.h"

namespace strahl::scene_detail {

namespace {

constexpr std::string_view kExtensions[] = {".json"};

nlohmann::json toDocument(const std::string& text, const std::filesystem::path&,
                          const std::string& label) {
    return parseJsonText(text, label);
}

}  // namespace

extern const SceneFormat kJsonSceneFormat{"strahl JSON", kExtensions, &toDocument};

}  // namespace strahl::scene_detail
