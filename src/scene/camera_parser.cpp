// The scene file's "camera" (camera_parser.h).

#include "camera_parser.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#include <string>

#include "strahl/core/error.h"

namespace strahl::scene_detail {

namespace fs = std::filesystem;

namespace {

// Below this sine of the angle between up and the viewing axis, the camera frame
// is undefined.
constexpr float kMinUpSine = 1e-6f;


ImageWindow parseWindow(const JsonValue& value) {
    if (value.size() != 4)
        value.fail("expected an array of 4 numbers [l, r, b, t], got an array of ", value.size());
    ImageWindow w{value.at(0).number(), value.at(1).number(), value.at(2).number(),
                  value.at(3).number()};
    if (!(w.l < 0.0f && 0.0f < w.r && w.b < 0.0f && 0.0f < w.t))
        value.fail("must satisfy l < 0 < r and b < 0 < t, got [", w.l, ", ", w.r, ", ", w.b, ", ",
                   w.t, "]");
    return w;
}

// The thin lens keys and the shutter, which every camera takes.
void parseLensAndShutter(const JsonValue& v, CameraDesc& c) {
    if (auto shutter = v.find("shutter")) {
        const Vec2 s = shutter->vec2();
        if (!(0.0f <= s.x && s.x <= s.y && s.y <= 1.0f))
            shutter->fail("expected [open, close] in frame time with 0 <= open <= close <= 1, got ",
                          shutter->raw().dump());
        c.shutter = Shutter{s.x, s.y};
    }
    if (auto aperture = v.find("aperture_radius")) {
        c.apertureRadius = aperture->number();
        if (!(c.apertureRadius >= 0.0f))
            aperture->fail("must be at least 0, got ", aperture->raw().dump());
    }
    if (auto focus = v.find("focus_distance")) {
        const float f = focus->number();
        if (!(f > 0.0f)) focus->fail("must be greater than 0, got ", focus->raw().dump());
        c.focusDistance = f;
    }
}

// A camera a glTF file places: "gltf" names the file, "gltf_camera" the camera
// (an index among the placed cameras, or a camera's or node's name; default 0).
// The file is read, and the choice checked against it, when the world is built.
CameraDesc parseGltfCamera(const JsonValue& v, const fs::path& folder) {
    v.requireKeys({"gltf", "gltf_camera", "aperture_radius", "focus_distance", "shutter"});
    const JsonValue file = v.get("gltf");
    GltfCameraChoice choice;
    choice.file = resolveExistingFile(folder, file, "glTF file");
    choice.fileAt = file.place();
    choice.cameraAt = {file.place().label, v.pointer() + "/gltf_camera"};
    if (auto which = v.find("gltf_camera")) {
        if (which->raw().is_string()) {
            choice.byName = true;
            choice.name = which->string();
        } else {
            // Any integer here; its range is known once the file is read.
            choice.index = which->integerOrNone();
            choice.indexText = which->raw().dump();
        }
    }
    CameraDesc c;
    c.gltf = std::move(choice);
    parseLensAndShutter(v, c);
    return c;
}

}  // namespace

CameraDesc parseCamera(const JsonValue& v, const fs::path& folder) {
    if (v.has("gltf")) return parseGltfCamera(v, folder);
    v.requireKeys({"type", "eye", "look_at", "back", "up", "focal_distance", "fov", "window",
                   "aperture_radius", "focus_distance", "shutter"});
    CameraDesc c;
    if (auto type = v.find("type"))
        c.projection = type->oneOf({"perspective", "orthographic"}) == "perspective"
                           ? Projection::Perspective
                           : Projection::Orthographic;
    if (auto eye = v.find("eye")) c.eye = eye->vec3();

    // The back axis w, from "back" or from the eye and "look_at".
    if (v.has("look_at") && v.has("back")) v.fail("'look_at' and 'back' are exclusive: give one");
    Vec3 w;
    if (auto back = v.find("back")) {
        c.back = back->vec3();
        if (*c.back == Vec3(0.0f)) back->fail("must be non-zero");
        w = *c.back;
    } else {
        auto lookAt = v.find("look_at");
        c.lookAt = lookAt ? lookAt->vec3() : Vec3(0.0f);
        w = c.eye - *c.lookAt;
        const JsonValue& where = lookAt ? *lookAt : v;
        if (w == Vec3(0.0f)) where.fail("the camera looks at its own eye position");
        if (!isFinite(w)) where.fail("eye - look_at exceeds the float range");
    }
    if (auto up = v.find("up")) {
        c.up = up->vec3();
        if (c.up == Vec3(0.0f)) up->fail("must be non-zero");
        if (glm::length(glm::cross(unitVector(w), unitVector(c.up))) < kMinUpSine)
            up->fail("is parallel to the viewing direction");
    } else if (glm::length(glm::cross(unitVector(w), c.up)) < kMinUpSine) {
        v.fail("the viewing direction is vertical: give an 'up' not parallel to it");
    }

    if (auto d = v.find("focal_distance")) {
        c.focalDistance = d->number();
        if (!(c.focalDistance > 0.0f)) d->fail("must be greater than 0, got ", d->raw().dump());
    }
    if (auto fov = v.find("fov")) {
        if (c.projection != Projection::Perspective)
            fov->fail("only for a perspective camera (this one is orthographic)");
        if (v.has("window")) v.fail("'fov' and 'window' are exclusive: give one");
        const float degrees = fov->number();
        if (!(degrees > 0.0f && degrees < 180.0f))
            fov->fail("must be greater than 0 and less than 180, got ", fov->raw().dump());
        c.fovYDegrees = degrees;
    }
    if (auto window = v.find("window")) c.window = parseWindow(*window);
    parseLensAndShutter(v, c);

    if (!c.fovYDegrees && !c.window) {
        if (c.projection == Projection::Perspective)
            c.fovYDegrees = 45.0f;
        else
            c.window = ImageWindow{};
    }
    return c;
}

}  // namespace strahl::scene_detail
