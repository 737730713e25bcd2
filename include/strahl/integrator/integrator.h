#pragma once
// Integrators turn a camera ray and its first hit into radiance.
//
//   eyelight  |N . D|: the cosine between shading normal and view ray (grey)
//   normal    the shading normal mapped to colour, 0.5 N + 0.5
//   depth     hit distance divided by the scene's bounding-box diagonal (grey)
//   primid    a stable pseudo-random colour per (geomID, primID)
//   direct    emission + Lambertian reflection of point and directional lights
//             with hard shadows (one occlusion ray per light)
//
// Debug integrators return black for rays that miss; `direct` returns the
// scene background. Surfaces are two-sided.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "strahl/core/math.h"
#include "strahl/core/ray.h"
#include "strahl/core/rng.h"
#include "strahl/integrator/surface_hit.h"
#include "strahl/integrator/world.h"

namespace strahl {

// Per-thread counters, summed by the renderer.
struct ShadingStats {
    uint64_t shadowRays = 0;
};

class Integrator {
public:
    virtual ~Integrator() = default;
    virtual std::string_view name() const = 0;

    // Radiance along a ray towards its closest hit.
    virtual Color shade(const World& world, const SurfaceHit& hit, SampleRng& rng,
                        ShadingStats& stats) const = 0;
    // Radiance along a ray that hit nothing.
    virtual Color miss(const World& world, const Ray& ray) const = 0;
};

std::span<const std::string_view> integratorNames();

// Throws strahl::Error naming the integrator and the valid names if unknown.
void requireIntegratorName(std::string_view name);
std::unique_ptr<Integrator> makeIntegrator(std::string_view name, const World& world);

}  // namespace strahl
