#pragma once
// The built-in implicit surfaces a scene file names by "type", a closed
// family: one file per kind, src/geometry/implicit_<kind>.cpp, holding its
// surface class, its factory (implicit_builtins.h), its keys and defaults and
// its parsing; implicitKinds() (implicit_kinds.cpp) lists them. A kind parses
// its parameters through ImplicitParameters, which the scene module
// implements over the scene file's JSON, so geometry needs no JSON library.
// Formulas and CSG are not kinds: they are compositions the scene parser
// builds itself. docs/architecture.md: how to add one.

#include <functional>
#include <initializer_list>
#include <memory>
#include <span>
#include <string_view>

#include "strahl/core/math.h"
#include "strahl/geometry/implicit_surface.h"

namespace strahl {

// The parameters of one surface object (or a nested object of it). Every
// error it throws names the scene file and the place.
class ImplicitParameters {
public:
    virtual ~ImplicitParameters() = default;

    // The "type" the surface was given (a kind may answer to several).
    virtual std::string_view type() const = 0;
    // Every key present must be one of `allowed`.
    virtual void requireKeys(std::initializer_list<std::string_view> allowed) const = 0;
    // A finite number, or `fallback` when the key is absent.
    virtual double number(std::string_view key, double fallback) const = 0;
    // [x, y, z] of finite numbers, or `fallback` when the key is absent.
    virtual DVec3 vec3(std::string_view key, const DVec3& fallback) const = 0;
    // The required object or array at `key`.
    virtual std::unique_ptr<ImplicitParameters> child(std::string_view key) const = 0;
    // For an array: its length and its elements.
    virtual size_t size() const = 0;
    virtual std::unique_ptr<ImplicitParameters> at(size_t index) const = 0;
    // Runs a surface factory; its strahl::Error (which names the parameter, not
    // the place) is thrown again with the place.
    virtual ImplicitSurfacePtr checked(const std::function<ImplicitSurfacePtr()>& make) const = 0;
};

struct ImplicitKind {
    std::span<const std::string_view> names;  // the "type" values it answers to
    ImplicitSurfacePtr (*parse)(const ImplicitParameters& parameters);
};

// Every built-in kind, in the order `type` errors list their names.
std::span<const ImplicitKind* const> implicitKinds();
// The kind answering to `name`, or null.
const ImplicitKind* findImplicitKind(std::string_view name);

}  // namespace strahl
