// Mitsuba 3 scene files (.xml): read by mitsuba_xml.cpp, mapped onto strahl's
// scene document by mitsuba_plugins.cpp. docs/mitsuba.md.

#include "mitsuba_plugins.h"
#include "mitsuba_xml.h"
#include "scene_formats.h"

namespace strahl::scene_detail {

namespace {

constexpr std::string_view kMitsubaExtensions[] = {".xml"};

nlohmann::json mitsubaToDocument(const std::string& text, const std::filesystem::path& file,
                                 const std::string& label,
                                 const std::map<std::string, std::string>& defines) {
    const mitsuba::Scene scene = mitsuba::readScene(text, label, defines);
    return mitsuba::toStrahlDocument(scene, std::filesystem::absolute(file).parent_path());
}

}  // namespace

extern const SceneFormat kMitsubaSceneFormat{"Mitsuba 3 XML", kMitsubaExtensions,
                                             &mitsubaToDocument};

}  // namespace strahl::scene_detail
