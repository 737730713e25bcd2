// Scene document to SceneDesc: the top level, the shapes and the groups here;
// the camera, film and render settings, materials and lights in their own
// *_parser.cpp files. The format is documented key by key in
// docs/scene-format.md; every value read is checked, and anything rejected is
// named by its JSON pointer. No other file is read here: mesh, texture and
// environment files, a glTF camera's file, Bézier patch files and height
// images are named (and most checked to exist) with their place, and read
// when the world is built (scene_builder.h), whose errors name the same place.

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <string_view>

#include "camera_parser.h"
#include "film_parser.h"
#include "curve_parser.h"
#include "subdivision_parser.h"
#include "implicit_parser.h"
#include "instance_arrays.h"
#include "instance_flattening.h"
#include "json_reader.h"
#include "light_parser.h"
#include "material_parser.h"
#include "parametric_parser.h"
#include "scene_json.h"
#include "transform_parser.h"
#include "strahl/core/error.h"
#include "strahl/core/motion.h"
#include "strahl/geometry/loop_subdivision.h"
#include "strahl/meshio/mesh_format.h"
#include "strahl/scene/scene_desc.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using scene_detail::JsonValue;
using scene_detail::parseCamera;
using scene_detail::parseFilm;
using scene_detail::parseLight;
using scene_detail::parseRender;
using scene_detail::joinList;
using scene_detail::parseTransform;
using scene_detail::resolveExistingFile;
using scene_detail::resolvePath;

// --- shapes --------------------------------------------------------------------

void checkMeshFile(const JsonValue& value, const fs::path& path) {
    std::error_code ec;
    const std::string given = value.string();
    if (!fs::exists(path, ec))
        value.fail("no such file '", given, "' (looked at ", path.string(), ")");
    if (!fs::is_regular_file(path, ec))
        value.fail("'", given, "' is not a regular file (looked at ", path.string(), ")");
    if (!findMeshFormat(path))
        value.fail("'", given, "' is not a supported mesh format (extensions: ",
                   meshExtensionList(", ", ", "), ")");
}

// An element [x, y, z] of finite float numbers, read without building its
// JSON pointer (large inline meshes: an imported pbrt trianglemesh has
// millions); false sends the caller to JsonValue::at(i).vec3(), which
// reports the error.
bool readVec3Directly(const nlohmann::json& e, Vec3& out) {
    if (!e.is_array() || e.size() != 3) return false;
    for (int k = 0; k < 3; ++k) {
        if (!e[k].is_number()) return false;
        out[k] = static_cast<float>(e[k].get<double>());
        if (!std::isfinite(out[k])) return false;
    }
    return true;
}

TriangleMesh parseInlineMesh(const JsonValue& v, const std::string& label) {
    TriangleMesh mesh;
    const JsonValue positions = v.get("positions");
    mesh.positions.reserve(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        Vec3 p;
        mesh.positions.push_back(readVec3Directly(positions.raw()[i], p) ? p : positions.at(i).vec3());
    }

    const JsonValue indices = v.get("indices");
    if (indices.size() == 0) indices.fail("must contain at least one triangle");
    if (indices.size() % 3 != 0)
        indices.fail("has ", indices.size(), " entries, not a multiple of 3 (triangles only)");
    mesh.indices.reserve(indices.size());
    for (size_t i = 0; i < indices.size(); ++i) {
        const nlohmann::json& e = indices.raw()[i];
        if (e.is_number_unsigned() && e.get<uint64_t>() <= std::numeric_limits<uint32_t>::max()) {
            mesh.indices.push_back(static_cast<uint32_t>(e.get<uint64_t>()));
            continue;
        }
        mesh.indices.push_back(static_cast<uint32_t>(
            indices.at(i).unsignedInteger(std::numeric_limits<uint32_t>::max())));
    }
    if (auto deform = v.find("deform")) {
        // Keyframes 1 … K − 1 of the positions (`positions` is keyframe 0).
        if (deform->size() < 1 || deform->size() + 1 > kMaxKeyframes)
            deform->fail("expected an array of 1 to ", kMaxKeyframes - 1,
                         " keyframes of the positions (after 'positions'), got ", deform->size());
        for (size_t k = 0; k < deform->size(); ++k) {
            const JsonValue key = deform->at(k);
            if (!key.raw().is_array() || key.size() != mesh.positions.size())
                key.fail("expected ", mesh.positions.size(), " positions (as many as 'positions'), got ",
                         key.raw().is_array() ? concat(key.size()) : key.describe());
            std::vector<Vec3>& list = mesh.laterPositions.emplace_back();
            list.reserve(key.size() + 1);  // Embree's padding
            for (size_t i = 0; i < key.size(); ++i) {
                Vec3 p;
                list.push_back(readVec3Directly(key.raw()[i], p) ? p : key.at(i).vec3());
            }
        }
    }
    if (auto normals = v.find("normals"); normals && normals->raw().is_array()) {
        if (v.has("deform"))
            normals->fail("a deforming mesh's normals follow it: give \"normals\": \"smooth\" (computed at every "
                          "keyframe) or none");
        mesh.normals.reserve(normals->size());
        for (size_t i = 0; i < normals->size(); ++i) {
            Vec3 n;
            mesh.normals.push_back(readVec3Directly(normals->raw()[i], n) ? n : normals->at(i).vec3());
        }
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

// "motion": keyframes equally spaced over frame time [0, 1], each a transform
// as "transform" takes; at most kMaxKeyframes (Embree's limit).
std::vector<Mat4> parseMotion(const JsonValue& v) {
    if (!v.raw().is_array() || v.size() < 2 || v.size() > kMaxKeyframes)
        v.fail("expected an array of 2 to ", kMaxKeyframes, " keyframe transforms, got ",
               v.raw().is_array() ? concat("an array of ", v.size()) : v.describe());
    std::vector<Mat4> keys;
    for (size_t k = 0; k < v.size(); ++k) keys.push_back(parseTransform(v.at(k)));
    return keys;
}

ShapeDesc parseShape(const JsonValue& v, const ShapeContext& context) {
    const fs::path& folder = context.folder;
    const std::string& label = context.label;
    const std::vector<MaterialDesc>& materials = context.materials;
    ShapeDesc s;
    s.where = v.pointer();
    if (!v.raw().is_object()) v.fail("expected an object, got ", v.describe());
    const std::string type =
        v.get("type").oneOf({"mesh", "implicit", "parametric", "curves", "subdivision", "instance"});
    if (type == "instance") {
        v.requireKeys({"type", "name", "group", "transform", "motion", "placements", "scatter"});
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
        if (auto motion = v.find("motion")) {
            if (v.has("transform")) v.fail("give 'transform' (at rest) or 'motion' (keyframes), not both");
            s.motion = parseMotion(*motion);
        }
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
        v.requireKeys({"type", "name", "material", "transform", "motion", "surface", "box", "cells",
                       "tolerance"});
        s.kind = ShapeKind::Implicit;
        scene_detail::parseImplicitShape(v, s.implicitSurface, s.implicitOptions);
        s.name = s.where;
    } else if (type == "curves") {
        scene_detail::parseCurvesShape(v, folder, s);
    } else if (type == "subdivision") {
        scene_detail::parseSubdivisionShape(v, folder, s);
    } else if (type == "parametric") {
        v.requireKeys({"type", "name", "material", "transform", "motion", "surface", "mode", "tessellation",
                       "direct", "flip_normals"});
        s.kind = ShapeKind::Parametric;
        s.parametric = scene_detail::parseParametricShape(v, folder);
        s.name = s.where;
        if (auto flip = v.find("flip_normals")) s.flipNormals = flip->boolean();
    } else {
        v.requireKeys({"type", "name", "file", "positions", "indices", "normals", "uvs",
                       "material", "transform", "motion", "flip_normals", "shape_index", "subdivision", "deform"});
        parseMeshSource(v, folder, label, s);
        if (auto flip = v.find("flip_normals")) s.flipNormals = flip->boolean();
        if (auto index = v.find("shape_index")) {
            if (s.file.extension() != ".serialized")
                index->fail("only for a .serialized file, which may hold several meshes");
            s.shapeIndex = static_cast<uint32_t>(index->integer(0, 1u << 30));
        }
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
    if (s.material.empty() && (s.file.empty() || s.kind == ShapeKind::Curves || s.kind == ShapeKind::Subdivision))
        s.material = "default";

    if (auto transform = v.find("transform")) s.transform = parseTransform(*transform);
    if (auto motion = v.find("motion")) {  // wrapped in an instance by wrapMovingShapes
        if (v.has("transform")) v.fail("give 'transform' (at rest) or 'motion' (keyframes), not both");
        s.motion = parseMotion(*motion);
    }
    return s;
}

// A shape that moves is a moving instance of a group of its own: Embree moves
// instances, not meshes or user shapes. Each shape with "motion" (other than
// an instance) becomes the one shape of a new group, named after it, placed
// by an instance with its keyframes.
void wrapMovingShapes(SceneDesc& scene) {
    auto wrap = [&scene](ShapeDesc& shape) {
        if (shape.kind == ShapeKind::Instance || shape.motion.empty()) return;
        GroupDesc group;
        group.name = concat(shape.name, " (moving)");
        group.where = shape.where;
        ShapeDesc instance;
        instance.kind = ShapeKind::Instance;
        instance.name = shape.name;
        instance.where = shape.where;
        instance.motion = std::move(shape.motion);
        instance.group = scene.groups.size();
        shape.motion.clear();
        group.shapes.push_back(std::move(shape));
        shape = std::move(instance);
        scene.groups.push_back(std::move(group));
    };
    for (ShapeDesc& shape : scene.shapes) wrap(shape);
    const size_t declared = scene.groups.size();  // (the new groups hold no moving shapes)
    for (size_t g = 0; g < declared; ++g)
        for (size_t i = 0; i < scene.groups[g].shapes.size(); ++i) wrap(scene.groups[g].shapes[i]);
}

// The mesh of a "mesh" shape: a file, or inline arrays.
void parseMeshSource(const JsonValue& v, const fs::path& folder, const std::string& label,
                     ShapeDesc& s) {
    const auto file = v.find("file");
    if (file && v.has("positions")) v.fail("'file' and 'positions' are exclusive: give one");
    if (file) {
        for (std::string_view key : {"indices", "uvs", "subdivision", "deform"}) {
            if (auto extra = v.find(key))
                extra->fail("only for inline meshes (with 'positions'), not with 'file'");
        }
        if (auto normals = v.find("normals")) {
            if (!normals->raw().is_string())
                normals->fail("with 'file': \"file\", \"flat\" or \"smooth\" (an array of "
                              "normals is for inline meshes)");
            const std::string n = normals->oneOf({"file", "flat", "smooth"});
            s.fileNormals = n == "flat"     ? ShapeDesc::FileNormals::Flat
                            : n == "smooth" ? ShapeDesc::FileNormals::Smooth
                                            : ShapeDesc::FileNormals::AsGiven;
        }
        s.file = resolvePath(folder, *file);
        checkMeshFile(*file, s.file);
        s.name = s.file.stem().string();
    } else if (v.has("positions")) {
        s.inlineMesh = parseInlineMesh(v, label);
        s.name = s.where;
        if (auto normals = v.find("normals"); normals && !normals->raw().is_array()) {
            // "smooth": computed (angle-weighted, at every keyframe of a
            // deforming mesh) after the transform; "flat": none.
            const std::string n = normals->oneOf({"flat", "smooth"});
            s.fileNormals = n == "smooth" ? ShapeDesc::FileNormals::Smooth : ShapeDesc::FileNormals::Flat;
        }
        if (auto subdivision = v.find("subdivision")) {
            // {"scheme": "loop", "levels": n}: the control mesh subdivided
            // (geometry/loop_subdivision.h), with its own smooth normals.
            subdivision->requireKeys({"scheme", "levels"});
            subdivision->get("scheme").oneOf({"loop"});
            int levels = 3;
            if (auto l = subdivision->find("levels")) levels = static_cast<int>(l->integer(0, kMaxLoopLevels));
            for (std::string_view key : {"normals", "uvs", "deform"})
                if (auto extra = v.find(key)) extra->fail("not with 'subdivision' (the subdivided mesh has its own)");
            s.inlineMesh = loopSubdivide(s.inlineMesh, levels, concat(label, ": ", subdivision->pointer()));
        }
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
    wrapMovingShapes(scene);

    if (auto lights = root.find("lights")) {
        for (size_t i = 0; i < lights->size(); ++i)
            scene.lights.push_back(parseLight(lights->at(i), folder));
    }
    return scene;
}

}  // namespace strahl
