#pragma once
// Rendering a SceneDesc in a test, and the list of regression scenes: shared by
// the render-module tests that compare images.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "strahl/render/renderer.h"
#include "strahl/scene/scene_builder.h"
#include "test_support.h"

namespace strahl::test {

// How renderFilm renders a SceneDesc. The defaults are the scene's own
// settings and those of a plain `strahl render`. Every member has an
// initializer, so designated initializers may name any subset (in this order).
struct RenderSetup {
    std::vector<AovKind> aovs{};  // the film's AOVs besides beauty
    AccelKind accel = AccelKind::Embree;
    std::string integrator{};  // empty: desc.render.integrator
    int threads = 0;           // for the BVH build and the render; 0: all hardware threads
    int tile = 32;
    std::optional<int> spp{};                 // default: desc.render.spp (one pass)
    std::optional<uint64_t> seed{};           // default: desc.render.seed
    std::optional<LightSampling> sampling{};  // default: buildIntegratorOptions' (MIS)
    PacketMode packets = PacketMode::Auto;
    AdaptiveSampling adaptive{};  // when enabled, the film tracks convergence
};

// The whole film of `desc` rendered as `setup` says: the scene built, its
// camera, integrator options and pixel filter, one renderImage pass.
inline Film renderFilm(const SceneDesc& desc, const RenderSetup& setup = {}) {
    BuildOptions build;
    build.accel = setup.accel;
    build.threads = setup.threads;
    const BuiltScene scene = buildScene(desc, build);
    const World& world = scene.world;
    const Camera camera = buildCamera(scene.camera, desc.film.width, desc.film.height);
    IntegratorOptions integratorOptions = buildIntegratorOptions(desc, camera);
    if (setup.sampling) integratorOptions.sampling = *setup.sampling;
    const auto integrator =
        makeIntegrator(setup.integrator.empty() ? desc.render.integrator : setup.integrator, world,
                       integratorOptions);
    Film film(desc.film.width, desc.film.height, PixelRect{0, 0, desc.film.width, desc.film.height},
              setup.aovs);
    if (setup.adaptive.enabled()) film.trackConvergence();
    RenderOptions options;
    options.packets = setup.packets;
    options.adaptive = setup.adaptive;
    options.threads = setup.threads;
    options.tileSize = setup.tile;
    options.spp = setup.spp.value_or(desc.render.spp);
    options.seed = setup.seed.value_or(desc.render.seed);
    options.filter = buildPixelFilter(desc.film);
    renderImage(world, camera, *integrator, film, options);
    return film;
}

// The resolved beauty (RGB per pixel) of renderFilm(desc).
inline std::vector<float> renderBeauty(const SceneDesc& desc, const RenderSetup& setup = {}) {
    return renderFilm(desc, setup).resolveBeauty();
}

// Fraction of pixels whose beauty (RGB) differs by more than 2 % of the
// brightest value of `a`: where two tracers of one surface may disagree
// (silhouettes, rims) is a few pixels, a wrong surface many.
inline double differingPixels(const std::vector<float>& a, const std::vector<float>& b) {
    float peak = 0.0f;
    for (float v : a) peak = std::max(peak, v);
    int differing = 0;
    for (size_t i = 0; i < a.size(); i += 3) {
        const float d = std::abs(a[i] - b[i]) + std::abs(a[i + 1] - b[i + 1]) + std::abs(a[i + 2] - b[i + 2]);
        if (d > 0.02f * peak) ++differing;
    }
    return double(differing) / double(a.size() / 3);
}

// The sum of every channel of an image.
inline double channelSum(const std::vector<float>& image) {
    double s = 0.0;
    for (float v : image) s += v;
    return s;
}

// The mean of every channel of an image.
inline double channelMean(const std::vector<float>& image) {
    return channelSum(image) / double(image.size());
}

struct Rendered {
    std::vector<float> beauty, depth, normal;
};

// The whole film of `desc` with `integrator` (one pass of desc's spp), beauty
// plus the depth and normal AOVs.
inline Rendered render(const SceneDesc& desc, AccelKind accel, const std::string& integrator,
                       int threads = 2, int tile = 32) {
    const Film film = renderFilm(desc, {.aovs = {AovKind::Normal, AovKind::Depth},
                                        .accel = accel,
                                        .integrator = integrator,
                                        .threads = threads,
                                        .tile = tile});
    return Rendered{film.resolveBeauty(), film.resolveAov(AovKind::Depth),
                    film.resolveAov(AovKind::Normal)};
}

// The names (file stems) of every scene in scenes/regression/, sorted.
inline std::vector<std::string> regressionScenes() {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(sourceDir() / "scenes/regression")) {
        if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

// Names parameterised tests after their scene ("…/instances", not "…/5").
inline std::string sceneTestName(const ::testing::TestParamInfo<std::string>& scene) {
    return scene.param;
}

}  // namespace strahl::test
