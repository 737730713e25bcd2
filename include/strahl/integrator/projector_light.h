#pragma once
// "projector": a slide projector, the reciprocal of a pinhole camera (Mitsuba's
// projector): from a point, an image is projected through a rectangular
// frustum, giving the irradiance `irradiance` × image on a plane one unit
// away, facing the projector, and falling off as 1/z² beyond (docs/lights.md).
//
//   key          value                                            default
//   position     [x, y, z]                                         required
//   direction    the optical axis, non-zero (or look_at, not both) one required
//   look_at      a point on the axis
//   up           the image's up side, not along the axis            [0, 1, 0]
//   fov          field of view in degrees, (0, 180)                 required
//   fov_axis     what fov spans: "x" (the image's width), "y",      "x"
//                "diagonal", "smaller", "larger"
//   irradiance   colour, W/m² on the plane at distance 1 (× image)  1
//   texture      an image texture object {"texture": file, "wrap",  none: uniform,
//                "filter", "uv_transform"}; its aspect ratio         square
//                shapes the frustum
//
// With the frame z = axis, right x = normalize(z × up), y = x × z, and
// tan(fov_x / 2) = tx, ty = tx / aspect, a direction d from the projector
// reads the image at
//     (s, t) = (1/2 + (d·x) / (2 (d·z) tx), 1/2 − (d·y) / (2 (d·z) ty))
// (s right, t down: the image appears as on a screen, seen from behind the
// projector) and is dark outside [0, 1]². The intensity towards d is
// I(d) = irradiance × image(s, t) / cos³θ, cos θ = d·z: a plane at z = 1 then
// receives irradiance × image everywhere, the edges as much as the centre.

#include <array>
#include <cmath>
#include <glm/trigonometric.hpp>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "strahl/integrator/light_sample.h"
#include "strahl/integrator/point_light.h"
#include "strahl/material/textured.h"

namespace strahl {

struct ProjectorLight {
    static constexpr std::array<std::string_view, 1> kNames = {"projector"};

    Vec3 position{0.0f};
    Vec3 axis{0.0f, 0.0f, -1.0f};                    // z: unit, away from the projector
    Vec3 right{1.0f, 0.0f, 0.0f}, up{0.0f, 1.0f, 0.0f};  // x, y: unit, across the axis
    Color irradiance{1.0f};
    enum class FovAxis { X, Y, Diagonal, Smaller, Larger };
    float fovDegrees = 90.0f;
    FovAxis fovAxis = FovAxis::X;
    float tanX = 1.0f, tanY = 1.0f;  // the frustum's half-extents at distance 1
    // The projected image, held apart so that the light table stays small;
    // none: a uniform square.
    std::shared_ptr<const TextureRef> image;

    template <typename Reader>
    static ProjectorLight parse(const Reader& r) {
        const auto& v = r.json();
        v.requireKeys({"type", "position", "direction", "look_at", "up", "fov", "fov_axis",
                       "irradiance", "texture"});
        ProjectorLight l;
        l.position = v.get("position").vec3();
        l.axis = light_detail::axisFrom(v, l.position);
        Vec3 up(0.0f, 1.0f, 0.0f);
        if (auto given = v.find("up")) up = light_detail::nonZeroDirection(*given);
        const Vec3 right = glm::cross(l.axis, up);
        if (!(glm::length(right) > 1e-6f))
            (v.has("up") ? v.get("up") : v).fail("the image's up is along the projector's axis: give another 'up'");
        l.right = glm::normalize(right);
        l.up = glm::cross(l.right, l.axis);
        const auto fov = v.get("fov");
        l.fovDegrees = fov.number();
        if (!(l.fovDegrees > 0.0f && l.fovDegrees < 180.0f))
            fov.fail("must be strictly between 0 and 180 degrees, got ", l.fovDegrees);
        if (auto axis = v.find("fov_axis")) {
            const std::string a = axis->oneOf({"x", "y", "diagonal", "smaller", "larger"});
            l.fovAxis = a == "x"          ? FovAxis::X
                        : a == "y"        ? FovAxis::Y
                        : a == "diagonal" ? FovAxis::Diagonal
                        : a == "smaller"  ? FovAxis::Smaller
                                          : FovAxis::Larger;
        }
        if (auto value = v.find("irradiance")) l.irradiance = value->color();
        if (auto texture = v.find("texture"))
            l.image = std::make_shared<const TextureRef>(r.imageTexture(*texture));
        l.setFrustum(1.0f);
        return l;
    }
    // Registers the image (in a copy: the description may build other
    // worlds) and shapes the frustum by its aspect ratio.
    template <typename Loader>
    void load(const Loader& loader) {
        if (!image) return;
        auto bound = std::make_shared<TextureRef>(*image);
        bound->handle = loader.colorTexture(bound->file);
        const glm::ivec2 size = loader.textureResolution(bound->handle);
        image = std::move(bound);
        setFrustum(static_cast<float>(size.x) / static_cast<float>(size.y));
    }
    // tanX, tanY from the fov along fovAxis for an image of this aspect
    // (width / height), as a camera's fov_axis reads it.
    void setFrustum(float aspect) {
        const float t = std::tan(glm::radians(fovDegrees) / 2.0f);
        const FovAxis a = fovAxis;
        const bool wide = aspect >= 1.0f;
        if (a == FovAxis::X || (a == FovAxis::Larger && wide) || (a == FovAxis::Smaller && !wide)) {
            tanX = t;
            tanY = t / aspect;
        } else if (a != FovAxis::Diagonal) {
            tanY = t;
            tanX = t * aspect;
        } else {  // diagonal: t spans half the diagonal
            tanY = t / std::sqrt(aspect * aspect + 1.0f);
            tanX = tanY * aspect;
        }
    }

    void validate(size_t index) const {
        light_detail::checkColor(index, "irradiance", irradiance);
        if (image && !image->valid())
            fail("light ", index, ": the projector's image '", image->file.string(), "' was not loaded");
        if (!light_detail::isUnit(axis) || !light_detail::isUnit(right) || !light_detail::isUnit(up))
            fail("light ", index, ": the projector's frame must be unit vectors");
        if (!(tanX > 0.0f && tanY > 0.0f && std::isfinite(tanX) && std::isfinite(tanY)))
            fail("light ", index, ": the projector's frustum must be finite and open");
    }

    // Intensity towards the unit direction d from the projector.
    Color intensityTowards(const Vec3& d, const TextureSystem* textures) const {
        const float cosTheta = glm::dot(d, axis);
        if (!(cosTheta > 0.0f)) return Color(0.0f);
        const Vec2 st(0.5f + 0.5f * glm::dot(d, right) / (cosTheta * tanX),
                      0.5f - 0.5f * glm::dot(d, up) / (cosTheta * tanY));
        if (!(st.x >= 0.0f && st.x <= 1.0f && st.y >= 0.0f && st.y <= 1.0f)) return Color(0.0f);
        Color value = irradiance / (cosTheta * cosTheta * cosTheta);
        if (image) {
            if (!image->valid() || !textures)
                fail("projector light: its image '", image->file.string(), "' was not loaded");
            value *= Color(lookupTexture(*image, st, 0.0f, *textures));
        }
        return value;
    }

    bool isDelta() const { return true; }
    bool isInfinite() const { return false; }
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, const Vec2&) const {
        std::optional<LightLiSample> s =
            samplePointLike(position, ctx.p, Color(1.0f), [](const Vec3&) { return 1.0f; });
        if (!s) return std::nullopt;
        s->L *= intensityTowards(-s->wi, ctx.textures);
        if (light_detail::isBlack(s->L)) return std::nullopt;
        return s;
    }
    float pdfLi(const LightSampleContext&, const Vec3&, const Vec3&) const { return 0.0f; }
    Color infiniteLe(const Vec3&) const { return Color(0.0f); }
    // Φ = ∫ I dω over the frustum; on the plane z = 1, dω = cos³θ dA, so
    // Φ = irradiance × (the image's mean) × the frustum's area there,
    // (2 tanX)(2 tanY). The image's mean is taken as 1: this only weighs
    // which light is sampled.
    float power(float /*sceneDisk*/) const {
        return light_detail::mean(irradiance) * 4.0f * tanX * tanY;
    }
};

}  // namespace strahl
