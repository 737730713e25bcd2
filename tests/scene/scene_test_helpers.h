#pragma once
// Shared by the scene tests: JSON scene text parsed as "scene.json", the
// messages of its errors, and the naive-accel build options.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "strahl/core/math.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl::test {

// A shape list with one inline triangle, for tests about the other sections.
inline const std::string kTriangleShapes =
    R"("shapes": [{"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [0,1,2]}])";

// One inline triangle, a JSON shape object.
inline const std::string kTriangleShape =
    R"({"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [0,1,2]})";

// A JSON scene `text` parsed as "scene.json".
inline SceneDesc parseJson(const std::string& text) {
    return parseSceneText(text, "scene.json");
}

// The message of the strahl::Error that parsing `text` throws.
inline std::string parseError(const std::string& text) {
    return errorMessage([&] { parseJson(text); });
}

// The message of parsing a scene made of kTriangleShapes plus `sections`
// (comma-separated top-level members).
inline std::string errorWith(const std::string& sections) {
    return parseError("{" + sections + ", " + kTriangleShapes + "}");
}

// A scene whose only shapes are `shapes` (JSON objects, comma-separated).
inline std::string sceneWith(const std::string& shapes) {
    return R"({"shapes": [)" + shapes + "]}";
}

// sceneWith(shapes) parsed as `file`, and the message of the error that
// parsing it as "scene.json" throws.
inline SceneDesc parseShapes(const std::string& shapes,
                             const std::filesystem::path& file = "scene.json") {
    return parseSceneText(sceneWith(shapes), file);
}
inline std::string shapesError(const std::string& shapes) {
    return errorMessage([&] { parseShapes(shapes); });
}

// Build options for the naive (reference) accel.
inline BuildOptions naive() {
    BuildOptions options;
    options.accel = AccelKind::Naive;
    return options;
}

// Vectors equal to 1e-5 in every component.
inline void expectNear(const Vec3& actual, const Vec3& expected) {
    EXPECT_NEAR(actual.x, expected.x, 1e-5f);
    EXPECT_NEAR(actual.y, expected.y, 1e-5f);
    EXPECT_NEAR(actual.z, expected.z, 1e-5f);
}

}  // namespace strahl::test
