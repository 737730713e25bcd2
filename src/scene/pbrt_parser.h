#pragma once
// Internal to the scene module: the pbrt-v4 scene language read into a flat
// description, with everything the language itself defines resolved — the
// tokens and parameter lists, Include and Import, the transform directives
// and the named coordinate systems, AttributeBegin/End and the graphics state
// (current material, area light, ReverseOrientation, Attribute defaults),
// named materials and textures, and ObjectBegin/End/ObjectInstance. What the
// shapes, materials and lights mean is pbrt_mapping.cpp's business.
// docs/pbrt.md.
//
// Transforms are pbrt's: points are column vectors, every directive
// post-multiplies the current transformation matrix (CTM = CTM · T), and the
// space is pbrt's own (left-handed camera space); the mapping mirrors it.

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace strahl::scene_detail::pbrt {

// Where something is written: "scene.pbrt:42" (the main file as named, an
// included one relative to the main file's folder).
struct Place {
    std::string file;
    int line = 0;
    std::string text() const { return file + ":" + std::to_string(line); }
};

// One entry of a parameter list: "float radius" [ 2 ].
struct Parameter {
    std::string type;  // as written: float, integer, rgb, point3, string, ...
    std::string name;
    std::vector<double> numbers;      // numeric types and bool (1/0)
    std::vector<std::string> strings; // string, texture, and spectrum given by name
    Place place;
    mutable bool used = false;  // read by the mapping; unread ones are errors
};

struct ParameterList {
    std::vector<Parameter> items;
    const Parameter* find(const std::string& name) const;
    // Adds the entries of `defaults` (Attribute directives) that this list
    // does not set itself.
    void addDefaults(const ParameterList& defaults);
};

// A directive with a type and parameters: Shape "sphere" ..., Material ...
struct Entity {
    std::string directive;  // "Shape", "Material", ...
    std::string type;       // "sphere"
    ParameterList params;
    Place place;
    // "Shape \"sphere\"" for messages.
    std::string element() const { return directive + " \"" + type + "\""; }
};

struct Texture {
    std::string name;
    std::string valueType;  // "float" or "spectrum"
    Entity entity;          // directive "Texture", type = the class (imagemap, ...)
};

struct Shape {
    Entity entity;
    glm::dmat4 toWorld{1.0};   // pbrt's render-from-object (or object-from-shape inside ObjectBegin)
    // An animated CTM (ActiveTransform EndTime): the transform at the end
    // time, `toWorld` being the start's. Top-level shapes only.
    std::optional<glm::dmat4> toWorldEnd;
    bool reverseOrientation = false;
    int material = -1;          // index into Scene::materials
    std::string materialName;   // NamedMaterial's name, resolved into `material` at the end
    int areaLight = -1;         // index into Scene::areaLights, or -1
};

struct Light {
    Entity entity;
    glm::dmat4 toWorld{1.0};
};

struct ObjectDefinition {
    std::string name;
    std::vector<Shape> shapes;
    Place place;
};

struct Instance {
    std::string object;
    glm::dmat4 toWorld{1.0};
    Place place;
    std::optional<glm::dmat4> toWorldEnd;  // animated, as Shape::toWorldEnd
};

struct Scene {
    std::optional<Entity> camera, film, sampler, integrator, filter;
    glm::dmat4 cameraFromWorld{1.0};
    double transformStart = 0.0, transformEnd = 1.0;  // TransformTimes: when the start and end CTMs hold
    std::vector<Entity> materials;  // index 0 is pbrt's default, diffuse 0.5
    std::map<std::string, int> namedMaterials;  // name -> index in materials
    std::vector<Entity> areaLights;
    std::map<std::string, Texture> floatTextures, spectrumTextures;
    std::vector<Shape> shapes;
    std::vector<Light> lights;
    std::map<std::string, ObjectDefinition> objects;
    std::vector<Instance> instances;
    std::filesystem::path folder;  // of the main file: relative names resolve here
    std::string label;             // how messages name the main file
};

// Throws strahl::Error "<file>:<line>: <what>" for a syntax error, an unknown
// directive, a parameter of an unknown type or with the wrong number of
// values, an unbalanced AttributeBegin/End or ObjectBegin/End, a missing or
// cyclic Include, an unknown named material, coordinate system or object,
// and for the features of the language strahl cannot render the same
// (a moving camera or light, animated shapes inside ObjectBegin,
// participating media, colour spaces other than sRGB), naming the directive.
// `file` anchors relative names; `label` names it in messages.
Scene readScene(const std::string& text, const std::filesystem::path& file, const std::string& label);

}  // namespace strahl::scene_detail::pbrt
