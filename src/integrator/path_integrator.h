#pragma once
// Internal: the unidirectional path tracer (see strahl/integrator/integrator.h).

#include "strahl/integrator/integrator.h"

namespace strahl {

class PathIntegrator final : public Integrator {
public:
    explicit PathIntegrator(const IntegratorOptions& options) : options_(options) {}
    std::string_view name() const override { return "path"; }
    Color shade(const World& world, const SurfaceHit& hit, Sampler& sampler,
                ShadingStats& stats) const override;
    Color miss(const World& world, const Ray& ray) const override {
        return options_.hideEmitters ? Color(0.0f) : world.escapedRadiance(glm::normalize(ray.dir));
    }

private:
    IntegratorOptions options_;
};

}  // namespace strahl
