#pragma once
// Integrators turn a camera ray and its first hit into radiance.
//
//   eyelight  |N . D|: the cosine between shading normal and view ray (grey)
//   normal    the shading normal mapped to colour, 0.5 N + 0.5
//   depth     hit distance divided by the scene's bounding-box diagonal (grey)
//   primid    a stable pseudo-random colour per (geomID, primID)
//   direct    emission + the materials' reflection of every light, one
//             shadow ray per light (area and environment lights: one sample)
//   ao        ambient occlusion: the fraction of the cosine-weighted
//             hemisphere not blocked within a distance
//   path      unidirectional path tracing with next-event estimation and
//             multiple importance sampling (power heuristic), Russian roulette
//
// Debug integrators return black for rays that miss; `direct` and `path`
// return what the infinite lights (background, environment) send along the
// ray. Opaque surfaces are two-sided.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "strahl/core/math.h"
#include "strahl/core/ray.h"
#include "strahl/core/sampler.h"
#include "strahl/integrator/surface_hit.h"
#include "strahl/integrator/world.h"

namespace strahl {

// Per-thread counters, summed by the renderer.
struct ShadingStats {
    uint64_t shadowRays = 0;
    uint64_t bounceRays = 0;  // secondary rays other than shadow rays
};

// Which estimators the path tracer combines (the single ones are for tests).
enum class LightSampling { Mis, BsdfOnly, LightOnly };

struct IntegratorOptions {
    int maxDepth = 8;          // path: bounces; 0 shows emitters only
    bool russianRoulette = true;
    int russianRouletteDepth = 1;  // path: roulette after this bounce and every later one
    // path: a path continues with q = min(1, throughput / threshold): only paths
    // whose throughput fell below the threshold play (docs/scene-format.md#render).
    float russianRouletteThreshold = 0.5f;
    // path: the largest channel of one sample's light after one reflection
    // (direct) or more (indirect); 0: not clamped (docs/scene-format.md#render).
    float clampDirect = 0.0f;
    float clampIndirect = 0.0f;
    // path: Cycles' filter glossy, 0 = off (path_integrator.cpp, docs/scene-format.md#render).
    float filterGlossy = 0.0f;
    LightSampling sampling = LightSampling::Mis;
    float aoDistance = 0.0f;   // ao: occluder search distance; 0: the scene's diagonal / 4
    int aoSamples = 1;         // ao: rays per camera sample
    // direct, path: camera rays see no emission (emitting surfaces, lights'
    // shapes, the sky), only what the emitters light (Mitsuba's hide_emitters).
    bool hideEmitters = false;
    // Ray cone of camera rays for texture filtering: footprint width at
    // distance t is coneWidth + coneAngle * t (perspective: coneWidth 0).
    float coneWidth = 0.0f;
    float coneAngle = 0.0f;
};

// A camera packet's rays and closest hits, lane by lane: views of the SoA
// arrays of a RayHitPacket (core/packet.h), for integrators that shade a
// packet at once (Integrator::shadeCameraLanes).
struct CameraLanes {
    int count = 0;                // lanes
    const int* valid = nullptr;   // -1: traced, 0: not
    const float *dirX = nullptr, *dirY = nullptr, *dirZ = nullptr;
    const float *ngX = nullptr, *ngY = nullptr, *ngZ = nullptr;  // Embree's Ng, not unit
    const uint32_t *geomID = nullptr, *instID = nullptr;          // kInvalidId: a miss / not instanced

    template <class Packet>
    static CameraLanes of(const Packet& p, const int* valid) {
        return {Packet::kWidth, valid, p.dir_x, p.dir_y, p.dir_z, p.Ng_x, p.Ng_y, p.Ng_z, p.geomID, p.instID};
    }
};

class Integrator {
public:
    virtual ~Integrator() = default;
    virtual std::string_view name() const = 0;

    // Radiance along a ray towards its closest hit.
    virtual Color shade(const World& world, const SurfaceHit& hit, Sampler& sampler,
                        ShadingStats& stats) const = 0;
    // Radiance along a ray that hit nothing.
    virtual Color miss(const World& world, const Ray& ray) const = 0;
    // Camera packets (at most 32 lanes): shades the traced lanes it can from
    // the accelerator's hit alone, without a SurfaceHit or a sampler, writing
    // radiance[lane] and setting bit `lane` of the returned mask. The renderer
    // shades every other traced lane with shade() or miss(). The values must
    // be shade()'s and miss()'s bit for bit, finite (a non-finite one as 0,
    // as shadeCameraSample drops it). The default shades none; eyelight and
    // normal shade hits on meshes without vertex normals this way, where the
    // per-lane calls cost as much as Embree's traversal (issue 20).
    virtual uint32_t shadeCameraLanes(const World& /*world*/, const CameraLanes& /*lanes*/,
                                      Color* /*radiance*/) const {
        return 0;
    }
};

std::span<const std::string_view> integratorNames();

// Throws strahl::Error naming the integrator and the valid names if unknown.
void requireIntegratorName(std::string_view name);
std::unique_ptr<Integrator> makeIntegrator(std::string_view name, const World& world,
                                           const IntegratorOptions& options = {});

}  // namespace strahl
