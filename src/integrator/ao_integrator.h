#pragma once
// Internal: ambient occlusion (see strahl/integrator/integrator.h).

#include "strahl/integrator/integrator.h"

namespace strahl {

class AoIntegrator final : public Integrator {
public:
    AoIntegrator(const World& world, const IntegratorOptions& options);
    std::string_view name() const override { return "ao"; }
    Color shade(const World& world, const SurfaceHit& hit, Sampler& sampler,
                ShadingStats& stats) const override;
    Color miss(const World&, const Ray&) const override { return Color(0.0f); }

private:
    float distance_;
    int samples_;
};

}  // namespace strahl
