#pragma once
// Internal to the scene module: a surface object of the scene file as the
// built-in surface kinds read it (strahl/geometry/surface_parameters.h). The
// families differ only in how they read a number (implicit surfaces: as the
// scene's floats; parametric ones: in double precision or as a constant
// formula), which the parser passes in. Also what both surface parsers use to
// run a geometry constructor (buildAt).

#include <memory>
#include <string>
#include <string_view>

#include "json_reader.h"
#include "strahl/core/error.h"
#include "strahl/geometry/surface_parameters.h"

namespace strahl::scene_detail {

class JsonSurfaceParameters final : public SurfaceParameters {
public:
    // Reads `key` of `object`, or `fallback` when it is absent.
    using NumberReader = double (*)(const JsonValue& object, std::string_view key, double fallback);

    JsonSurfaceParameters(const JsonValue& v, std::string_view type, NumberReader readNumber)
        : v_(v), type_(type), number_(readNumber) {}

    std::string_view type() const override { return type_; }
    void requireKeys(std::initializer_list<std::string_view> allowed) const override {
        v_.requireKeys(allowed);
    }
    double number(std::string_view key, double fallback) const override {
        return number_(v_, key, fallback);
    }
    DVec3 vec3(std::string_view key, const DVec3& fallback) const override {
        const auto found = v_.find(key);
        return found ? DVec3(found->vec3()) : fallback;
    }
    std::unique_ptr<SurfaceParameters> child(std::string_view key) const override {
        return std::make_unique<JsonSurfaceParameters>(v_.get(key), type_, number_);
    }
    size_t size() const override { return v_.size(); }
    std::unique_ptr<SurfaceParameters> at(size_t index) const override {
        return std::make_unique<JsonSurfaceParameters>(v_.at(index), type_, number_);
    }

private:
    void throwAtPlace(const std::string& message) const override { v_.fail(message); }

    JsonValue v_;
    std::string_view type_;
    NumberReader number_;
};

// Runs a geometry constructor; its strahl::Error (which names the parameter but
// not the place) is re-thrown with the JSON pointer of `v`.
template <class Make>
auto buildAt(const JsonValue& v, Make&& make) -> decltype(make()) {
    try {
        return make();
    } catch (const Error& e) {
        v.fail(e.what());
    }
}

}  // namespace strahl::scene_detail
