#pragma once
// What a built-in surface kind (implicit_kinds.h, parametric_kinds.h) reads
// its parameters through: one object of the scene file, or a nested object
// or array of it. The scene module implements it over JSON, so the geometry
// module needs no JSON library; every error it throws names the scene file
// and the place.

#include <initializer_list>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/core/math.h"

namespace strahl {

class SurfaceParameters {
public:
    virtual ~SurfaceParameters() = default;

    // The "type" the surface was given (a kind may answer to several).
    virtual std::string_view type() const = 0;
    // Every key present must be one of `allowed`.
    virtual void requireKeys(std::initializer_list<std::string_view> allowed) const = 0;
    // A finite number, or `fallback` when the key is absent.
    virtual double number(std::string_view key, double fallback) const = 0;
    // [x, y, z] of finite numbers, or `fallback` when the key is absent.
    virtual DVec3 vec3(std::string_view key, const DVec3& fallback) const = 0;
    // The required object or array at `key`.
    virtual std::unique_ptr<SurfaceParameters> child(std::string_view key) const = 0;
    // For an array: its length and its elements.
    virtual size_t size() const = 0;
    virtual std::unique_ptr<SurfaceParameters> at(size_t index) const = 0;
    // Throws strahl::Error with the place in front of `message`.
    [[noreturn]] void fail(const std::string& message) const {
        throwAtPlace(message);
        throw Error(message);  // reached only by an implementation that did not throw
    }

    // Runs a surface factory; its strahl::Error (which names the parameter,
    // not the place) is thrown again with the place.
    template <typename Make>
    auto checked(Make&& make) const {
        try {
            return make();
        } catch (const Error& e) {
            fail(e.what());
        }
    }

protected:
    // Throws strahl::Error "<file>: <place>: <message>".
    virtual void throwAtPlace(const std::string& message) const = 0;
};

// One built-in kind of a surface family (implicit_kinds.h, parametric_kinds.h):
// the "type" values it answers to and how it reads its parameters.
template <typename SurfacePtr>
struct SurfaceKind {
    std::span<const std::string_view> names;
    SurfacePtr (*parse)(const SurfaceParameters& parameters);
};

// The kind of `kinds` answering to `name`, or null.
template <typename Kind>
const Kind* findKindNamed(std::span<const Kind* const> kinds, std::string_view name) {
    for (const Kind* kind : kinds)
        for (std::string_view n : kind->names)
            if (n == name) return kind;
    return nullptr;
}

// Every name of `kinds`, in order, then `more` (the types a parser builds itself).
template <typename Kind>
std::vector<std::string_view> kindNamesThen(std::span<const Kind* const> kinds,
                                            std::initializer_list<std::string_view> more) {
    std::vector<std::string_view> names;
    for (const Kind* kind : kinds) names.insert(names.end(), kind->names.begin(), kind->names.end());
    names.insert(names.end(), more);
    return names;
}

}  // namespace strahl
