#pragma once
// Internal: the debug integrators (see strahl/integrator/integrator.h).

#include "strahl/integrator/integrator.h"

namespace strahl {

class DebugIntegrator : public Integrator {
public:
    Color miss(const World&, const Ray&) const override { return Color(0.0f); }
};

class EyelightIntegrator final : public DebugIntegrator {
public:
    std::string_view name() const override { return "eyelight"; }
    Color shade(const World&, const SurfaceHit& hit, Sampler&, ShadingStats&) const override;
    uint32_t shadeCameraLanes(const World& world, const CameraLanes& lanes,
                              Color* radiance) const override;
};

class NormalIntegrator final : public DebugIntegrator {
public:
    std::string_view name() const override { return "normal"; }
    Color shade(const World&, const SurfaceHit& hit, Sampler&, ShadingStats&) const override;
    uint32_t shadeCameraLanes(const World& world, const CameraLanes& lanes,
                              Color* radiance) const override;
};

class DepthIntegrator final : public DebugIntegrator {
public:
    explicit DepthIntegrator(const World& world);
    std::string_view name() const override { return "depth"; }
    Color shade(const World&, const SurfaceHit& hit, Sampler&, ShadingStats&) const override;

private:
    float invScale_ = 1.0f;
};

class PrimIdIntegrator final : public DebugIntegrator {
public:
    std::string_view name() const override { return "primid"; }
    Color shade(const World&, const SurfaceHit& hit, Sampler&, ShadingStats&) const override;
};

}  // namespace strahl
