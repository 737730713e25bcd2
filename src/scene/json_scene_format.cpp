// strahl's own scene format: JSON with comments (docs/scene-format.md). The
// default for any extension no other format claims.

#include "json_reader.h"
#include "strahl/core/error.h"
#include "scene_formats.h"

namespace strahl::scene_detail {

namespace {

constexpr std::string_view kJsonExtensions[] = {".json"};

nlohmann::json jsonToDocument(const std::string& text, const std::filesystem::path&,
                              const std::string& label,
                              const std::map<std::string, std::string>& defines) {
    if (!defines.empty())
        fail(label, ": -D ", defines.begin()->first,
             ": strahl JSON scenes have no parameters to define (use --set POINTER=VALUE)");
    return parseJsonText(text, label);
}

}  // namespace

extern const SceneFormat kJsonSceneFormat{"strahl JSON", kJsonExtensions, &jsonToDocument};

}  // namespace strahl::scene_detail
