#pragma once
// Internal to the scene module: JSON text to typed values, with every error
// naming the file and the place. Syntax errors carry "file:LINE:COLUMN", content
// errors the JSON pointer of the offending value ("file: /film/width: ...").
// Objects are read with an explicit list of allowed keys, so a misspelt key is an
// error rather than a silently ignored setting.

#include <array>
#include <filesystem>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "strahl/core/error.h"
#include "strahl/core/math.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

// Parses JSON that may contain // and /* */ comments. Throws strahl::Error
// "<label>:LINE:COLUMN: syntax error: <reason>" (1-based) on malformed text.
nlohmann::json parseJsonText(const std::string& text, const std::string& label);

// The error of a value in the document: the message, and the JSON pointer
// it names ("" for the top level), so callers can tell where it is without
// reading the message (SceneDocument names the command-line patches there).
class JsonError : public Error {
public:
    JsonError(const std::string& message, std::string pointer)
        : Error(message), pointer_(std::move(pointer)) {}
    const std::string& pointer() const { return pointer_; }

private:
    std::string pointer_;
};

// A value inside a parsed document together with its JSON pointer. Cheap to
// copy; refers to the document and the label, which must outlive it.
class JsonValue {
public:
    JsonValue(const nlohmann::json& value, std::string pointer, const std::string& label)
        : value_(&value), pointer_(std::move(pointer)), label_(&label) {}

    const std::string& pointer() const { return pointer_; }
    const nlohmann::json& raw() const { return *value_; }
    // Where it is, for errors found after parsing (when a file it names is read).
    ScenePlace place() const { return {*label_, pointer_}; }

    // Throws JsonError "<label>: <pointer>: <pieces...>".
    template <typename... Args>
    [[noreturn]] void fail(const Args&... args) const {
        throw JsonError(concat(*label_, ": ", where(), ": ", args...), pointer_);
    }

    // --- objects -------------------------------------------------------------
    // Requires an object whose keys are all in `allowed`; otherwise throws
    // "unknown key 'x' (allowed: a, b, c)".
    void requireKeys(std::span<const std::string_view> allowed) const;
    void requireKeys(std::initializer_list<std::string_view> allowed) const {
        requireKeys(std::span(allowed.begin(), allowed.size()));
    }
    bool has(std::string_view key) const;
    JsonValue get(std::string_view key) const;  // throws "missing key 'x'"
    std::optional<JsonValue> find(std::string_view key) const;

    // --- arrays --------------------------------------------------------------
    size_t size() const;  // requires an array
    JsonValue at(size_t index) const;

    // --- scalars -------------------------------------------------------------
    bool boolean() const;
    std::string string() const;
    // One of `choices`; throws "must be one of a, b, got 'c'".
    std::string oneOf(std::span<const std::string_view> choices) const;
    std::string oneOf(std::initializer_list<std::string_view> choices) const {
        return oneOf(std::span(choices.begin(), choices.size()));
    }
    // A number whose value is finite as a float.
    float number() const;
    // A number() in [lo, hi]; throws "must be in [lo, hi], got x", or with a
    // unit "must be in [lo, hi] <unit>, got x".
    float numberIn(float lo, float hi, std::string_view unit = {}) const;
    // An integer (an integral number such as 2 or 2.0) in [lo, hi].
    int64_t integer(int64_t lo, int64_t hi) const;
    // A non-negative integer no larger than `hi`.
    uint64_t unsignedInteger(uint64_t hi) const;
    // Any integer: its value if in [0, 2^64), none if negative or larger.
    std::optional<uint64_t> integerOrNone() const;

    // --- vectors and colours -------------------------------------------------
    Vec2 vec2() const;  // [x, y]
    Vec3 vec3() const;  // [x, y, z]
    // A grey level (one number) or [r, g, b]; every component finite and >= 0.
    Color color() const;

    // "string", "array", ... or the number itself: what a message says was found.
    std::string describe() const;

private:
    std::string where() const { return pointer_.empty() ? "top level" : pointer_; }
    std::string childPointer(std::string_view key) const;
    void requireArray() const;
    // The numbers of an array of exactly N elements.
    template <size_t N>
    std::array<float, N> numbers() const;

    const nlohmann::json* value_;
    std::string pointer_;
    const std::string* label_;
};

// "a, b, c": the items joined for error messages.
std::string joinList(std::span<const std::string_view> items);

// Whether the path's extension, lower-cased, is one of `extensions` (".exr").
bool hasExtension(const std::filesystem::path& path, std::span<const std::string_view> extensions);

// A path from the scene file: relative paths are relative to the scene file's
// folder, absolute ones are kept. Fails on an empty string.
std::filesystem::path resolvePath(const std::filesystem::path& folder, const JsonValue& value);

// resolvePath, and there must be a regular file there; otherwise throws
// "no such <noun> 'given' (looked at <resolved>)" (noun: "texture file", ...).
std::filesystem::path resolveExistingFile(const std::filesystem::path& folder,
                                          const JsonValue& value, std::string_view noun);

}  // namespace strahl::scene_detail
