#pragma once
// Internal: Whitted-style direct lighting (see strahl/integrator/integrator.h).

#include "strahl/integrator/integrator.h"

namespace strahl {

class DirectIntegrator final : public Integrator {
public:
    explicit DirectIntegrator(bool hideEmitters = false) : hideEmitters_(hideEmitters) {}
    std::string_view name() const override { return "direct"; }
    Color shade(const World& world, const SurfaceHit& hit, Sampler& sampler,
                ShadingStats& stats) const override;
    Color miss(const World& world, const Ray& ray) const override {
        return hideEmitters_ ? Color(0.0f) : world.escapedRadiance(glm::normalize(ray.dir));
    }

private:
    bool hideEmitters_;  // every ray it shades is a camera ray
};

}  // namespace strahl
