#pragma once
// Rendering a SceneDesc in a test, and the list of regression scenes: shared by
// the render-module tests that compare images.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "strahl/render/renderer.h"
#include "strahl/scene/scene_builder.h"
#include "test_support.h"

namespace strahl::test {

struct Rendered {
    std::vector<float> beauty, depth, normal;
};

// The whole film of `desc` with `integrator` (one pass of desc's spp), beauty
// plus the depth and normal AOVs.
inline Rendered render(const SceneDesc& desc, AccelKind accel, const std::string& integrator,
                       int threads = 2, int tile = 32) {
    BuildOptions build;
    build.accel = accel;
    build.threads = threads;
    const World world = buildWorld(desc, build);
    const Camera camera = buildCamera(desc.camera, desc.film.width, desc.film.height);
    Film film(desc.film.width, desc.film.height, PixelRect{0, 0, desc.film.width, desc.film.height},
              {AovKind::Normal, AovKind::Depth});
    RenderOptions options;
    options.threads = threads;
    options.tileSize = tile;
    options.spp = desc.render.spp;
    options.seed = desc.render.seed;
    options.filter = buildPixelFilter(desc.film);
    renderImage(world, camera,
                *makeIntegrator(integrator, world, buildIntegratorOptions(desc, camera)), film,
                options);
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
