// The light family's operations: each visits LightKind and asks the kind
// (point_light.h ... triangle_light.h hold the math).

#include "strahl/integrator/light.h"

#include <algorithm>
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
    : lights_(std::move(lights)), selection_(selection) {
    if (selection_ == LightSelection::Auto) {
        const auto infinite = size_t(std::count_if(lights_.begin(), lights_.end(),
                                                   [](const Light& l) { return l.isInfinite(); }));
        const size_t finite = lights_.size() - infinite;
        selection_ = finite > kAutoBvhLights || infinite >= kAutoBvhInfiniteLights ? LightSelection::Bvh
                                                                                  : LightSelection::Power;
    }
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
    if (selection_ == LightSelection::Bvh) {
        std::vector<LightBounds> bounds;
        std::vector<uint32_t> index;
        for (size_t i = 0; i < lights_.size(); ++i)
            if (const auto b = boundsOf(lights_[i], powers[i])) {
                bounds.push_back(*b);
                index.push_back(static_cast<uint32_t>(i));
            }
        bvh_ = LightBvh(std::move(bounds), std::move(index));
        return;
    }
    if (selection_ == LightSelection::UniformEmitters) {
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

// Bvh: each infinite light and the tree as a whole are chosen equally often
// (pbrt-v4's rule: the tree's importances cannot be compared with a light at
// infinity); `choices` counts them.
namespace {
size_t bvhChoices(const std::vector<uint32_t>& infinite, const LightBvh& bvh) {
    return infinite.size() + (bvh.empty() ? 0 : 1);
}
}  // namespace

std::optional<std::pair<uint32_t, float>> LightSet::choose(float u,
                                                           const LightSampleContext& at) const {
    if (lights_.empty()) return std::nullopt;
    if (selection_ == LightSelection::Bvh) {
        const size_t choices = bvhChoices(infinite_, bvh_);
        if (choices == 0) return std::nullopt;
        const float scaled = u * float(choices);
        const size_t pick = std::min(static_cast<size_t>(scaled), choices - 1);
        const float share = 1.0f / float(choices);
        if (pick < infinite_.size()) return std::make_pair(infinite_[pick], share);
        // The rest of u, rescaled to [0, 1), walks the tree.
        const float rest = std::min(scaled - float(pick), 0x1.fffffep-1f);
        auto choice = bvh_.choose(rest, at.p, at.n);
        if (choice) choice->second *= share;
        return choice;
    }
    float pmf;
    const size_t index = distribution_.sampleDiscrete(u, pmf);
    return std::make_pair(static_cast<uint32_t>(index), pmf);
}

float LightSet::pmf(uint32_t index, const LightSampleContext& at) const {
    if (selection_ == LightSelection::Bvh) {
        const size_t choices = bvhChoices(infinite_, bvh_);
        if (choices == 0 || index >= lights_.size()) return 0.0f;
        const float share = 1.0f / float(choices);
        if (lights_[index].isInfinite()) return share;
        return bvh_.pmf(index, at.p, at.n) * share;
    }
    return distribution_.pmf(index);
}

}  // namespace strahl
