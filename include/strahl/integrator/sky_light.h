#pragma once
// "sky": constant radiance from every direction, sampled cosine-weighted
// around the surface normal (uniformly for a point off surfaces). The scene's
// "background" colour becomes one too (docs/lights.md).
//
//   key        value                  default
//   radiance   colour, W/(m^2 sr)     1

#include <array>
#include <optional>
#include <string_view>

#include "strahl/core/sampling.h"
#include "strahl/integrator/light_sample.h"

namespace strahl {

struct SkyLight {
    static constexpr std::array<std::string_view, 1> kNames = {"sky"};

    Color radiance{1.0f};

    template <typename Reader>
    static SkyLight parse(const Reader& r) {
        const auto& v = r.json();
        v.requireKeys({"type", "radiance"});
        SkyLight l;
        if (auto radiance = v.find("radiance")) l.radiance = radiance->color();
        return l;
    }
    template <typename Loader>
    void load(const Loader&) {}
    void validate(size_t index) const { light_detail::checkColor(index, "radiance", radiance); }

    // The density of sampleLi, in the one formula both use so they agree exactly.
    static float pdf(const LightSampleContext& ctx, const Vec3& wi) {
        if (glm::dot(ctx.n, ctx.n) > 0.0f)
            return cosineHemispherePdf(glm::dot(glm::normalize(ctx.n), wi));
        return kUniformSpherePdf;
    }

    bool isDelta() const { return false; }
    bool isInfinite() const { return true; }
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, const Vec2& u) const {
        if (light_detail::isBlack(radiance)) return std::nullopt;
        LightLiSample s;
        s.atInfinity = true;
        s.L = radiance;
        if (glm::dot(ctx.n, ctx.n) > 0.0f)
            s.wi = glm::normalize(
                light_detail::aroundAxis(sampleCosineHemisphere(u), glm::normalize(ctx.n)));
        else
            s.wi = sampleUniformSphere(u);
        s.pdf = pdf(ctx, s.wi);
        if (!(s.pdf > 0.0f)) return std::nullopt;  // on the horizon
        return s;
    }
    float pdfLi(const LightSampleContext& ctx, const Vec3& wi, const Vec3&) const {
        return light_detail::isBlack(radiance) ? 0.0f : pdf(ctx, wi);
    }
    Color infiniteLe(const Vec3&) const { return radiance; }
    // Irradiance pi L on each point of the bounding sphere's area 4 pi R^2.
    float power(float sceneDisk) const { return 4.0f * kPi * sceneDisk * light_detail::mean(radiance); }
};

}  // namespace strahl
