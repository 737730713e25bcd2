#pragma once
// "triangle": one emissive triangle of an area light, in world space. Scene
// files do not name it: World::prepareLights splits every mesh whose emission
// is uniform, or textured through uvs, into these. Sampled uniformly in solid
// angle (spherical triangle, Arvo 1995) when it subtends between 3e-4 sr and
// 6.22 sr, else uniformly by area (docs/lights.md). A textured emission is
// read at the sampled point; the sampling does not follow the texture.

#include <array>
#include <optional>
#include <string_view>

#include "strahl/core/sampling.h"
#include "strahl/core/spherical_triangle.h"
#include "strahl/integrator/light_sample.h"
#include "strahl/material/material.h"

namespace strahl {

struct TriangleLight {
    static constexpr std::string_view kName = "triangle";
    static constexpr std::array<std::string_view, 0> kNames = {};  // not in scene files

    Vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};  // front = counter-clockwise
    Color radiance{0.0f};  // uniform emission; textured: the emission's scale
    bool twoSided = false;  // emits from both faces
    // A textured emission: the material whose emission it is (the world's
    // materials outlive its light table), the vertices' uvs, and the
    // texture's mean for power(). Null: `radiance` everywhere.
    const Material* textured = nullptr;
    Vec2 uv0{0.0f}, uv1{1.0f, 0.0f}, uv2{0.0f, 1.0f};
    float textureMean = 1.0f;

    // Spherical-triangle sampling is used between these solid angles. Below
    // 3e-4 sr (a triangle ~1 degree across) area sampling is as good: its
    // density dist^2 / (cos A) varies by only ~ the angular size over the
    // triangle. Above 6.22 sr (2 pi - 0.06) the point is almost in the plane of
    // a large triangle and Arvo's inversion loses accuracy. Both as in pbrt-v4.
    static constexpr float kMinSphericalSolidAngle = 3e-4f;
    static constexpr float kMaxSphericalSolidAngle = 6.22f;
    static bool sampleBySolidAngle(float solidAngle) {
        return solidAngle >= kMinSphericalSolidAngle && solidAngle <= kMaxSphericalSolidAngle;
    }

    template <typename Loader>
    void load(const Loader&) {}
    void validate(size_t index) const {
        light_detail::checkColor(index, "radiance", radiance);
        if (!isFinite(p0) || !isFinite(p1) || !isFinite(p2))
            fail("light ", index, ": triangle vertices must be finite");
    }

    // The geometric normal, length = twice the area.
    Vec3 cross() const { return glm::cross(p1 - p0, p2 - p0); }
    // A one-sided triangle light is seen only from its front half-space.
    bool seesFront(const Vec3& normal, const Vec3& p) const {
        return twoSided || glm::dot(normal, p - p0) > 0.0f;
    }
    // Radiance leaving a point of a uniform triangle towards w (0 behind a
    // one-sided one).
    Color Le(const Vec3& w) const {
        const float cosTheta = glm::dot(cross(), w);
        const bool emits = twoSided ? cosTheta != 0.0f : cosTheta > 0.0f;
        return emits ? radiance : Color(0.0f);
    }
    // The same at the point with barycentrics b, textured or not.
    Color Le(const Vec3& w, const Vec3& b, const TextureSystem* textures) const {
        const Color front = Le(w);
        if (!textured || light_detail::isBlack(front)) return front;
        ShadingPoint sp;
        sp.p = b.x * p0 + b.y * p1 + b.z * p2;
        sp.n = glm::normalize(cross());
        sp.uv = b.x * uv0 + b.y * uv1 + b.z * uv2;
        return evaluateColor(textured->emission, textured->mapping, sp, textures);
    }

    bool isDelta() const { return false; }
    bool isInfinite() const { return false; }
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, const Vec2& u) const {
        const Vec3 n = cross();
        const float twiceArea = glm::length(n);
        if (!(twiceArea > 0.0f) || !seesFront(n, ctx.p) || light_detail::isBlack(radiance))
            return std::nullopt;
        LightLiSample s;
        Vec3 b;  // barycentrics of the sampled point
        const float solidAngle = triangleSolidAngle(ctx.p, p0, p1, p2);
        if (sampleBySolidAngle(solidAngle)) {
            const auto st = sampleSphericalTriangle(ctx.p, p0, p1, p2, u, solidAngle);
            if (!st) return std::nullopt;
            b = st->barycentrics;
            s.pLight = b.x * p0 + b.y * p1 + b.z * p2;
            const Vec3 d = s.pLight - ctx.p;
            if (!(glm::dot(d, d) > 0.0f)) return std::nullopt;
            s.wi = unitVector(d);
            s.pdf = st->pdf;
        } else {
            // Uniform in area (density 1 / A), as solid angle density: d omega =
            // |cos theta_light| dA / dist^2, so pdf = dist^2 / (|cos theta_light| A).
            b = sampleUniformTriangle(u);
            s.pLight = b.x * p0 + b.y * p1 + b.z * p2;
            const Vec3 d = s.pLight - ctx.p;
            const float dist2 = glm::dot(d, d);
            if (!(dist2 > 0.0f)) return std::nullopt;
            s.wi = d / std::sqrt(dist2);
            const float cosLight = std::abs(glm::dot(n, s.wi)) / twiceArea;
            s.pdf = dist2 / (cosLight * 0.5f * twiceArea);
            if (!std::isfinite(s.pdf)) return std::nullopt;  // grazing: cos = 0
        }
        s.L = Le(-s.wi, b, ctx.textures);
        if (light_detail::isBlack(s.L)) return std::nullopt;
        return s;
    }
    // The decision rule of sampleLi, on the same inputs.
    float pdfLi(const LightSampleContext& ctx, const Vec3& wi, const Vec3& pLight) const {
        const Vec3 n = cross();
        const float twiceArea = glm::length(n);
        if (!(twiceArea > 0.0f) || !seesFront(n, ctx.p) || light_detail::isBlack(radiance))
            return 0.0f;
        const float solidAngle = triangleSolidAngle(ctx.p, p0, p1, p2);
        if (sampleBySolidAngle(solidAngle)) return 1.0f / solidAngle;
        const Vec3 d = pLight - ctx.p;
        const float cosLight = std::abs(glm::dot(n, wi)) / twiceArea;
        const float pdf = glm::dot(d, d) / (cosLight * 0.5f * twiceArea);
        return std::isfinite(pdf) ? pdf : 0.0f;
    }
    Color infiniteLe(const Vec3&) const { return Color(0.0f); }
    // A Lambertian emitter sends pi L per unit area from each emitting face
    // (textured: its mean L, the texture's mean over the whole image).
    float power(float /*sceneDisk*/) const {
        const float area = 0.5f * glm::length(cross());
        return kPi * area * light_detail::mean(radiance) * textureMean * (twoSided ? 2.0f : 1.0f);
    }
};

}  // namespace strahl
