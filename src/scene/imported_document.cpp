// Pieces of the importers' documents (imported_document.h).

#include "imported_document.h"

#include "strahl/core/error.h"

namespace strahl::scene_detail {

using json = nlohmann::json;

json matrixTransform(const glm::dmat4& m) {
    json rows = json::array();
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) rows.push_back(r == 3 ? (c == 3 ? 1.0 : 0.0) : m[c][r]);
    return json::array({json{{"matrix", rows}}});
}

bool readsTextures(const json& value) {
    if (value.is_object()) {
        if (value.contains("texture") || value.contains("checkerboard") || value.contains("attribute"))
            return true;
        for (const auto& item : value.items())
            if (readsTextures(item.value())) return true;
    } else if (value.is_array()) {
        for (const json& item : value)
            if (readsTextures(item)) return true;
    }
    return false;
}

const json& materialNamed(const json& materials, const std::string& name) {
    for (const json& m : materials)
        if (m["name"] == name) return m;
    fail("internal: no material '", name, "' was made");
}

}  // namespace strahl::scene_detail
