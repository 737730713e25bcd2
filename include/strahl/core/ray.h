#pragma once
// Rays, hit records and robust spawning of secondary rays.
//
// Secondary rays never use an absolute epsilon. A hit point carries a
// conservative bound on its floating-point error (pError, per axis); the spawn
// function pushes the origin out along the geometric normal just far enough to
// leave that error box, then rounds away from the surface (pbrt-v4, ray.h,
// OffsetRayOrigin). The bound scales with the magnitude of the coordinates, so
// it works for scenes at any scale.

#include <cstdint>

#include "strahl/core/math.h"

namespace strahl {

inline constexpr uint32_t kInvalidId = 0xFFFFFFFFu;

struct Ray {
    Vec3 origin{0.0f};
    Vec3 dir{0.0f, 0.0f, -1.0f};
    float tnear = 0.0f;
    float tfar = kInfinity;
    // When the ray is cast, in frame time: 0 and 1 are a moving instance's
    // first and last keyframe (core/motion.h); the camera's shutter picks it
    // for camera rays, and secondary rays inherit it.
    float time = 0.0f;

    Vec3 at(float t) const { return origin + t * dir; }
};

// The preliminary hit: only what the accelerator reports. The full surface
// interaction is computed lazily by the scene for the closest hit.
//
// A hit inside an instance (Embree's convention): instID is the instance's ID
// in the top-level scene, geomID and primID name the shape and primitive within
// the instanced prototype, and Ng is in the prototype's object space. t is the
// parameter along the caller's (world-space) ray either way.
struct Hit {
    float t = kInfinity;
    float u = 0.0f, v = 0.0f;  // barycentrics of vertices 1 and 2 (Embree convention)
    Vec3 Ng{0.0f};             // unnormalised geometric normal
    uint32_t geomID = kInvalidId;
    uint32_t primID = kInvalidId;
    uint32_t instID = kInvalidId;  // kInvalidId: not inside an instance

    bool valid() const { return geomID != kInvalidId; }
};

// gamma(n) = n*eps/(1-n*eps): bound on relative error after n float operations
// (pbrt-v4 3.9.1), eps = 2^-24 is the unit roundoff of float.
constexpr float gammaBound(int n) {
    constexpr float eps = 0.5f * std::numeric_limits<float>::epsilon();
    return (static_cast<float>(n) * eps) / (1.0f - static_cast<float>(n) * eps);
}

// Moves p off the surface with geometric normal n (any length, any side) to the
// side that w points to, far enough to escape the error box pError.
Vec3 offsetRayOrigin(const Vec3& p, const Vec3& pError, const Vec3& n, const Vec3& w);

// A ray from a surface point towards direction dir (unbounded).
Ray spawnRay(const Vec3& p, const Vec3& pError, const Vec3& n, const Vec3& dir);

// A shadow ray from a surface point towards target; tfar stops just short of the
// target (1 - shadow epsilon as a fraction of the segment, see ray.cpp).
Ray spawnRayTo(const Vec3& p, const Vec3& pError, const Vec3& n, const Vec3& target);

}  // namespace strahl
