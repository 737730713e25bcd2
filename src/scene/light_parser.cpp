// One element of the scene file's "lights" (light_parser.h).

#include "light_parser.h"

#include <string>
#include <string_view>

#include "strahl/core/closed_family.h"
#include "texture_parser.h"

namespace strahl::scene_detail {

namespace fs = std::filesystem;

namespace {

// What a light kind's parse() reads the light object through: the object, the
// type name it was given (a kind may answer to several) and files resolved
// against the scene's folder.
class LightReader {
public:
    LightReader(const JsonValue& light, std::string_view name, const fs::path& folder)
        : light_(light), name_(name), folder_(folder) {}

    const JsonValue& json() const { return light_; }
    std::string_view name() const { return name_; }
    fs::path existingFile(const JsonValue& v, std::string_view noun) const {
        return resolveExistingFile(folder_, v, noun);
    }
    TextureRef imageTexture(const JsonValue& v) const { return parseImageTexture(v, folder_); }

private:
    const JsonValue& light_;
    std::string_view name_;
    const fs::path& folder_;
};

}  // namespace

LightDesc parseLight(const JsonValue& v, const fs::path& folder) {
    LightDesc l;
    l.where = v.pointer();
    static constexpr auto kTypes = kindNames<LightKind>();
    const std::string type = v.get("type").oneOf(kTypes);
    const LightReader reader(v, type, folder);
    l.light = *withKindNamed<LightKind>(type, [&](auto kind) -> LightKind {
        return decltype(kind)::type::parse(reader);
    });
    return l;
}

}  // namespace strahl::scene_detail
