// The light family's operations: each visits LightKind and asks the kind
// (point_light.h ... triangle_light.h hold the math).

#include "strahl/integrator/light.h"

#include <cmath>
#include <map>

#include "strahl/core/error.h"

namespace strahl {

bool Light::isDelta() const {
    return std::visit([](const auto& k) { return k.isDelta(); }, kind);
}

bool Light::isInfinite() const {
    return std::visit([](const auto& k) { return k.isInfinite(); }, kind);
}

std::optional<LightLiSample> sampleLi(const Light& light, const LightSampleContext& ctx,
                                      const Vec2& u) {
    return std::visit([&](const auto& k) { return k.sampleLi(ctx, u); }, light.kind);
}

float pdfLi(const Light& light, const LightSampleContext& ctx, const Vec3& wi, const Vec3& pLight) {
    return std::visit([&](const auto& k) { return k.pdfLi(ctx, wi, pLight); }, light.kind);
}

Color infiniteLe(const Light& light, const Vec3& dir) {
    return std::visit([&](const auto& k) { return k.infiniteLe(dir); }, light.kind);
}

Color triangleLe(const Light& light, const Vec3& w) {
    const auto* triangle = std::get_if<TriangleLight>(&light.kind);
    return triangle ? triangle->Le(w) : Color(0.0f);
}

float lightPower(const Light& light, const Bounds3& sceneBounds) {
    const float radius = 0.5f * glm::length(sceneBounds.diagonal());
    const float disk = kPi * radius * radius;  // the bounding sphere's cross-section
    return std::visit([&](const auto& k) { return k.power(disk); }, light.kind);
}

LightSet::LightSet(std::vector<Light> lights, const Bounds3& sceneBounds)
    : LightSet(std::move(lights), sceneBounds, LightSelection::Power, {}) {}

LightSet::LightSet(std::vector<Light> lights, const Bounds3& sceneBounds, LightSelection selection,
                   const std::vector<uint32_t>& emitterOf)
    : lights_(std::move(lights)) {
    if (lights_.empty()) return;
    if (lights_.size() > UINT32_MAX) fail("too many lights: ", lights_.size());
    std::vector<float> powers(lights_.size());
    for (size_t i = 0; i < lights_.size(); ++i) {
        std::visit([&](const auto& k) { k.validate(i); }, lights_[i].kind);
        powers[i] = lightPower(lights_[i], sceneBounds);
        if (!std::isfinite(powers[i]) || powers[i] < 0.0f)
            fail("light ", i, ": power ", powers[i], " is not finite and >= 0");
        if (lights_[i].isInfinite()) infinite_.push_back(static_cast<uint32_t>(i));
    }
    if (selection == LightSelection::UniformEmitters) {
        if (emitterOf.size() != lights_.size())
            fail("light selection: ", emitterOf.size(), " emitter ids for ", lights_.size(), " lights");
        // Each emitter 1 / emitters; within one, its lights by power (evenly if
        // they carry none): weight_i = power_i / (power of i's emitter) / emitters.
        std::map<uint32_t, std::pair<double, size_t>> emitters;  // id -> (power, lights)
        for (size_t i = 0; i < lights_.size(); ++i) {
            auto& e = emitters[emitterOf[i]];
            e.first += powers[i];
            ++e.second;
        }
        for (size_t i = 0; i < lights_.size(); ++i) {
            const auto& [power, count] = emitters[emitterOf[i]];
            const double share = power > 0.0 ? powers[i] / power : 1.0 / double(count);
            powers[i] = static_cast<float>(share / double(emitters.size()));
        }
    }
    distribution_ = Distribution1D(std::move(powers));  // all zero: uniform
}

std::optional<std::pair<uint32_t, float>> LightSet::choose(float u) const {
    if (lights_.empty()) return std::nullopt;
    float pmf;
    const size_t index = distribution_.sampleDiscrete(u, pmf);
    return std::make_pair(static_cast<uint32_t>(index), pmf);
}

float LightSet::pmf(uint32_t index) const {
    return distribution_.pmf(index);
}

}  // namespace strahl
