#pragma once
// Internal to the scene module: the scene file formats strahl reads, a closed
// family. Each turns a file's text into a strahl scene document (the JSON of
// docs/scene-format.md), on which the command line's patches, the
// fingerprints and the parser then work, so a scene written for another
// renderer gets every option of `strahl render` through its importer. One
// file per format (json_scene_format.cpp, ...), listed in scene_formats.cpp;
// docs/architecture.md, "How to add a scene file format".

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>

namespace strahl::scene_detail {

struct SceneFormat {
    std::string_view name;                         // for messages: "strahl JSON"
    std::span<const std::string_view> extensions;  // lower case, with the dot
    // The document of `text`; `file` anchors relative paths, `label` names the
    // file in errors ("<label>:LINE:COLUMN: ..." or "<label>: <place>: ..."),
    // `defines` are -D name=value (values for the format's parameters).
    nlohmann::json (*toDocument)(const std::string& text, const std::filesystem::path& file,
                                 const std::string& label,
                                 const std::map<std::string, std::string>& defines);
};

// The format of `file` by its extension (case-insensitive); strahl's JSON for
// any extension no other format claims.
const SceneFormat& sceneFormatOf(const std::filesystem::path& file);

}  // namespace strahl::scene_detail
