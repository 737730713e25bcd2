#pragma once
// Internal to the scene module: the Mitsuba 3 scene language (XML) read into
// a tree of plugin objects, with everything the language itself defines
// resolved: <default> parameters (overridden by -D) substituted for $name in
// every attribute, <include>d files spliced in (cycles refused), <path>
// folders kept for finding files, objects given an id placed where a <ref>
// names them, <transform> operations composed into one matrix, and the
// property types (integer, float, boolean, string, point, vector, rgb,
// spectrum) read with their place. What the plugins mean is
// mitsuba_plugins.cpp's business. docs/mitsuba.md.

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace strahl::scene_detail::mitsuba {

// -D name=value: values for <default> parameters.
using Defines = std::map<std::string, std::string>;

// Where something is written: "scene.xml:42" (the file as named, or
// relative to the scene's folder for an included one).
struct Place {
    std::string file;
    int line = 0;
    std::string text() const { return file + ":" + std::to_string(line); }
};

struct Property {
    std::string tag;    // integer, float, boolean, string, point, vector, rgb, spectrum, transform
    std::string name;
    std::string value;  // the value attribute, substituted ("" for a transform or x/y/z form)
    glm::dvec3 xyz{0.0};      // point and vector
    glm::dmat4 matrix{1.0};   // transform: the operations composed, first applied first
    Place place;
};

struct Object;

// A nested object or a <ref>: `name` is its role in the parent ("" when the
// XML gives none, as for a shape's bsdf).
struct Child {
    std::string name;
    std::shared_ptr<const Object> object;
    Place place;  // of the nesting element or the <ref>
};

struct Object {
    std::string tag;   // scene, shape, bsdf, emitter, sensor, film, rfilter, sampler,
                       // integrator, texture, medium, phase, volume, spectrum
    std::string type;  // the plugin ("diffuse"); "" for the scene
    std::string id;
    Place place;
    std::vector<Property> properties;
    std::vector<Child> children;
    std::filesystem::path folder;  // of the file it is written in (relative file names)

    const Property* property(const std::string& name) const;
    // "<bsdf type="diffuse">" or "<bsdf type="diffuse" id="wood">", for messages.
    std::string element() const;
};

struct Scene {
    std::shared_ptr<const Object> root;
    // The folders <path> added, in order, then the scene file's folder:
    // where a relative file name is looked for.
    std::vector<std::filesystem::path> searchPath;
};

// Throws strahl::Error "<file>:<line>: <what>" for malformed XML, a scene
// version Mitsuba 3 does not read, an unknown element or property type, a
// $name without a value, a bad number, a missing or cyclic include, or a
// <ref> to no object.
Scene readScene(const std::string& text, const std::filesystem::path& file, const Defines& defines);

// Numbers separated by commas and/or blanks ("0, 0,-1" or "1 2 3").
std::vector<double> numbers(const std::string& text, const Place& place, const std::string& what);

}  // namespace strahl::scene_detail::mitsuba
