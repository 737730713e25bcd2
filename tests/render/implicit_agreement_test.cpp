// Implicit shapes through the whole renderer: Embree's BVH and the naive
// tracer run the same ImplicitShape code, so every pixel whose first hit is an
// implicit shape (or nothing) is bit-identical between them, with every
// integrator; pixels on the floor *mesh* agree to float rounding only (Embree's
// triangle kernel is not the naive tracer's watertight test), and a scene
// without meshes is bit-identical everywhere. Renders are bit-identical for any
// thread count and tile size, and a cone whose apex (where ∇f = 0) is in view
// shades to finite values everywhere.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "strahl/integrator/surface_hit.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene_builder.h"
#include "render_helpers.h"
#include "sanitizers/sanitized.h"
#include "test_support.h"

namespace strahl {
namespace {

// 64 x 48, 1 spp: a floor mesh, a torus, blobs, a formula surface with a box,
// a CSG (a sphere minus a rotated torus, smooth-unioned with a superellipsoid),
// lit by a point and a directional light.
const std::string kScene = R"({
  "camera": { "eye": [0, 2.6, 5.5], "look_at": [0, 0.6, 0], "fov": 42 },
  "film": { "width": 64, "height": 48 },
  "render": { "integrator": "direct", "spp": 1 },
  "background": [0.2, 0.25, 0.3],
  "materials": [ { "name": "floor", "color": 0.6 }, { "name": "gold", "color": [0.9, 0.6, 0.2] },
                 { "name": "red", "color": [0.8, 0.2, 0.2] } ],
  "shapes": [
    { "type": "mesh", "name": "floor", "material": "floor",
      "positions": [[-8, 0, -8], [8, 0, -8], [8, 0, 8], [-8, 0, 8]], "indices": [0, 2, 1, 0, 3, 2] },
    { "type": "implicit", "name": "torus", "material": "gold",
      "surface": { "type": "torus", "major_radius": 0.6, "minor_radius": 0.2 }, "cells": 16,
      "transform": [ { "rotate": { "axis": [1, 0, 0], "angle": -60 } }, { "translate": [-1.6, 0.7, 0.2] } ] },
    { "type": "implicit", "name": "blobs", "material": "red",
      "surface": { "type": "blobs", "threshold": 0.3, "blobs": [
        { "center": [0, 0, 0], "radius": 0.7 }, { "center": [0.45, 0.35, 0], "radius": 0.55 },
        { "center": [-0.2, 0.45, 0.3], "radius": 0.5, "strength": 0.8 } ] }, "cells": 12,
      "transform": [ { "translate": [1.6, 0.55, 0.3] } ] },
    { "type": "implicit", "name": "tanglecube",
      "surface": { "type": "formula", "f": "x^4 - 5*x^2 + y^4 - 5*y^2 + z^4 - 5*z^2 + c",
                   "parameters": { "c": 11.8 } },
      "box": [[-3, -3, -3], [3, 3, 3]], "cells": 10,
      "transform": [ { "scale": 0.25 }, { "rotate": { "axis": [0, 1, 0], "angle": 25 } },
                     { "translate": [0, 0.8, -1.6] } ] },
    { "type": "implicit", "name": "csg", "material": "gold",
      "surface": { "type": "smooth_union", "blend": 0.2, "operands": [
        { "type": "difference", "operands": [
          { "type": "sphere", "radius": 0.5 },
          { "type": "torus", "major_radius": 0.5, "minor_radius": 0.18,
            "transform": [ { "rotate": { "axis": [1, 0, 0], "angle": 90 } } ] } ] },
        { "type": "superellipsoid", "radii": [0.3, 0.3, 0.3], "e1": 0.3, "e2": 0.3,
          "transform": [ { "translate": [0, 0.55, 0] } ] } ] },
      "cells": 12, "transform": [ { "translate": [0, 0.5, 0.9] } ] }
  ],
  "lights": [ { "type": "point", "position": [-2, 5, 3], "intensity": 30 },
              { "type": "directional", "direction": [0.4, -1, -0.3], "irradiance": 0.7 } ]
})";

using test::render;
using test::Rendered;

const SceneDesc& scene() {
    static const SceneDesc desc = parseSceneText(kScene, "implicit_agreement.json");
    return desc;
}

// The primid colour of (geomID, primID): what the primid integrator shades.
Color primIdColour(const World& world, uint32_t geomID, uint32_t primID) {
    Hit hit;
    hit.t = 1.0f;
    hit.geomID = geomID;
    hit.primID = primID;
    Sampler rng;
    ShadingStats stats;
    return makeIntegrator("primid", world)->shade(world, SurfaceHit(world, Ray{}, hit), rng, stats);
}

// Which pixels see the floor mesh (geomID 0) first, from a primid render.
std::vector<bool> floorPixels(const SceneDesc& desc) {
    const World world = buildWorld(desc, BuildOptions{});
    const Color floor0 = primIdColour(world, 0, 0), floor1 = primIdColour(world, 0, 1);
    const std::vector<float> ids = render(desc, AccelKind::Embree, "primid").beauty;
    std::vector<bool> floor(ids.size() / 3);
    for (size_t p = 0; p < floor.size(); ++p) {
        const Color c(ids[3 * p], ids[3 * p + 1], ids[3 * p + 2]);
        floor[p] = c == floor0 || c == floor1;
    }
    return floor;
}

// Compares two renders value by value: pixels not in `looser` must be
// bit-identical; pixels in it may differ by `relative` (reported as a count
// and the first few places, so a failure says where).
void expectAgree(const std::vector<float>& a, const std::vector<float>& b, int channels, int width,
                 const char* what, const std::vector<bool>& looser = {}, float relative = 0.0f) {
    ASSERT_EQ(a.size(), b.size()) << what;
    int differing = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i]))) continue;
        const size_t pixel = i / size_t(channels);
        const bool loose = pixel < looser.size() && looser[pixel];
        if (loose && std::abs(a[i] - b[i]) <= relative * std::max(std::abs(a[i]), std::abs(b[i])))
            continue;
        if (++differing <= 5)
            ADD_FAILURE() << what << ": pixel (" << pixel % size_t(width) << ", "
                          << pixel / size_t(width) << ") channel " << i % size_t(channels) << ": "
                          << a[i] << " vs " << b[i] << (loose ? " (floor)" : "");
    }
    EXPECT_EQ(differing, 0) << what << ": values differ";
}

void expectIdentical(const std::vector<float>& a, const std::vector<float>& b, int channels,
                     int width, const char* what) {
    expectAgree(a, b, channels, width, what);
}

// Embree's triangle kernel and the naive tracer's watertight test are
// different float computations: hits on the floor mesh agree to ~1e-7
// relative, not bit for bit (tests/reference/naive_accel_test.cpp allows 1e-5
// in t). Everything the implicit shapes produce runs the same code and must be
// bit-identical.
constexpr float kMeshRelative = 1e-5f;

// How many pixels of an RGB image are not black: the scene is really in view.
int litPixels(const std::vector<float>& rgb) {
    int lit = 0;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3) lit += rgb[i] + rgb[i + 1] + rgb[i + 2] > 0.0f;
    return lit;
}

int count(const std::vector<bool>& mask) {
    return static_cast<int>(std::count(mask.begin(), mask.end(), true));
}

TEST(ImplicitAgreement, DirectIntegratorEmbreeAndNaiveAreIdentical) {
    const int w = scene().film.width, h = scene().film.height;
    const std::vector<bool> floor = floorPixels(scene());
    EXPECT_GT(count(floor), w * h / 4);
    EXPECT_LT(count(floor), w * h - w * h / 8);  // and the implicit shapes cover the rest
    const Rendered embree = render(scene(), AccelKind::Embree, "direct");
    const Rendered naive = render(scene(), AccelKind::Naive, "direct");
    expectAgree(embree.beauty, naive.beauty, 3, w, "direct beauty", floor, kMeshRelative);
    expectAgree(embree.depth, naive.depth, 1, w, "depth AOV", floor, kMeshRelative);
    expectAgree(embree.normal, naive.normal, 3, w, "normal AOV", floor, kMeshRelative);
    EXPECT_GT(litPixels(embree.beauty), w * h / 2);
}

TEST(ImplicitAgreement, DebugIntegratorsEmbreeAndNaiveAreIdentical) {
    const int w = scene().film.width, h = scene().film.height;
    const std::vector<bool> floor = floorPixels(scene());
    for (const char* integrator : {"normal", "depth", "primid", "eyelight"}) {
        SCOPED_TRACE(integrator);
        const Rendered embree = render(scene(), AccelKind::Embree, integrator);
        const Rendered naive = render(scene(), AccelKind::Naive, integrator);
        expectAgree(embree.beauty, naive.beauty, 3, w, integrator, floor, kMeshRelative);
        // Nearly every pixel sees a surface (the floor fills the lower part).
        EXPECT_GT(litPixels(embree.beauty), w * h / 2);
    }
}

// The same scene without the floor mesh: every pixel, bit for bit.
TEST(ImplicitAgreement, WithoutMeshesEveryPixelIsBitIdentical) {
    SceneDesc desc = scene();
    desc.shapes.erase(desc.shapes.begin());
    const int w = desc.film.width;
    for (const char* integrator : {"direct", "primid", "normal"}) {
        SCOPED_TRACE(integrator);
        const Rendered embree = render(desc, AccelKind::Embree, integrator);
        const Rendered naive = render(desc, AccelKind::Naive, integrator);
        expectIdentical(embree.beauty, naive.beauty, 3, w, integrator);
        expectIdentical(embree.depth, naive.depth, 1, w, "depth AOV");
        expectIdentical(embree.normal, naive.normal, 3, w, "normal AOV");
    }
}

TEST(ImplicitAgreement, EveryImplicitShapeIsInView) {
    // The agreement above means something only if the implicit shapes are hit:
    // count the distinct primid colours (one per (geomID, primID)).
    const Rendered primid = render(scene(), AccelKind::Embree, "primid");
    std::vector<std::array<float, 3>> colours;
    for (size_t i = 0; i + 2 < primid.beauty.size(); i += 3) {
        const std::array<float, 3> c{primid.beauty[i], primid.beauty[i + 1], primid.beauty[i + 2]};
        if (std::find(colours.begin(), colours.end(), c) == colours.end()) colours.push_back(c);
    }
    // Floor (2 triangles) + many cells of each of the 4 implicit shapes.
    EXPECT_GT(colours.size(), 40u);

    // Each implicit shape alone, rendered with depth, covers pixels.
    const SceneDesc& desc = scene();
    for (size_t shape = 1; shape < desc.shapes.size(); ++shape) {
        SceneDesc only = desc;
        only.shapes = {desc.shapes[shape]};
        const Rendered depth = render(only, AccelKind::Embree, "depth");
        EXPECT_GT(litPixels(depth.beauty), 40) << desc.shapes[shape].name;
    }
}

TEST(ImplicitAgreement, BitIdenticalForAnyThreadCountAndTileSize) {
    // A quarter of the pixels under the sanitizers (still several 8-pixel tiles
    // per row, and two 32-pixel ones): determinism needs the tiling, not the detail.
    SceneDesc desc = scene();
    test::shrinkFilmWhenSanitized(desc, 2);
    for (const AccelKind accel : {AccelKind::Embree, AccelKind::Naive}) {
        SCOPED_TRACE(accelName(accel));
        const int w = desc.film.width;
        const Rendered one = render(desc, accel, "direct", 1, 32);
        const Rendered two = render(desc, accel, "direct", 2, 32);
        const Rendered tiles8 = render(desc, accel, "direct", 2, 8);
        const Rendered tiles8one = render(desc, accel, "direct", 1, 8);
        expectIdentical(one.beauty, two.beauty, 3, w, "1 vs 2 threads");
        expectIdentical(one.beauty, tiles8.beauty, 3, w, "tile 32 vs 8");
        expectIdentical(one.beauty, tiles8one.beauty, 3, w, "tile 32 vs 8, 1 thread");
        expectIdentical(one.depth, tiles8.depth, 1, w, "depth AOV, tile 32 vs 8");
        expectIdentical(one.normal, two.normal, 3, w, "normal AOV, 1 vs 2 threads");
    }
}

// A double cone x² + y² − z² = 0 (closed-form quadric) clipped to a box, apex
// at the origin, where ∇f = 0: the normal there must fall back to facing the
// ray, never NaN.
std::string coneScene(const std::string& camera) {
    return R"({ "camera": )" + camera + R"(,
      "film": { "width": 33, "height": 33 },
      "shapes": [
        { "type": "mesh", "positions": [[-4, -2, -4], [4, -2, -4], [4, -2, 4], [-4, -2, 4]],
          "indices": [0, 2, 1, 0, 3, 2] },
        { "type": "implicit", "surface": { "type": "quadric", "coefficients": { "xx": 1, "zz": 1, "yy": -1 } },
          "box": [[-1, -1, -1], [1, 1, 1]] } ],
      "lights": [ { "type": "point", "position": [1, 3, 2], "intensity": 10 },
                  { "type": "directional", "direction": [0, -1, 0] } ] })";
}

void expectAllFinite(const std::vector<float>& values, const char* what) {
    int bad = 0;
    for (const float v : values) bad += !std::isfinite(v);
    EXPECT_EQ(bad, 0) << what << ": non-finite values";
}

TEST(ImplicitAgreement, ConeApexInViewShadesFinite) {
    // A perspective view from the side and above (apex in the middle of the
    // image), and an orthographic view straight down the axis whose centre ray
    // hits the apex exactly.
    const std::string cameras[] = {
        R"({ "eye": [1.5, 1.2, 2.5], "look_at": [0, 0, 0], "fov": 50 })",
        R"({ "type": "orthographic", "eye": [0, 5, 0], "back": [0, 1, 0], "up": [0, 0, -1],
             "window": [-1, 1, -1, 1] })"};
    for (const std::string& camera : cameras) {
        SCOPED_TRACE(camera);
        const SceneDesc desc = parseSceneText(coneScene(camera), "cone.json");
        const std::vector<bool> floor = floorPixels(desc);
        for (const char* integrator : {"direct", "normal", "eyelight", "depth"}) {
            SCOPED_TRACE(integrator);
            const Rendered embree = render(desc, AccelKind::Embree, integrator);
            const Rendered naive = render(desc, AccelKind::Naive, integrator);
            expectAllFinite(embree.beauty, "beauty");
            expectAllFinite(embree.normal, "normal AOV");
            expectAllFinite(naive.beauty, "naive beauty");
            expectAgree(embree.beauty, naive.beauty, 3, 33, "embree vs naive", floor, kMeshRelative);
            // The centre pixel sees the cone at its apex (not the floor, not a miss).
            const size_t centre = 16 * 33 + 16;
            EXPECT_TRUE(std::isfinite(embree.depth[centre]));
            const float n = embree.normal[3 * centre] * embree.normal[3 * centre] +
                            embree.normal[3 * centre + 1] * embree.normal[3 * centre + 1] +
                            embree.normal[3 * centre + 2] * embree.normal[3 * centre + 2];
            EXPECT_NEAR(n, 1.0f, 1e-3f) << "a unit normal at the apex";
        }
    }
    // Straight down the axis, the centre ray meets the apex at depth 5 exactly.
    const SceneDesc down = parseSceneText(coneScene(cameras[1]), "cone.json");
    const Rendered r = render(down, AccelKind::Embree, "normal");
    const size_t centre = 16 * 33 + 16;
    EXPECT_NEAR(r.depth[centre], 5.0f, 1e-4f);
    // The apex normal faces the ray (up), as the fallback promises.
    EXPECT_NEAR(r.normal[3 * centre + 1], 1.0f, 1e-4f);
}

}  // namespace
}  // namespace strahl
