#pragma once
// What every light kind's sampling takes and gives (light.h has the family),
// and small helpers the kinds share.

#include <cmath>

#include "strahl/core/error.h"
#include "strahl/core/math.h"

namespace strahl {

class TextureSystem;

// Where the light is sampled from: a surface point with its geometric normal
// (zero for a point not on a surface). Only the sky uses n: it samples the
// hemisphere n points into, so n should face the side being shaded.
// `textures` is the world's, for lights that read images: a spot's or a
// projector's, a patterned emissive triangle's.
struct LightSampleContext {
    Vec3 p{0.0f};
    Vec3 n{0.0f};
    const TextureSystem* textures = nullptr;
};

struct LightLiSample {
    Color L{0.0f};      // incident radiance (delta lights: the irradiance I/r^2 or E)
    Vec3 wi{0.0f};      // unit direction towards the light
    float pdf = 0.0f;   // solid angle density (delta lights: 1)
    Vec3 pLight{0.0f};  // the sampled point (finite lights), for the shadow ray; unused at infinity
    bool atInfinity = false;
};

namespace light_detail {

inline float mean(const Color& c) {
    return (c.r + c.g + c.b) / 3.0f;
}
inline bool isBlack(const Color& c) {
    return c.r == 0.0f && c.g == 0.0f && c.b == 0.0f;
}

// A local direction (z along the unit axis) in world space.
inline Vec3 aroundAxis(const Vec3& local, const Vec3& axis) {
    Vec3 b1, b2;
    orthonormalBasis(axis, b1, b2);
    return local.x * b1 + local.y * b2 + local.z * axis;
}

// A direction handed to the sampling code must be unit length; 1e-3 lets a
// direction typed with 4-5 significant digits pass.
inline bool isUnit(const Vec3& v) {
    return isFinite(v) && std::abs(glm::length(v) - 1.0f) < 1e-3f;
}

// Throws "light <index>: <what> (r, g, b) must be finite and >= 0".
inline void checkColor(size_t index, const char* what, const Color& c) {
    if (!isFinite(c) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f)
        fail("light ", index, ": ", what, " (", c.r, ", ", c.g, ", ", c.b,
             ") must be finite and >= 0");
}

// A light direction from the scene file: a non-zero vector, normalised.
template <typename Json>
Vec3 nonZeroDirection(const Json& v) {
    const Vec3 d = v.vec3();
    if (d == Vec3(0.0f)) v.fail("must be non-zero");
    return unitVector(d);
}

// The axis of a light at `position` from the scene file: exactly one of
// "direction" (non-zero) and "look_at" (a point other than the position),
// normalised. Spot and projector lights read it alike.
template <typename Json>
Vec3 axisFrom(const Json& v, const Vec3& position) {
    if (v.has("direction") == v.has("look_at")) v.fail("give exactly one of 'direction' and 'look_at'");
    if (auto direction = v.find("direction")) return nonZeroDirection(*direction);
    const auto target = v.get("look_at");
    const Vec3 d = target.vec3() - position;
    if (d == Vec3(0.0f)) target.fail("must differ from the position");
    return unitVector(d);
}

}  // namespace light_detail
}  // namespace strahl
