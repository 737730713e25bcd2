#pragma once
// Shared by the scene tests that check what a material reads at a point: the
// albedo of the BSDF where a downward ray meets (x, y) (a diffuse material's
// colour), through the world's own tracer and shading point.

#include <gtest/gtest.h>

#include "strahl/integrator/surface_hit.h"
#include "strahl/material/material.h"

namespace strahl::test {

inline Color albedoAt(const World& world, float x, float y) {
    Ray ray;
    ray.origin = Vec3(x, y, 1.0f);
    ray.dir = Vec3(0, 0, -1);
    const Hit hit = world.accel->intersect(ray);
    EXPECT_TRUE(hit.valid());
    if (!hit.valid()) return Color(-1.0f);
    const SurfaceHit surface(world, ray, hit);
    return makeBsdf(surface.material(), shadingPointAt(surface.interaction()), world.textures.get())
        .albedo();
}

}  // namespace strahl::test
