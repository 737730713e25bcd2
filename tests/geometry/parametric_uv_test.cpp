// Texture coordinates of parametric surfaces: a hit's uv is the surface's
// (u, v) normalised over the domain, its dpdu the tangent ∂p/∂uv.x — parallel
// to ∂u f, in the same space as p — and its uvDensity the uv length per world
// length there, in both the direct and the tessellated mode, and under an
// instance transform.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <random>

#include "ray_probes.h"
#include "strahl/core/transform.h"
#include "strahl/geometry/parametric_builtins.h"
#include "strahl/geometry/parametric_grid.h"
#include "strahl/geometry/parametric_shape.h"
#include "strahl/geometry/parametric_tessellation.h"
#include "strahl/geometry/surface_interaction.h"

namespace strahl {
namespace {

// Rotated, scaled unevenly and moved: tangents must follow the linear part.
Mat4 unevenPlacement() {
    return glm::rotate(
        glm::scale(glm::translate(Mat4(1.0f), Vec3(0.5f, -0.2f, 0.3f)), Vec3(1.2f, 0.8f, 1.0f)),
        0.7f, Vec3(1.0f, 0.3f, 0.0f));
}

// The world point of the surface at normalised texture coordinates (s, t).
DVec3 worldPoint(const ParametricSurface& surface, const Mat4& toWorld, double s, double t) {
    const ParamDomain& d = surface.domain();
    const DVec3 p = surface.point(0, d.u0 + s * d.width(), d.v0 + t * d.height());
    return DVec3(glm::dmat4(toWorld) * glm::dvec4(p, 1.0));
}

// The surface parameters (u, v) a normalised uv stands for.
DVec3 parametersOf(const ParametricSurface& surface, const Vec2& uv) {
    const ParamDomain& d = surface.domain();
    return DVec3(d.u0 + static_cast<double>(uv.x) * d.width(),
                 d.v0 + static_cast<double>(uv.y) * d.height(), 0.0);
}

// Checks dpdu and uvDensity of `si` against central differences of the world
// surface in uv (independent of the partials the shapes use), and dpdu against
// ∂u f mapped by the linear part.
void expectTextureFrame(const ParametricSurface& surface, const Mat4& toWorld,
                        const SurfaceInteraction& si, const char* where) {
    const double s = si.uv.x, t = si.uv.y;
    // 1e-5 of the domain: central differences err by O(h²) ~ 1e-10 relative,
    // the float uv by ~1e-7 relative — both far below the tolerances.
    const double h = 1e-5;
    const DVec3 dpds =
        (worldPoint(surface, toWorld, s + h, t) - worldPoint(surface, toWorld, s - h, t)) / (2 * h);
    const DVec3 dpdt =
        (worldPoint(surface, toWorld, s, t + h) - worldPoint(surface, toWorld, s, t - h)) / (2 * h);
    const DVec3 dpdu(si.dpdu);
    ASSERT_GT(glm::length(dpdu), 0.0) << where;
    // ∂p/∂uv.x: the direction and length of the world surface's u derivative
    // (float dpdu and uv: 1e-4 relative).
    EXPECT_LT(glm::length(dpdu - dpds) / glm::length(dpds), 1e-4) << where;
    // Parallel to ∂u f mapped like a tangent, pointing the same way.
    const DVec3 params = parametersOf(surface, si.uv);
    const SurfacePoint sp = surface.partials(0, params.x, params.y);
    const DVec3 fu = glm::dmat3(glm::dmat4(toWorld)) * sp.dpdu;
    const double sine = glm::length(glm::cross(glm::normalize(dpdu), glm::normalize(fu)));
    EXPECT_LT(sine, 1e-5) << where;
    EXPECT_GT(glm::dot(dpdu, fu), 0.0) << where;
    // A tangent: perpendicular to the shading normal (which is exact on both modes).
    EXPECT_LT(std::abs(glm::dot(glm::normalize(dpdu), DVec3(si.Ns))), 1e-4) << where;
    // uv length per world length: 1 / sqrt(world area per unit uv area).
    const double density = 1.0 / std::sqrt(glm::length(glm::cross(dpds, dpdt)));
    EXPECT_NEAR(si.uvDensity, density, 1e-4 * density) << where;
}

TEST(ParametricUv, DirectHitsCarryTheirParametersAndTangent) {
    const ParametricSurfacePtr torus = makeParametricTorus(1.0, 0.35);
    const Mat4 toWorld = unevenPlacement();
    const ParametricShape shape(torus, toWorld, ParametricShapeOptions{});
    std::mt19937 rng(31);
    int hits = 0;
    for (int i = 0; i < 3000; ++i) {
        const Ray ray = rayTowards(rng, 5.0, 1.2);
        const Hit hit = nearestHit(shape, ray);
        if (!hit.valid()) continue;
        ++hits;
        const SurfaceInteraction si = shape.interaction(ray, hit);
        // uv is the hit's (u, v), normalised: f there is the hit point (to the
        // float rounding of uv, ~1e-7 of the torus' size).
        const DVec3 params = shape.hitParameters(hit);
        const DVec3 fromUv = parametersOf(*torus, si.uv);
        EXPECT_NEAR(fromUv.x, params.x, 1e-6) << "ray " << i;
        EXPECT_NEAR(fromUv.y, params.y, 1e-6) << "ray " << i;
        EXPECT_LT(glm::length(worldPoint(*torus, toWorld, si.uv.x, si.uv.y) - DVec3(si.p)), 1e-5)
            << "ray " << i;
        expectTextureFrame(*torus, toWorld, si, "direct");
    }
    EXPECT_GT(hits, 500);
}

TEST(ParametricUv, TessellatedHitsCarryTheirParametersAndTangent) {
    const ParametricSurfacePtr torus = makeParametricTorus(1.0, 0.35);
    const Mat4 toWorld = unevenPlacement();
    ParametricGridOptions options;
    options.initialSegmentsU = options.initialSegmentsV = 64;
    Tessellation t = tessellateParametric(*torus, buildParametricGrid(*torus, options),
                                          ParametricNormals::Exact);
    TriangleMesh mesh = t.mesh;
    mesh.transform(toWorld);
    const TessellatedSurface tess(torus, std::move(t), toWorld, ParametricNormals::Exact);
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 2000; ++i) {
        const uint32_t prim = static_cast<uint32_t>(rng() % mesh.triangleCount());
        float b1 = unit(rng), b2 = unit(rng);
        if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
        const SurfaceInteraction si = tess.interaction(mesh, prim, b1, b2);
        // uv is the normalised (u, v) the triangle's corners interpolate to...
        const Vec2 params = tess.parameters(mesh, prim, b1, b2);
        const DVec3 fromUv = parametersOf(*torus, si.uv);
        EXPECT_NEAR(fromUv.x, params.x, 1e-6) << "triangle " << prim;
        EXPECT_NEAR(fromUv.y, params.y, 1e-6) << "triangle " << prim;
        // ...and f there is the hit point up to the tessellation's error: the
        // chord error of 64 segments around the outer ring, (2π/64)²/8 of its
        // 1.35 radius, ~2e-3 after the 1.2 scale, and about as much along the
        // surface (barycentrics are not arc length).
        EXPECT_LT(glm::length(worldPoint(*torus, toWorld, si.uv.x, si.uv.y) - DVec3(si.p)), 1e-2)
            << "triangle " << prim;
        expectTextureFrame(*torus, toWorld, si, "tessellated");
    }
}

TEST(ParametricUv, InstancedInteractionsMatchTheShapePlacedDirectly) {
    // A similarity map (rotation, uniform scale, move): transformInteraction()
    // takes an object-space interaction to the world exactly as the shape's
    // own transform does, dpdu by the linear part and uvDensity by the scale.
    const ParametricSurfacePtr sphere = makeParametricSphere(0.8);
    const Mat4 toWorld =
        glm::rotate(glm::scale(glm::translate(Mat4(1.0f), Vec3(0.3f, 0.1f, -0.4f)), Vec3(1.7f)),
                    1.1f, Vec3(0.2f, 1.0f, 0.5f));
    const ParametricShape placed(sphere, toWorld, ParametricShapeOptions{});
    const ParametricShape prototype(sphere, Mat4(1.0f), ParametricShapeOptions{});
    const Mat4 toObject = glm::inverse(toWorld);
    std::mt19937 rng(12);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        const Ray ray = rayTowards(rng, 5.0, 1.3);
        const Hit hit = nearestHit(placed, ray);
        if (!hit.valid()) continue;
        const Ray local = transformRay(toObject, ray);
        const Hit localHit = nearestHit(prototype, local);
        // The rounding of the mapped ray may turn a silhouette graze into a miss.
        if (!localHit.valid()) continue;
        ++hits;
        const SurfaceInteraction world = placed.interaction(ray, hit);
        const SurfaceInteraction mapped = transformInteraction(
            prototype.interaction(local, localHit), toWorld, normalMatrix(toWorld));
        EXPECT_LT(glm::length(mapped.uv - world.uv), 1e-5f) << "ray " << i;
        EXPECT_LT(glm::length(mapped.dpdu - world.dpdu), 1e-4f * glm::length(world.dpdu))
            << "ray " << i;
        EXPECT_NEAR(mapped.uvDensity, world.uvDensity, 1e-4f * world.uvDensity) << "ray " << i;
        expectTextureFrame(*sphere, toWorld, world, "placed sphere");
    }
    EXPECT_GT(hits, 500);
}

}  // namespace
}  // namespace strahl
