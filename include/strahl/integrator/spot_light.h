#pragma once
// "spot": a point light inside a cone, full intensity inside falloff_start
// and down to 0 at cone_angle: by default a smoothstep in cos(angle)
// (pbrt-v4's falloff), or linear in the angle (Mitsuba's spot). It may
// project an image, as Mitsuba's spot does (docs/lights.md).
//
//   key             value                                       default
//   position        [x, y, z]                                    required
//   direction       axis, non-zero (or look_at, not both)        one required
//   look_at         a point the axis goes through
//   intensity       colour, W/sr on the axis                     1
//   cone_angle      half-angle in degrees, [0.01, 180]           30
//   falloff_start   half-angle of full intensity, <= cone_angle  25 (or cone_angle if smaller)
//   falloff         "smooth" or "linear" (in the angle)          "smooth"
//   texture         an image texture object, multiplying the     none
//                   intensity: {"texture": file, "wrap", "filter",
//                   "uv_transform"}; needs cone_angle < 90
//   up              orients the image, not along the axis        [0, 1, 0]
//
// The projected image: with the light's frame z = axis, x = normalize(up × z),
// y = z × x, a direction d from the light reads the image at
//     (s, t) = (1/2 + (d·x) / (2 (d·z) tan(cone_angle)), 1/2 + (d·y) / (2 (d·z) tan(cone_angle)))
// (s right, t down the image): the image spans the cone's base square, its
// columns along x (the light's left, looking along the axis with up up) and
// its rows along y (up), so seen from behind the light it is turned 180°
// (top row towards −up), as Mitsuba's spot projects it.

#include <algorithm>
#include <array>
#include <memory>
#include <glm/trigonometric.hpp>
#include <optional>
#include <string_view>

#include "strahl/integrator/light_sample.h"
#include "strahl/integrator/point_light.h"
#include "strahl/material/textured.h"

namespace strahl {

struct SpotLight {
    static constexpr std::array<std::string_view, 1> kNames = {"spot"};

    enum class Falloff { Smooth, LinearAngle };

    Vec3 position{0.0f};
    Vec3 direction{0.0f, -1.0f, 0.0f};  // the axis (unit), pointing away from the light
    Color intensity{1.0f};
    float cosFalloffStart = 1.0f;  // full intensity inside this cone
    float cosTotalWidth = 0.0f;    // zero outside this cone
    Falloff shape = Falloff::Smooth;
    // The projected image and its frame: x, y across the axis, tanCone =
    // tan(cone_angle). Held apart (and shared between copies) so that the
    // light table, one Light per emissive triangle, stays small.
    struct Image {
        TextureRef texture;
        Vec3 x{1.0f, 0.0f, 0.0f}, y{0.0f, 0.0f, 1.0f};
        float tanCone = 1.0f;
    };
    std::shared_ptr<const Image> image;  // none without a "texture"

    template <typename Reader>
    static SpotLight parse(const Reader& r) {
        const auto& v = r.json();
        v.requireKeys({"type", "position", "direction", "look_at", "intensity", "cone_angle",
                       "falloff_start", "falloff", "texture", "up"});
        SpotLight l;
        l.position = v.get("position").vec3();
        l.direction = light_detail::axisFrom(v, l.position);
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
        if (auto falloff = v.find("falloff"))
            l.shape = falloff->oneOf({"smooth", "linear"}) == "linear" ? Falloff::LinearAngle
                                                                       : Falloff::Smooth;
        Vec3 up(0.0f, 1.0f, 0.0f);
        if (auto given = v.find("up")) up = light_detail::nonZeroDirection(*given);
        if (auto image = v.find("texture")) {
            if (!(coneAngle < 90.0f))
                image->fail("a projected image needs cone_angle < 90 degrees, got ", coneAngle);
            const Vec3 x = glm::cross(up, l.direction);
            if (!(glm::length(x) > 1e-6f))
                (v.has("up") ? v.get("up") : *image)
                    .fail("the image's up ([", up.x, ", ", up.y, ", ", up.z,
                          "]) is along the spot's axis: give another 'up'");
            auto projected = std::make_shared<Image>();
            projected->texture = r.imageTexture(*image);
            projected->x = glm::normalize(x);
            projected->y = glm::cross(l.direction, projected->x);
            projected->tanCone = std::tan(glm::radians(coneAngle));
            l.image = std::move(projected);
        } else if (v.has("up")) {
            v.get("up").fail("only a spot with a 'texture' has an up side");
        }
        return l;
    }
    // Registers the projected image, in a copy of it: the description this
    // light was copied from may build other worlds, with other texture systems.
    template <typename Loader>
    void load(const Loader& loader) {
        if (!image) return;
        auto bound = std::make_shared<Image>(*image);
        bound->texture.handle = loader.colorTexture(bound->texture.file);
        image = std::move(bound);
    }
    void validate(size_t index) const {
        light_detail::checkColor(index, "intensity", intensity);
        if (image && !image->texture.valid())
            fail("light ", index, ": the spot's image '", image->texture.file.string(), "' was not loaded");
        if (image && !(cosTotalWidth > 0.0f && image->tanCone > 0.0f))
            fail("light ", index, ": a spot with an image needs a cone under 90 degrees");
        if (!light_detail::isUnit(direction))
            fail("light ", index, ": spot direction must be a unit vector");
        if (!(-1.0f <= cosTotalWidth && cosTotalWidth <= cosFalloffStart && cosFalloffStart <= 1.0f))
            fail("light ", index, ": spot needs -1 <= cosTotalWidth (", cosTotalWidth,
                 ") <= cosFalloffStart (", cosFalloffStart, ") <= 1");
    }

    // 1 inside the falloff_start cone, 0 outside cone_angle (a hard edge if
    // they coincide), and between them a smoothstep in cos(theta), or linear
    // in theta: (cone − theta) / (cone − start).
    float falloff(float cosTheta) const {
        if (cosTheta >= cosFalloffStart) return 1.0f;
        if (cosTheta <= cosTotalWidth) return 0.0f;
        if (shape == Falloff::LinearAngle) {
            const float cone = std::acos(cosTotalWidth), start = std::acos(cosFalloffStart);
            return (cone - std::acos(std::clamp(cosTheta, -1.0f, 1.0f))) / (cone - start);
        }
        const float t = (cosTheta - cosTotalWidth) / (cosFalloffStart - cosTotalWidth);
        return t * t * (3.0f - 2.0f * t);
    }

    // The projected image's colour towards direction d (from the light,
    // inside the cone); white without an image.
    Color imageColor(const Vec3& d, const TextureSystem* textures) const {
        if (!image) return Color(1.0f);
        if (!image->texture.valid() || !textures)
            fail("spot light: its image '", image->texture.file.string(), "' was not loaded");
        const float z = glm::dot(d, direction) * image->tanCone;
        const Vec2 st(0.5f + 0.5f * glm::dot(d, image->x) / z, 0.5f + 0.5f * glm::dot(d, image->y) / z);
        return Color(lookupTexture(image->texture, st, 0.0f, *textures));
    }

    bool isDelta() const { return true; }
    bool isInfinite() const { return false; }
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, const Vec2&) const {
        std::optional<LightLiSample> s = samplePointLike(
            position, ctx.p, intensity, [&](const Vec3& wi) { return falloff(glm::dot(-wi, direction)); });
        if (s && image) {
            s->L *= imageColor(-s->wi, ctx.textures);
            if (light_detail::isBlack(s->L)) return std::nullopt;
        }
        return s;
    }
    float pdfLi(const LightSampleContext&, const Vec3&, const Vec3&) const { return 0.0f; }
    Color infiniteLe(const Vec3&) const { return Color(0.0f); }
    // 2 pi I times the integral of the falloff over cos(theta) (the image is
    // not counted: this only weighs the light's choice): 1 on [cosStart, 1],
    // then smoothstep, whose mean on its interval is 1/2, or the linear ramp,
    // whose integral over the sphere's band is
    //   ∫ (a − θ)/(a − b) sin θ dθ from b to a = cos b − (sin a − sin b)/(a − b)
    // (a the cone, b the start), so that the total is 1 − (sin a − sin b)/(a − b).
    // For the linear ramp, in double and in the form
    //   1 − (sin a − sin b)/(a − b) = 1 − cos m · sin h / h,  m = (a + b)/2, h = (a − b)/2
    //   = 2 sin²(m/2) + cos m · (1 − sin h / h),
    // which keeps its digits for small cones (both terms are positive).
    float power(float /*sceneDisk*/) const {
        const double I = 2.0 * 3.14159265358979323846 * light_detail::mean(intensity);
        if (shape == Falloff::LinearAngle) {
            const double a = std::acos(double(cosTotalWidth)), b = std::acos(double(cosFalloffStart));
            const double m = 0.5 * (a + b), h = 0.5 * (a - b);
            // 1 − sin h / h, by its series below 1e-3 (the first omitted term is h⁶/5040).
            const double oneMinusSinc = h < 1e-3 ? h * h / 6.0 - h * h * h * h / 120.0 : 1.0 - std::sin(h) / h;
            const double sinHalf = std::sin(0.5 * m);
            return float(I * std::max(0.0, 2.0 * sinHalf * sinHalf + std::cos(m) * oneMinusSinc));
        }
        return float(I * ((1.0 - cosFalloffStart) + 0.5 * (double(cosFalloffStart) - cosTotalWidth)));
    }
};

}  // namespace strahl
