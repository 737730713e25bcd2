// Scene file (JSON with comments) to SceneDesc. The format is documented key by
// key in docs/scene-format.md; this file checks every value it reads and names
// the JSON pointer of anything it rejects. Mesh, texture and environment files
// are only checked to exist; three kinds of file are read here, because their
// content is part of the description and their errors must name its place: a
// glTF file's cameras (a camera chosen from it), Bézier patch files (.bpt) and
// height images of parametric shapes (whose surfaces are built at parse time).

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <memory>
#include <span>
#include <string_view>

#include "implicit_parser.h"
#include "instance_arrays.h"
#include "instance_flattening.h"
#include "parametric_parser.h"
#include "scene_json.h"
#include "json_reader.h"
#include "material_parser.h"
#include "transform_parser.h"
#include "strahl/core/error.h"
#include "strahl/core/filter.h"
#include "strahl/film/image_output.h"
#include "strahl/integrator/integrator.h"
#include "strahl/meshio/gltf_camera.h"
#include "strahl/core/closed_family.h"
#include "strahl/scene/scene_desc.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using scene_detail::JsonValue;
using scene_detail::joinList;
using scene_detail::parseTransform;
using scene_detail::resolveExistingFile;
using scene_detail::resolvePath;

constexpr int64_t kMaxSpp = 65536;
// Below this sine of the angle between up and the viewing axis, the camera frame
// is undefined.
constexpr float kMinUpSine = 1e-6f;

bool hasExtension(const fs::path& path, std::span<const std::string_view> extensions) {
    std::string ext = path.extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    for (std::string_view allowed : extensions) {
        if (ext == allowed) return true;
    }
    return false;
}

// --- camera --------------------------------------------------------------------

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

// The thin lens keys, which every camera takes.
void parseLens(const JsonValue& v, CameraDesc& c) {
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
CameraDesc parseGltfCamera(const JsonValue& v, const fs::path& folder) {
    v.requireKeys({"gltf", "gltf_camera", "aperture_radius", "focus_distance"});
    const JsonValue file = v.get("gltf");
    const fs::path path = resolveExistingFile(folder, file, "glTF file");
    std::vector<GltfCamera> cameras;
    try {
        cameras = loadGltfCameras(path);
    } catch (const Error& e) {
        file.fail(e.what());
    }
    if (cameras.empty()) file.fail(path.filename().string(), " places no camera in its scene");
    size_t chosen = 0;
    if (auto which = v.find("gltf_camera")) {
        if (which->raw().is_string()) {
            const std::string name = which->string();
            const auto found = std::find_if(cameras.begin(), cameras.end(),
                                            [&](const GltfCamera& c) { return c.name == name; });
            if (found == cameras.end()) {
                std::string names;
                for (const GltfCamera& c : cameras) names += (names.empty() ? "" : ", ") + c.name;
                which->fail("no camera named '", name, "' (the file has: ", names, ")");
            }
            chosen = size_t(found - cameras.begin());
        } else {
            chosen = size_t(which->unsignedInteger(cameras.size() - 1));
        }
    }
    const GltfCamera& g = cameras[chosen];
    CameraDesc c;
    c.eye = g.eye;
    c.back = g.back;
    c.up = g.up;
    if (g.orthographic) {
        c.projection = Projection::Orthographic;
        c.window = ImageWindow{-g.xmag, g.xmag, -g.ymag, g.ymag};
    } else {
        c.fovYDegrees = g.yfovDegrees;
    }
    parseLens(v, c);
    return c;
}

CameraDesc parseCamera(const JsonValue& v, const fs::path& folder) {
    if (v.has("gltf")) return parseGltfCamera(v, folder);
    v.requireKeys({"type", "eye", "look_at", "back", "up", "focal_distance", "fov", "window",
                   "aperture_radius", "focus_distance"});
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
    parseLens(v, c);

    if (!c.fovYDegrees && !c.window) {
        if (c.projection == Projection::Perspective)
            c.fovYDegrees = 45.0f;
        else
            c.window = ImageWindow{};
    }
    return c;
}

// --- film and render -----------------------------------------------------------

FilmDesc parseFilm(const JsonValue& v, const fs::path& folder) {
    v.requireKeys({"width", "height", "outputs", "aovs", "exr_float", "filter"});
    FilmDesc f;
    if (auto width = v.find("width")) f.width = static_cast<int>(width->integer(1, kMaxFilmSide));
    if (auto height = v.find("height"))
        f.height = static_cast<int>(height->integer(1, kMaxFilmSide));
    if (int64_t(f.width) * f.height > kMaxFilmPixels)
        v.fail("width x height = ", int64_t(f.width) * f.height, " pixels, more than the limit of ",
               kMaxFilmPixels, " (2^28)");

    if (auto outputs = v.find("outputs")) {
        for (size_t i = 0; i < outputs->size(); ++i) {
            const JsonValue output = outputs->at(i);
            fs::path path = resolvePath(folder, output);
            if (!hasExtension(path, supportedImageExtensions()))
                output.fail("'", path.filename().string(), "' is not a supported image format ",
                            "(extensions: ", joinList(supportedImageExtensions()), ")");
            f.outputs.push_back(std::move(path));
        }
    }
    if (auto aovs = v.find("aovs")) {
        for (size_t i = 0; i < aovs->size(); ++i) {
            const JsonValue aov = aovs->at(i);
            const std::string name = aov.oneOf(aovNames());
            const AovKind kind = *aovFromName(name);
            if (std::find(f.aovs.begin(), f.aovs.end(), kind) != f.aovs.end())
                aov.fail("'", name, "' is listed twice");
            f.aovs.push_back(kind);
        }
    }
    if (auto exrFloat = v.find("exr_float")) f.exrFloat = exrFloat->boolean();
    if (auto filter = v.find("filter")) {
        if (filter->raw().is_object()) {
            filter->requireKeys({"type", "radius"});
            f.filter = filter->get("type").oneOf(PixelFilter::names());
            if (auto radius = filter->find("radius")) {
                const float r = radius->number();
                // Beyond 16 pixels a filter is a blur, not an antialiasing filter.
                if (!(r > 0.0f && r <= 16.0f))
                    radius->fail("must be greater than 0 and at most 16 pixels, got ",
                                 radius->raw().dump());
                f.filterRadius = r;
            }
        } else {
            f.filter = filter->oneOf(PixelFilter::names());
        }
    }
    return f;
}

RenderDesc parseRender(const JsonValue& v) {
    v.requireKeys({"integrator", "spp", "seed", "max_depth", "russian_roulette", "ao_distance",
                   "ao_samples"});
    RenderDesc r;
    if (auto integrator = v.find("integrator"))
        r.integrator = integrator->oneOf(integratorNames());
    if (auto spp = v.find("spp")) r.spp = static_cast<int>(spp->integer(1, kMaxSpp));
    if (auto seed = v.find("seed"))
        r.seed = seed->unsignedInteger(std::numeric_limits<uint64_t>::max());
    // Paths longer than 1024 bounces carry no measurable energy.
    if (auto depth = v.find("max_depth")) r.maxDepth = static_cast<int>(depth->integer(0, 1024));
    if (auto rr = v.find("russian_roulette")) r.russianRoulette = rr->boolean();
    if (auto distance = v.find("ao_distance")) {
        r.aoDistance = distance->number();
        if (!(r.aoDistance >= 0.0f)) distance->fail("must be non-negative, got ", r.aoDistance);
    }
    if (auto samples = v.find("ao_samples")) r.aoSamples = static_cast<int>(samples->integer(1, 4096));
    return r;
}

// --- shapes --------------------------------------------------------------------

void checkMeshFile(const JsonValue& value, const fs::path& path) {
    std::error_code ec;
    const std::string given = value.string();
    if (!fs::exists(path, ec))
        value.fail("no such file '", given, "' (looked at ", path.string(), ")");
    if (!fs::is_regular_file(path, ec))
        value.fail("'", given, "' is not a regular file (looked at ", path.string(), ")");
    constexpr std::string_view kMeshExtensions[] = {".obj", ".ply", ".gltf", ".glb"};
    if (!hasExtension(path, kMeshExtensions))
        value.fail("'", given,
                   "' is not a supported mesh format (extensions: .obj, .ply, .gltf, .glb)");
}

TriangleMesh parseInlineMesh(const JsonValue& v, const std::string& label) {
    TriangleMesh mesh;
    const JsonValue positions = v.get("positions");
    mesh.positions.reserve(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) mesh.positions.push_back(positions.at(i).vec3());

    const JsonValue indices = v.get("indices");
    if (indices.size() == 0) indices.fail("must contain at least one triangle");
    if (indices.size() % 3 != 0)
        indices.fail("has ", indices.size(), " entries, not a multiple of 3 (triangles only)");
    mesh.indices.reserve(indices.size());
    for (size_t i = 0; i < indices.size(); ++i) {
        mesh.indices.push_back(static_cast<uint32_t>(
            indices.at(i).unsignedInteger(std::numeric_limits<uint32_t>::max())));
    }
    if (auto normals = v.find("normals")) {
        for (size_t i = 0; i < normals->size(); ++i) mesh.normals.push_back(normals->at(i).vec3());
    }
    if (auto uvs = v.find("uvs")) {
        for (size_t i = 0; i < uvs->size(); ++i) mesh.uvs.push_back(uvs->at(i).vec2());
    }
    mesh.validate(concat(label, ": ", v.pointer()));
    return mesh;
}

void parseMeshSource(const JsonValue& v, const fs::path& folder, const std::string& label,
                     ShapeDesc& s);

// What a shape may refer to by name.
struct ShapeContext {
    fs::path folder;
    std::string label;
    const std::vector<MaterialDesc>& materials;
    std::span<const std::string> groupNames;
};

// The "scatter" object of an instance array.
scene_detail::Scatter parseScatter(const JsonValue& v) {
    v.requireKeys({"count", "seed", "min", "max", "height", "yaw", "scale"});
    scene_detail::Scatter scatter;
    scatter.count = v.get("count").unsignedInteger(scene_detail::kMaxInstances);
    if (scatter.count == 0) v.get("count").fail("an instance array needs at least one placement");
    if (auto seed = v.find("seed")) scatter.seed = seed->unsignedInteger(UINT64_MAX);
    scatter.min = v.get("min").vec2();
    scatter.max = v.get("max").vec2();
    if (!(scatter.min.x <= scatter.max.x && scatter.min.y <= scatter.max.y))
        v.get("max").fail("must not be below 'min' in x or z");
    if (auto height = v.find("height")) scatter.height = height->number();
    if (auto yaw = v.find("yaw")) {
        const Vec2 range = yaw->vec2();
        if (!(range.x <= range.y)) yaw->fail("expected [from, to] degrees with from <= to");
        scatter.yawMin = range.x;
        scatter.yawMax = range.y;
    }
    if (auto scale = v.find("scale")) {
        const Vec2 range = scale->vec2();
        if (!(range.x > 0.0f && range.x <= range.y))
            scale->fail("expected [from, to] with 0 < from <= to");
        scatter.scaleMin = range.x;
        scatter.scaleMax = range.y;
    }
    return scatter;
}

ShapeDesc parseShape(const JsonValue& v, const ShapeContext& context) {
    const fs::path& folder = context.folder;
    const std::string& label = context.label;
    const std::vector<MaterialDesc>& materials = context.materials;
    ShapeDesc s;
    s.where = v.pointer();
    if (!v.raw().is_object()) v.fail("expected an object, got ", v.describe());
    const std::string type = v.get("type").oneOf({"mesh", "implicit", "parametric", "instance"});
    if (type == "instance") {
        v.requireKeys({"type", "name", "group", "transform", "placements", "scatter"});
        s.kind = ShapeKind::Instance;
        const JsonValue group = v.get("group");
        const std::string groupName = group.string();
        const auto found = std::find(context.groupNames.begin(), context.groupNames.end(), groupName);
        if (found == context.groupNames.end()) {
            std::string defined;
            for (const std::string& name : context.groupNames)
                defined += (defined.empty() ? "" : ", ") + name;
            group.fail("unknown group '", groupName, "' (defined: ",
                       defined.empty() ? "none" : defined, ")");
        }
        s.group = static_cast<size_t>(found - context.groupNames.begin());
        s.name = s.where;
        if (auto name = v.find("name")) s.name = name->string();
        if (auto transform = v.find("transform")) s.transform = parseTransform(*transform);
        const auto file = v.find("placements");
        const auto scatter = v.find("scatter");
        if (file && scatter) v.fail("give 'placements' or 'scatter', not both");
        if (file) {
            const fs::path path = resolveExistingFile(folder, *file, "placement file");
            try {
                s.placements = scene_detail::readPlacementFile(path, scene_detail::kMaxInstances);
            } catch (const Error& e) {
                file->fail(e.what());
            }
        }
        if (scatter) s.placements = scene_detail::scatterPlacements(parseScatter(*scatter));
        return s;
    }
    if (type == "implicit") {
        v.requireKeys({"type", "name", "material", "transform", "surface", "box", "cells",
                       "tolerance"});
        s.kind = ShapeKind::Implicit;
        scene_detail::parseImplicitShape(v, s.implicitSurface, s.implicitOptions);
        s.name = s.where;
    } else if (type == "parametric") {
        v.requireKeys({"type", "name", "material", "transform", "surface", "mode", "tessellation",
                       "direct"});
        s.kind = ShapeKind::Parametric;
        s.parametric = scene_detail::parseParametricShape(v, folder);
        s.name = s.where;
    } else {
        v.requireKeys({"type", "name", "file", "positions", "indices", "normals", "uvs",
                       "material", "transform"});
        parseMeshSource(v, folder, label, s);
    }
    if (auto name = v.find("name")) s.name = name->string();

    if (auto material = v.find("material")) {
        s.material = material->string();
        const bool known = s.material.empty() || s.material == "default" ||
                           std::any_of(materials.begin(), materials.end(),
                                       [&](const MaterialDesc& m) { return m.name == s.material; });
        if (!known) {
            std::string defined;
            for (const MaterialDesc& m : materials) defined += m.name + ", ";
            material->fail("unknown material '", s.material, "' (defined: ", defined, "default)");
        }
    }
    if (s.material.empty() && s.file.empty()) s.material = "default";

    if (auto transform = v.find("transform")) s.transform = parseTransform(*transform);
    return s;
}

// The mesh of a "mesh" shape: a file, or inline arrays.
void parseMeshSource(const JsonValue& v, const fs::path& folder, const std::string& label,
                     ShapeDesc& s) {
    const auto file = v.find("file");
    if (file && v.has("positions")) v.fail("'file' and 'positions' are exclusive: give one");
    if (file) {
        for (std::string_view key : {"indices", "normals", "uvs"}) {
            if (auto extra = v.find(key))
                extra->fail("only for inline meshes (with 'positions'), not with 'file'");
        }
        s.file = resolvePath(folder, *file);
        checkMeshFile(*file, s.file);
        s.name = s.file.stem().string();
    } else if (v.has("positions")) {
        s.inlineMesh = parseInlineMesh(v, label);
        s.name = s.where;
    } else {
        v.fail("needs 'file' (a mesh file) or 'positions' (an inline mesh)");
    }
}

// --- groups --------------------------------------------------------------------

// The names of "groups", checked unique and non-empty, in order: shapes refer
// to groups by name, also to groups defined later in the list.
std::vector<std::string> parseGroupNames(const JsonValue& groups) {
    std::vector<std::string> names;
    for (size_t i = 0; i < groups.size(); ++i) {
        const JsonValue g = groups.at(i);
        if (!g.raw().is_object()) g.fail("expected an object, got ", g.describe());
        const JsonValue name = g.get("name");
        std::string text = name.string();
        if (text.empty()) name.fail("must not be empty");
        const auto earlier = std::find(names.begin(), names.end(), text);
        if (earlier != names.end())
            name.fail("group '", text, "' is already defined at ", groups.pointer(), "/",
                      earlier - names.begin());
        names.push_back(std::move(text));
    }
    return names;
}

// Rejects groups that place themselves, directly or through others, and
// chains of groups nested deeper than kMaxGroupNesting. Depth-first over the
// "instance" shapes; `path` is the chain of groups being expanded.
void checkGroupNesting(const SceneDesc& scene, size_t group, std::vector<size_t>& path,
                       std::vector<bool>& done, const std::string& label) {
    if (done[group]) return;
    const auto cycleStart = std::find(path.begin(), path.end(), group);
    if (cycleStart != path.end()) {
        std::string chain;
        for (auto it = cycleStart; it != path.end(); ++it) chain += scene.groups[*it].name + " -> ";
        fail(label, ": ", scene.groups[group].where, ": group '", scene.groups[group].name,
             "' places itself (", chain, scene.groups[group].name, ")");
    }
    if (path.size() >= static_cast<size_t>(kMaxGroupNesting))
        fail(label, ": ", scene.groups[group].where, ": groups nest more than ", kMaxGroupNesting,
             " levels deep");
    path.push_back(group);
    for (const ShapeDesc& shape : scene.groups[group].shapes) {
        if (shape.kind == ShapeKind::Instance) checkGroupNesting(scene, shape.group, path, done, label);
    }
    path.pop_back();
    done[group] = true;
}

std::vector<GroupDesc> parseGroups(const JsonValue& groups, const ShapeContext& context) {
    std::vector<GroupDesc> result;
    for (size_t i = 0; i < groups.size(); ++i) {
        const JsonValue g = groups.at(i);
        g.requireKeys({"name", "shapes"});
        GroupDesc group;
        group.name = context.groupNames[i];
        group.where = g.pointer();
        const JsonValue shapes = g.get("shapes");
        if (shapes.size() == 0) shapes.fail("a group needs at least one shape");
        for (size_t j = 0; j < shapes.size(); ++j)
            group.shapes.push_back(parseShape(shapes.at(j), context));
        result.push_back(std::move(group));
    }
    return result;
}

// --- lights --------------------------------------------------------------------

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

private:
    const JsonValue& light_;
    std::string_view name_;
    const fs::path& folder_;
};

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

}  // namespace

SceneDesc scene_detail::parseSceneJson(const nlohmann::json& document, const fs::path& file,
                                       const std::string& label) {
    const JsonValue root(document, "", label);
    root.requireKeys(
        {"camera", "film", "render", "background", "materials", "groups", "shapes", "lights"});

    SceneDesc scene;
    scene.file = file;
    const fs::path folder = scene.file.parent_path();

    // The camera's defaults depend on each other, so it is parsed even when absent.
    const nlohmann::json noCamera = nlohmann::json::object();
    scene.camera =
        parseCamera(root.find("camera").value_or(JsonValue(noCamera, "/camera", label)), folder);
    if (auto film = root.find("film")) scene.film = parseFilm(*film, folder);
    if (auto render = root.find("render")) scene.render = parseRender(*render);
    if (auto background = root.find("background")) scene.background = background->color();
    if (auto materials = root.find("materials"))
        scene.materials = scene_detail::parseMaterials(*materials, folder);

    const auto groups = root.find("groups");
    const std::vector<std::string> groupNames =
        groups ? parseGroupNames(*groups) : std::vector<std::string>();
    const ShapeContext context{folder, label, scene.materials, groupNames};
    if (groups) {
        scene.groups = parseGroups(*groups, context);
        std::vector<size_t> path;
        std::vector<bool> done(scene.groups.size(), false);
        for (size_t g = 0; g < scene.groups.size(); ++g)
            checkGroupNesting(scene, g, path, done, label);
    }

    const auto shapes = root.find("shapes");
    if (!shapes || shapes->size() == 0) fail(label, ": scene has no shapes");
    for (size_t i = 0; i < shapes->size(); ++i)
        scene.shapes.push_back(parseShape(shapes->at(i), context));

    if (auto lights = root.find("lights")) {
        for (size_t i = 0; i < lights->size(); ++i)
            scene.lights.push_back(parseLight(lights->at(i), folder));
    }
    return scene;
}

}  // namespace strahl
