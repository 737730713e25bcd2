#pragma once
// "environment": a lat-long radiance map at infinity, importance-sampled by a
// piecewise-constant 2D distribution weighted by sin(theta) (docs/lights.md).
// Lat-long convention (environment_map.h): +y up, the image centre towards +x,
// its left edge towards -x, u = 1/4 towards -z; not mirrored when seen from
// inside.
//
//   key        value                                              default
//   file       an image OpenImageIO reads (EXR, HDR, ...)          required
//   scale      colour multiplying the image                        1
//   rotation   degrees about +y, [-360, 360]                       0
//   rows       "centred": each row's values at its band's centre;  "centred"
//              "poles": the rows stretched from the zenith to the
//              nadir, as Mitsuba's envmap reads them (environment_map.h)
//   mapping    "latlong", or "equal_area": a square image in the      "latlong"
//              equal-area octahedral layout of pbrt-v4
//              (core/equal_area.h), resampled into a lat-long map
//              of twice its side by its side when the world is built
//   map_transform  equal_area only: 9 numbers, row by row, the     identity
//              linear map from world directions to the image's
//              directions (normalised after; any invertible
//              matrix, mirrors included)

#include <array>
#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <optional>
#include <string_view>

#include "strahl/integrator/environment_map.h"
#include "strahl/integrator/light_sample.h"

namespace strahl {

enum class EnvironmentMapping { LatLong, EqualArea };

struct EnvironmentLight {
    static constexpr std::array<std::string_view, 1> kNames = {"environment"};

    std::filesystem::path file;  // the image (resolved); read when the world is built
    std::shared_ptr<const EnvironmentMap> environment;
    Mat3 worldToEnvironment{1.0f};  // rotation (orthonormal) into map space
    Color scale{1.0f};              // multiplies the map
    RowLayout rows = RowLayout::Centred;
    // equal_area: from parse() to load(), worldToEnvironment holds the whole
    // map from world directions to the image's (map_transform after the
    // rotation), which load() bakes into the resampled lat-long map before
    // setting it to the identity (a field of its own would make every Light,
    // one per emissive triangle, larger).
    EnvironmentMapping mapping = EnvironmentMapping::LatLong;

    template <typename Reader>
    static EnvironmentLight parse(const Reader& r) {
        const auto& v = r.json();
        v.requireKeys({"type", "file", "scale", "rotation", "rows", "mapping", "map_transform"});
        EnvironmentLight l;
        l.file = r.existingFile(v.get("file"), "image file");
        if (auto scale = v.find("scale")) l.scale = scale->color();
        if (auto rows = v.find("rows"))
            l.rows = rows->oneOf({"centred", "poles"}) == "poles" ? RowLayout::PoleToPole
                                                                  : RowLayout::Centred;
        if (auto mapping = v.find("mapping"))
            l.mapping = mapping->oneOf({"latlong", "equal_area"}) == "equal_area" ? EnvironmentMapping::EqualArea
                                                                                  : EnvironmentMapping::LatLong;
        Mat3 mapTransform(1.0f);
        if (auto m = v.find("map_transform")) {
            if (l.mapping != EnvironmentMapping::EqualArea) m->fail("applies to \"mapping\": \"equal_area\" only");
            if (!m->raw().is_array() || m->raw().size() != 9)
                m->fail("expected 9 numbers (a 3 x 3 matrix, row by row)");
            for (int row = 0; row < 3; ++row)
                for (int col = 0; col < 3; ++col) mapTransform[col][row] = m->at(size_t(3 * row + col)).number();
            const float det = glm::determinant(mapTransform);
            if (!(std::abs(det) > 1e-12f) || !std::isfinite(det)) m->fail("the matrix is singular");
        }
        if (l.mapping == EnvironmentMapping::EqualArea && v.find("rows"))
            v.get("rows").fail("applies to \"mapping\": \"latlong\" only");
        float rotation = 0.0f;
        if (auto value = v.find("rotation")) rotation = value->numberIn(-360.0f, 360.0f, "degrees");
        // World to map space: the inverse of the map's rotation about +y.
        l.worldToEnvironment =
            Mat3(glm::rotate(Mat4(1.0f), glm::radians(-rotation), Vec3(0.0f, 1.0f, 0.0f)));
        if (l.mapping == EnvironmentMapping::EqualArea) l.worldToEnvironment = mapTransform * l.worldToEnvironment;
        return l;
    }
    // loader.environmentMap(file, rows) returns the lat-long map read from the
    // file, loader.equalAreaMap(file, mapFromWorld) one resampled from an
    // equal-area square (in world space: the map then needs no rotation).
    template <typename Loader>
    void load(const Loader& loader) {
        if (mapping == EnvironmentMapping::EqualArea) {
            environment = loader.equalAreaMap(file, worldToEnvironment);
            worldToEnvironment = Mat3(1.0f);
        } else {
            environment = loader.environmentMap(file, rows);
        }
    }
    void validate(size_t index) const {
        light_detail::checkColor(index, "scale", scale);
        if (!environment) fail("light ", index, ": environment light without a map");
        const Mat3& m = worldToEnvironment;
        const Mat3 shouldBeIdentity = glm::transpose(m) * m;
        float error = 0.0f;
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r)
                error = std::max(error, std::abs(shouldBeIdentity[c][r] - (c == r ? 1.0f : 0.0f)));
        // 1e-3: a rotation typed with 4-5 significant digits passes.
        if (!(error < 1e-3f) || !(glm::determinant(m) > 0.0f))
            fail("light ", index, ": worldToEnvironment must be a rotation");
    }

    bool isDelta() const { return false; }
    bool isInfinite() const { return true; }
    std::optional<LightLiSample> sampleLi(const LightSampleContext&, const Vec2& u) const {
        if (!environment) return std::nullopt;
        LightLiSample s;
        s.atInfinity = true;
        float mapPdf;
        const Vec3 dMap = environment->sample(u, mapPdf);
        if (!(mapPdf > 0.0f)) return std::nullopt;
        // The inverse of a rotation is its transpose.
        s.wi = glm::normalize(glm::transpose(worldToEnvironment) * dMap);
        // Radiance and density as infiniteLe and pdfLi compute them for s.wi, so
        // that MIS weights agree bit for bit. They differ from the map's own
        // values only where rotating back lands across a texel edge (a ~1e-6
        // fraction).
        s.pdf = environment->pdf(worldToEnvironment * s.wi);
        s.L = infiniteLe(s.wi);
        if (!(s.pdf > 0.0f) || light_detail::isBlack(s.L)) return std::nullopt;
        return s;
    }
    float pdfLi(const LightSampleContext&, const Vec3& wi, const Vec3&) const {
        if (!environment) return 0.0f;
        return environment->pdf(worldToEnvironment * wi);
    }
    Color infiniteLe(const Vec3& dir) const {
        if (!environment) return Color(0.0f);
        return scale * environment->lookup(worldToEnvironment * dir);
    }
    // As for the sky, with the map's mean radiance.
    float power(float sceneDisk) const {
        if (!environment) return 0.0f;
        return 4.0f * kPi * sceneDisk * light_detail::mean(scale * environment->average());
    }
};

}  // namespace strahl
