#pragma once
// "point": radiant intensity I (W/sr per channel) from a point; a delta light
// (docs/lights.md).
//
//   key         value                     default
//   position    [x, y, z]                 required
//   intensity   colour, W/sr              1

#include <array>
#include <optional>
#include <string_view>

#include "strahl/integrator/light_sample.h"

namespace strahl {

// Shared by point and spot lights: the inverse-square law E = I / r^2 times a
// falloff, seen from p.
inline std::optional<LightLiSample> samplePointLike(const Vec3& position, const Vec3& p,
                                                    const Color& I, auto&& falloffTowards) {
    const Vec3 toLight = position - p;
    const float dist2 = glm::dot(toLight, toLight);
    if (!(dist2 > 0.0f)) return std::nullopt;  // at the light itself: no direction
    LightLiSample s;
    s.wi = toLight / std::sqrt(dist2);
    const float falloff = falloffTowards(s.wi);
    if (falloff == 0.0f || light_detail::isBlack(I)) return std::nullopt;
    s.L = falloff * I / dist2;
    s.pdf = 1.0f;
    s.pLight = position;
    return s;
}

struct PointLight {
    static constexpr std::array<std::string_view, 1> kNames = {"point"};

    Vec3 position{0.0f};
    Color intensity{1.0f};

    template <typename Reader>
    static PointLight parse(const Reader& r) {
        const auto& v = r.json();
        v.requireKeys({"type", "position", "intensity"});
        PointLight l;
        l.position = v.get("position").vec3();
        if (auto intensity = v.find("intensity")) l.intensity = intensity->color();
        return l;
    }
    template <typename Loader>
    void load(const Loader&) {}
    void validate(size_t index) const { light_detail::checkColor(index, "intensity", intensity); }

    bool isDelta() const { return true; }
    bool isInfinite() const { return false; }
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, const Vec2&) const {
        return samplePointLike(position, ctx.p, intensity, [](const Vec3&) { return 1.0f; });
    }
    float pdfLi(const LightSampleContext&, const Vec3&, const Vec3&) const { return 0.0f; }
    Color infiniteLe(const Vec3&) const { return Color(0.0f); }
    // Power 4 pi I.
    float power(float /*sceneDisk*/) const { return 4.0f * kPi * light_detail::mean(intensity); }
};

}  // namespace strahl
