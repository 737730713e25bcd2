#pragma once
// "directional" and "sun": irradiance E (W/m^2 on a facing surface) from a
// direction; with an angular diameter > 0 it is a sun disk of uniform radiance
// E / (pi sin^2 r), r the angular radius, sampled uniformly in its cone
// (docs/lights.md).
//
//   key                value                                   default
//   direction          the direction light travels, non-zero   required
//   irradiance         colour, W/m^2                            1
//   angular_diameter   degrees in [0, 90]; 0 is a delta light   0 ("sun": 0.53)

#include <array>
#include <glm/trigonometric.hpp>
#include <optional>
#include <string_view>

#include "strahl/core/sampling.h"
#include "strahl/integrator/light_sample.h"

namespace strahl {

struct DirectionalLight {
    // "sun" is a directional light with the sun's angular diameter by default.
    static constexpr std::array<std::string_view, 2> kNames = {"directional", "sun"};

    Vec3 direction{0.0f, -1.0f, 0.0f};  // the direction light travels (unit)
    Color irradiance{1.0f};
    float angularRadius = 0.0f;  // sun disk half-angle, radians (0: delta)

    template <typename Reader>
    static DirectionalLight parse(const Reader& r) {
        const auto& v = r.json();
        v.requireKeys({"type", "direction", "irradiance", "angular_diameter"});
        DirectionalLight l;
        l.direction = light_detail::nonZeroDirection(v.get("direction"));
        if (auto irradiance = v.find("irradiance")) l.irradiance = irradiance->color();
        // The sun seen from the earth is 0.53 degrees across.
        float angularDiameter = r.name() == "sun" ? 0.53f : 0.0f;
        if (auto diameter = v.find("angular_diameter"))
            angularDiameter = diameter->numberIn(0.0f, 90.0f, "degrees");
        l.angularRadius = glm::radians(0.5f * angularDiameter);
        return l;
    }
    template <typename Loader>
    void load(const Loader&) {}
    void validate(size_t index) const {
        light_detail::checkColor(index, "irradiance", irradiance);
        if (!light_detail::isUnit(direction))
            fail("light ", index, ": directional direction must be a unit vector");
        // Beyond pi/2 the disk would cover more than a facing hemisphere and
        // E = L pi sin^2 r would no longer hold.
        if (!(angularRadius >= 0.0f && angularRadius <= 0.5f * kPi))
            fail("light ", index, ": angular radius ", angularRadius, " must lie in [0, pi/2]");
    }

    // Cone of the sun disk: 1 - cos r as 2 sin^2(r / 2), exact for tiny r.
    float oneMinusCos() const {
        const float s = std::sin(0.5f * angularRadius);
        return 2.0f * s * s;
    }
    // Radiance of the sun disk. A facing surface receives
    //     E = integral over the cone of L cos(theta) d omega
    //       = L 2 pi integral_0^r cos(theta) sin(theta) d theta = L pi sin^2 r,
    // (= solid angle 2 pi (1 - cos r) times mean cosine (1 + cos r) / 2), so
    // L = E / (pi sin^2 r).
    Color sunRadiance() const {
        const float s = std::sin(angularRadius);
        return irradiance / (kPi * s * s);
    }
    // Inside the sun's cone around axis = -direction: 1 - cos(angle to the
    // axis) is half the squared chord |dir - axis|^2, which stays accurate for
    // tiny angles.
    bool inSunDisk(const Vec3& dir) const {
        const Vec3 chord = glm::normalize(dir) + direction;
        return 0.5f * glm::dot(chord, chord) <= oneMinusCos();
    }

    bool isDelta() const { return angularRadius == 0.0f; }
    bool isInfinite() const { return true; }
    std::optional<LightLiSample> sampleLi(const LightSampleContext&, const Vec2& u) const {
        LightLiSample s;
        s.atInfinity = true;
        if (angularRadius == 0.0f) {
            s.wi = -direction;
            s.L = irradiance;
            s.pdf = 1.0f;
        } else {
            const float h = oneMinusCos();
            s.wi = glm::normalize(light_detail::aroundAxis(sampleUniformConeHeight(u, h), -direction));
            // Rounding can put a sample on the cone's edge a hair outside it;
            // drop those (a ~1e-5 fraction at the sun's size) so that every
            // sample is a direction where infiniteLe and pdfLi see the disk.
            if (!inSunDisk(s.wi)) return std::nullopt;
            s.L = sunRadiance();
            s.pdf = uniformConeHeightPdf(h);
        }
        if (light_detail::isBlack(s.L)) return std::nullopt;
        return s;
    }
    float pdfLi(const LightSampleContext&, const Vec3& wi, const Vec3&) const {
        if (angularRadius == 0.0f || !inSunDisk(wi)) return 0.0f;
        return uniformConeHeightPdf(oneMinusCos());
    }
    Color infiniteLe(const Vec3& dir) const {
        if (angularRadius > 0.0f && inSunDisk(dir)) return sunRadiance();
        return Color(0.0f);
    }
    // The flux through the scene's bounding-sphere cross-section.
    float power(float sceneDisk) const { return sceneDisk * light_detail::mean(irradiance); }
};

}  // namespace strahl
