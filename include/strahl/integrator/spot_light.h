#pragma once
// "spot": a point light inside a cone, full intensity inside falloff_start and
// a smoothstep in cos(angle) down to 0 at cone_angle (pbrt-v4's falloff;
// docs/lights.md).
//
//   key             value                                       default
//   position        [x, y, z]                                    required
//   direction       axis, non-zero (or look_at, not both)        one required
//   look_at         a point the axis goes through
//   intensity       colour, W/sr on the axis                     1
//   cone_angle      half-angle in degrees, [0.01, 180]           30
//   falloff_start   half-angle of full intensity, <= cone_angle  25 (or cone_angle if smaller)

#include <algorithm>
#include <array>
#include <glm/trigonometric.hpp>
#include <optional>
#include <string_view>

#include "strahl/integrator/light_sample.h"
#include "strahl/integrator/point_light.h"

namespace strahl {

struct SpotLight {
    static constexpr std::array<std::string_view, 1> kNames = {"spot"};

    Vec3 position{0.0f};
    Vec3 direction{0.0f, -1.0f, 0.0f};  // the axis (unit), pointing away from the light
    Color intensity{1.0f};
    float cosFalloffStart = 1.0f;  // full intensity inside this cone
    float cosTotalWidth = 0.0f;    // zero outside this cone

    template <typename Reader>
    static SpotLight parse(const Reader& r) {
        const auto& v = r.json();
        v.requireKeys({"type", "position", "direction", "look_at", "intensity", "cone_angle",
                       "falloff_start"});
        SpotLight l;
        l.position = v.get("position").vec3();
        if (v.has("direction") == v.has("look_at"))
            v.fail("give exactly one of 'direction' and 'look_at'");
        if (auto direction = v.find("direction"))
            l.direction = light_detail::nonZeroDirection(*direction);
        if (auto target = v.find("look_at")) {
            const Vec3 d = target->vec3() - l.position;
            if (d == Vec3(0.0f)) target->fail("must differ from the position");
            l.direction = unitVector(d);
        }
        if (auto intensity = v.find("intensity")) l.intensity = intensity->color();
        float coneAngle = 30.0f;
        if (auto cone = v.find("cone_angle")) coneAngle = cone->numberIn(0.01f, 180.0f, "degrees");
        float falloffStart = std::min(25.0f, coneAngle);
        if (auto start = v.find("falloff_start")) {
            falloffStart = start->numberIn(0.0f, 180.0f, "degrees");
            if (falloffStart > coneAngle)
                start->fail("must not exceed cone_angle (", coneAngle, " degrees), got ",
                            falloffStart);
        }
        l.cosTotalWidth = std::cos(glm::radians(coneAngle));
        l.cosFalloffStart = std::cos(glm::radians(falloffStart));
        return l;
    }
    template <typename Loader>
    void load(const Loader&) {}
    void validate(size_t index) const {
        light_detail::checkColor(index, "intensity", intensity);
        if (!light_detail::isUnit(direction))
            fail("light ", index, ": spot direction must be a unit vector");
        if (!(-1.0f <= cosTotalWidth && cosTotalWidth <= cosFalloffStart && cosFalloffStart <= 1.0f))
            fail("light ", index, ": spot needs -1 <= cosTotalWidth (", cosTotalWidth,
                 ") <= cosFalloffStart (", cosFalloffStart, ") <= 1");
    }

    // Smoothstep in cos(theta) between the two cones; a hard edge at
    // cosTotalWidth if the cones coincide.
    float falloff(float cosTheta) const {
        if (cosTheta >= cosFalloffStart) return 1.0f;
        if (cosTheta <= cosTotalWidth) return 0.0f;
        const float t = (cosTheta - cosTotalWidth) / (cosFalloffStart - cosTotalWidth);
        return t * t * (3.0f - 2.0f * t);
    }

    bool isDelta() const { return true; }
    bool isInfinite() const { return false; }
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, const Vec2&) const {
        return samplePointLike(position, ctx.p, intensity,
                               [&](const Vec3& wi) { return falloff(glm::dot(-wi, direction)); });
    }
    float pdfLi(const LightSampleContext&, const Vec3&, const Vec3&) const { return 0.0f; }
    Color infiniteLe(const Vec3&) const { return Color(0.0f); }
    // 2 pi I times the integral of the falloff over cos(theta): 1 on
    // [cosStart, 1], and smoothstep, whose mean on its interval is 1/2.
    float power(float /*sceneDisk*/) const {
        return 2.0f * kPi * light_detail::mean(intensity) *
               ((1.0f - cosFalloffStart) + 0.5f * (cosFalloffStart - cosTotalWidth));
    }
};

}  // namespace strahl
