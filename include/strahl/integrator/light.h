#pragma once
// Lights and how the path tracer samples them (next-event estimation).
//
//   point        radiant intensity I (W/sr) from a point
//   spot         a point light inside a cone, smoothstep falloff in cos(angle)
//                from 1 inside cosFalloffStart to 0 outside cosTotalWidth
//   directional  irradiance E from a direction; with an angular radius r > 0 it
//                is a sun disk of uniform radiance E / (pi sin^2 r), sampled
//                uniformly in its cone
//   triangle     one emissive triangle of an area light (emissive meshes are
//                split into these), world space, sampled uniformly in solid
//                angle (spherical triangle, Arvo 1995) when it subtends between
//                3e-4 sr and 6.22 sr, else uniformly by area
//   environment  a lat-long radiance map at infinity, importance-sampled by a
//                piecewise-constant 2D distribution weighted by sin(theta)
//   sky          constant radiance from every direction, sampled cosine-weighted
//                around the surface normal (uniformly for a point off surfaces)
//
// docs/lights.md derives every density and states units. Lat-long convention
// (environment_map.h): +y up, the image centre towards +x, its left edge towards
// -x, u = 1/4 towards -z; not mirrored when seen from inside.

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "strahl/core/bounds.h"
#include "strahl/core/distribution.h"
#include "strahl/core/math.h"
#include "strahl/integrator/environment_map.h"

namespace strahl {

struct Light {
    enum class Type { Point, Spot, Directional, Triangle, Environment, Sky };
    Type type = Type::Point;
    Vec3 position{0.0f};                // point, spot
    Vec3 direction{0.0f, -1.0f, 0.0f};  // spot axis / directional travel direction (unit)
    Color intensity{1.0f};              // point, spot: W/sr per channel
    Color irradiance{1.0f};             // directional: W/m^2 on a facing surface
    float cosFalloffStart = 1.0f;       // spot: full intensity inside this cone
    float cosTotalWidth = 0.0f;         // spot: zero outside this cone
    float angularRadius = 0.0f;         // directional: sun disk half-angle, radians (0: delta)
    Vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};  // triangle, world space; front = counter-clockwise
    Color radiance{0.0f};               // triangle: emitted radiance; sky: radiance
    bool twoSided = false;              // triangle: emits from both faces
    std::shared_ptr<const EnvironmentMap> environment;  // environment
    Mat3 worldToEnvironment{1.0f};  // environment: rotation (orthonormal) into map space
    Color scale{1.0f};              // environment: multiplies the map

    bool isDelta() const;     // point, spot, delta directional
    bool isInfinite() const;  // directional, environment, sky
};

// Where the light is sampled from: a surface point with its geometric normal
// (zero for a point not on a surface). Only the sky uses n: it samples the
// hemisphere n points into, so n should face the side being shaded.
struct LightSampleContext {
    Vec3 p{0.0f};
    Vec3 n{0.0f};
};

struct LightLiSample {
    Color L{0.0f};      // incident radiance (delta lights: the irradiance I/r^2 or E)
    Vec3 wi{0.0f};      // unit direction towards the light
    float pdf = 0.0f;   // solid angle density (delta lights: 1)
    Vec3 pLight{0.0f};  // the sampled point (finite lights), for the shadow ray; unused at infinity
    bool atInfinity = false;
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
// Radiance leaving a triangle light at a point towards w (0 behind a one-sided one).
Color triangleLe(const Light& light, const Vec3& w);
// Total emitted power estimate (W, average of RGB) for power-proportional light
// selection: point 4 pi I, spot 2 pi I (1 - (cosStart + cosWidth) / 2), triangle
// pi A L (twice if two-sided); infinite lights use the scene's bounding sphere of
// radius R: directional pi R^2 E (the flux through the sphere's cross-section),
// environment and sky 4 pi^2 R^2 L (L the mean radiance: irradiance pi L on each
// point of the sphere's area 4 pi R^2).
float lightPower(const Light& light, const Bounds3& sceneBounds);

// The lights of a scene and the discrete distribution that picks one per
// next-event estimate, proportional to power (uniform if every power is 0).
class LightSet {
public:
    LightSet() = default;
    // Throws strahl::Error naming the light for parameters the sampling code
    // cannot handle: negative or non-finite colours, a non-unit direction, spot
    // cosines out of order, an angular radius outside [0, pi/2], an environment
    // light without a map or with a non-rotation worldToEnvironment.
    LightSet(std::vector<Light> lights, const Bounds3& sceneBounds);

    const std::vector<Light>& lights() const { return lights_; }
    bool empty() const { return lights_.empty(); }
    // Index of the light picked by u in [0, 1) and its probability.
    std::optional<std::pair<uint32_t, float>> choose(float u) const;
    float pmf(uint32_t index) const;
    // Indices of the infinite lights (what an escaping ray sees).
    const std::vector<uint32_t>& infiniteLights() const { return infinite_; }

private:
    std::vector<Light> lights_;
    Distribution1D distribution_;  // over the lights' powers
    std::vector<uint32_t> infinite_;
};

}  // namespace strahl
