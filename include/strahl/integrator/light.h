#pragma once
// Lights and how the path tracer samples them (next-event estimation). A light
// is one kind of a closed family, one header per kind with its parameters,
// scene-file keys, validation, sampling, density and power:
//
//   point        point_light.h        radiant intensity from a point
//   spot         spot_light.h         a point light inside a cone
//   projector    projector_light.h    an image projected through a frustum
//   directional  directional_light.h  irradiance from a direction, or a sun disk ("sun")
//   environment  environment_light.h  a lat-long radiance map at infinity
//   sky          sky_light.h          constant radiance from every direction
//   triangle     triangle_light.h     one emissive triangle of an area light
//                                     (made from emissive meshes, not in scene files)
//
// LightKind lists them; the functions below visit it. docs/lights.md derives
// every density and states units; docs/architecture.md says how to add a kind.

#include <cstdint>
#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include "strahl/core/bounds.h"
#include "strahl/core/closed_family.h"
#include "strahl/core/distribution.h"
#include "strahl/integrator/directional_light.h"
#include "strahl/integrator/environment_light.h"
#include "strahl/integrator/light_bvh.h"
#include "strahl/integrator/light_sample.h"
#include "strahl/integrator/point_light.h"
#include "strahl/integrator/projector_light.h"
#include "strahl/integrator/sky_light.h"
#include "strahl/integrator/spot_light.h"
#include "strahl/integrator/triangle_light.h"

namespace strahl {

// The closed set of light kinds; the order is the order `type` errors list the
// scene-file names in.
using LightKind = std::variant<PointLight, SpotLight, ProjectorLight, DirectionalLight,
                               EnvironmentLight, SkyLight, TriangleLight>;

struct Light {
    LightKind kind;  // a point light of intensity 1 at the origin unless set

    Light() = default;
    template <typename Kind>
        requires std::is_constructible_v<LightKind, Kind>
    Light(Kind k) : kind(std::move(k)) {}  // NOLINT: a kind is a light

    bool isDelta() const;     // point, spot, delta directional
    bool isInfinite() const;  // directional, environment, sky
};

// Samples incident light at ctx from `light`; nullopt if the light contributes
// nothing there (behind a one-sided emitter, outside the spot cone, zero pdf).
std::optional<LightLiSample> sampleLi(const Light& light, const LightSampleContext& ctx,
                                      const Vec2& u);
// Solid-angle density with which sampleLi would produce direction wi, for a ray
// from ctx that reaches the light: for a triangle at pLight (the hit point).
// 0 for delta lights.
float pdfLi(const Light& light, const LightSampleContext& ctx, const Vec3& wi, const Vec3& pLight);
// Radiance an escaping ray in direction dir receives from an infinite light
// (environment, sky, sun disk); 0 for the others.
Color infiniteLe(const Light& light, const Vec3& dir);
// Radiance leaving a triangle light at a point towards w (0 behind a one-sided
// one, and for every other kind).
Color triangleLe(const Light& light, const Vec3& w);
// Total emitted power estimate (W, average of RGB) for power-proportional light
// selection: point 4 pi I, spot 2 pi I (1 - (cosStart + cosWidth) / 2) (linear
// falloff: docs/lights.md), projector E · 4 tanX tanY, triangle pi A L (twice if
// two-sided; patterned: times the pattern's mean); infinite lights use the scene's bounding sphere of
// radius R: directional pi R^2 E (the flux through the sphere's cross-section),
// environment and sky 4 pi^2 R^2 L (L the mean radiance: irradiance pi L on each
// point of the sphere's area 4 pi R^2).
float lightPower(const Light& light, const Bounds3& sceneBounds);

// How next-event estimation picks a light (docs/lights.md, "Choosing a light"):
// by its estimated contribution at the shading point through a light BVH
// (light_bvh.h; the infinite lights, which it does not hold, each as often as
// the whole tree), in proportion to its power, or each emitter (a light of
// the scene, the sky, an emitting shape as a whole) equally often and, within
// an emitting shape, its triangles in proportion to their power (Mitsuba's
// choice).
// Auto, the default, is the BVH for scenes with more than kAutoBvhLights
// finite lights or with two infinite lights or more, else power:
//  - with a few finite lights the tree's cost per choice (two importances per
//    level) outweighs what it saves (bench_convergence: the Cornell box's two
//    emissive triangles take up to 1.2x the time with it); with 1600 lamps it
//    pays (1.2x sooner to fixed sampling's 64-spp error, bench/RESULTS.md);
//  - infinite lights: power weighs a sun against a sky by their powers, so the
//    sky gets few samples even where the sun is blocked, which in an interior
//    is almost everywhere; the tree takes each infinite light as often as the
//    whole tree (pbrt-v4's rule), whose variance from the choice is at most
//    the square of the lights' difference (Sponza under sun and sky: 1.6x
//    sooner to fixed sampling's 64-spp error, 1.7x to its 256-spp error).
enum class LightSelection { Auto, Bvh, Power, UniformEmitters };
inline constexpr size_t kAutoBvhLights = 16;
inline constexpr size_t kAutoBvhInfiniteLights = 2;

// The lights of a scene and the discrete distribution that picks one per
// next-event estimate (uniform if every power is 0).
class LightSet {
public:
    LightSet() = default;
    // Throws strahl::Error naming the light for parameters the sampling code
    // cannot handle: negative or non-finite colours, a non-unit direction, spot
    // cosines out of order, an angular radius outside [0, pi/2], an environment
    // light without a map or with a non-rotation worldToEnvironment.
    LightSet(std::vector<Light> lights, const Bounds3& sceneBounds);
    // With a selection: emitterOf[i] names the emitter light i belongs to
    // (lights of one emitting shape share it); used by UniformEmitters.
    LightSet(std::vector<Light> lights, const Bounds3& sceneBounds, LightSelection selection,
             const std::vector<uint32_t>& emitterOf);

    const std::vector<Light>& lights() const { return lights_; }
    bool empty() const { return lights_.empty(); }
    // Index of the light picked by u in [0, 1) for a receiver at `at` (its
    // point and normal; only the light BVH reads them) and its probability;
    // none if no light can reach it. pmf gives the same probability.
    std::optional<std::pair<uint32_t, float>> choose(float u,
                                                     const LightSampleContext& at = {}) const;
    float pmf(uint32_t index, const LightSampleContext& at = {}) const;
    LightSelection selection() const { return selection_; }
    // Indices of the infinite lights (what an escaping ray sees).
    const std::vector<uint32_t>& infiniteLights() const { return infinite_; }

private:
    std::vector<Light> lights_;
    LightSelection selection_ = LightSelection::Power;
    Distribution1D distribution_;  // Power, UniformEmitters: over the lights' weights
    LightBvh bvh_;                 // Bvh: the finite lights with power
    std::vector<uint32_t> infinite_;
};

}  // namespace strahl
