// Adaptive sampling (render/adaptive_sampling.h): the noise measure, the 3 x 3
// stopping rule, and the render loop that skips stopped pixels while keeping
// the image a function of the film alone: the same bits for any threads,
// tiles or packets, and across a stop and resume.

#include "strahl/render/adaptive_sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <string>

#include "render_helpers.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

using test::renderFilm;

// A grey floor and wall under a point light, seen from above at an angle so
// that the top rows see only the black sky: indirect light makes the floor
// noisy, the sky is exactly black.
SceneDesc corner(int spp) {
    return parseSceneText(R"({
      "camera": { "eye": [0, 1, 3], "look_at": [0, 0.8, 0], "fov": 60 },
      "film": { "width": 16, "height": 12 },
      "render": { "integrator": "path", "spp": )" + std::to_string(spp) + R"(, "max_depth": 3 },
      "materials": [ { "name": "grey", "color": 0.7 } ],
      "shapes": [
        { "type": "mesh", "material": "grey", "positions": [[-2,0,-2],[2,0,-2],[2,0,2],[-2,0,2]],
          "indices": [0, 2, 1, 0, 3, 2] },
        { "type": "mesh", "material": "grey", "positions": [[-2,0,-2],[-2,0,2],[-2,1,2],[-2,1,-2]],
          "indices": [0, 1, 2, 0, 2, 3] } ],
      "lights": [ { "type": "point", "position": [0.5, 1.2, 0.5], "intensity": 3 } ]
    })", test::scratchDir("adaptive") / "corner.json");
}

AdaptiveSampling adaptive(float threshold, int minSamples) {
    AdaptiveSampling a;
    a.threshold = threshold;
    a.minSamples = minSamples;
    return a;
}

void addGrey(Film& film, int x, int y, float value) {
    film.addSample(x, y, Color(value), AovSample{});
}

TEST(AdaptiveSampling, NoiseIsTheRelativeStandardErrorAboveADarkFloor) {
    Film film(3, 1, PixelRect{0, 0, 3, 1}, {});
    film.trackConvergence();
    addGrey(film, 0, 0, 1.0f);  // one sample: no variance yet
    addGrey(film, 1, 0, 1.0f);
    addGrey(film, 1, 0, 3.0f);  // mean 2, sample variance 2, of the mean 1
    addGrey(film, 2, 0, 0.0f);
    addGrey(film, 2, 0, 0.0f);  // black: nothing to refine
    EXPECT_EQ(pixelNoise(film, 0, 0), kInfinity);
    EXPECT_NEAR(pixelNoise(film, 1, 0), 1.0 / std::sqrt(4.0 + 0.01), 1e-6);
    EXPECT_EQ(pixelNoise(film, 2, 0), 0.0f);
}

TEST(AdaptiveSampling, APixelStopsOnlyWhenItsWholeNeighbourhoodIsQuiet) {
    ASSERT_EQ(kNeighbourhoodRadius, 1);  // 3 x 3 neighbourhoods below
    Film film(11, 9, PixelRect{0, 0, 11, 9}, {});
    film.trackConvergence();
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 11; ++x) {
            // Flat everywhere but at (5, 4) and the corner (0, 0).
            const bool noisy = (x == 5 && y == 4) || (x == 0 && y == 0);
            addGrey(film, x, y, noisy ? 0.0f : 0.5f);
            addGrey(film, x, y, noisy ? 2.0f : 0.5f);
        }
    EXPECT_EQ(stopConvergedPixels(film, adaptive(0.1f, 2)), 9u + 4u);
    EXPECT_FALSE(film.converged(4, 3));  // one pixel from (5, 4) both ways
    EXPECT_FALSE(film.converged(6, 5));
    EXPECT_TRUE(film.converged(7, 4));  // two pixels away
    EXPECT_TRUE(film.converged(3, 2));
    EXPECT_FALSE(film.converged(1, 1));  // the corner's neighbourhood, clipped to the film
    EXPECT_TRUE(film.converged(2, 1));
    // A stopped pixel stays stopped; running ones are judged again.
    EXPECT_EQ(stopConvergedPixels(film, adaptive(10.0f, 2)), 0u);
    EXPECT_TRUE(film.converged(5, 4));
}

TEST(AdaptiveSampling, DecisionsComeAboutEightTimesPerDoubling) {
    std::vector<int> passes;
    for (int n = 1; n <= 40; ++n)
        if (isDecisionPass(n, 16)) passes.push_back(n);
    EXPECT_EQ(passes, (std::vector<int>{16, 18, 20, 22, 24, 27, 30, 33, 37}));
    EXPECT_TRUE(isDecisionPass(2, 2));
    EXPECT_TRUE(isDecisionPass(3, 2));  // below 8 samples, every pass
}

TEST(AdaptiveSampling, TheFlagsArePartOfTheFilmState) {
    Film film(4, 3, PixelRect{0, 0, 4, 3}, {});
    film.trackConvergence();
    film.setConverged(1, 2);
    std::stringstream state;
    film.writeState(state);
    Film restored(4, 3, PixelRect{0, 0, 4, 3}, {});
    restored.trackConvergence();
    restored.readState(state, "state");
    EXPECT_TRUE(restored.converged(1, 2));
    EXPECT_FALSE(restored.converged(0, 2));
    Film tile(4, 3, PixelRect{0, 0, 4, 3}, {});
    tile.trackConvergence();
    tile.unpackPixels(PixelRect{1, 1, 3, 3}, film.packPixels(PixelRect{1, 1, 3, 3}), "tile");
    EXPECT_TRUE(tile.converged(1, 2));
    Film plain(4, 3, PixelRect{0, 0, 4, 3}, {});
    EXPECT_THROW(plain.merge(film, "adaptive"), Error);
}

TEST(AdaptiveSampling, AThresholdNoPixelFailsStopsEveryPixelAtTheMinimum) {
    const SceneDesc desc = corner(64);
    const Film film = renderFilm(desc, {.aovs = {AovKind::Samples}, .threads = 2,
                                        .adaptive = adaptive(1.0f, 4)});
    for (float n : film.resolveAov(AovKind::Samples)) EXPECT_EQ(n, 4.0f);
}

TEST(AdaptiveSampling, QuietPixelsStopAndNoisyOnesTakeTheBudget) {
    const SceneDesc desc = corner(48);
    const Film film = renderFilm(desc, {.aovs = {AovKind::Samples}, .threads = 2,
                                        .adaptive = adaptive(0.01f, 8)});
    const std::vector<float> samples = film.resolveAov(AovKind::Samples);
    // The top row sees only the black sky, and so do its neighbours.
    for (int x = 0; x < 16; ++x) EXPECT_EQ(samples[size_t(x)], 8.0f) << "sky pixel " << x;
    EXPECT_EQ(*std::max_element(samples.begin(), samples.end()), 48.0f);
    // The floor is noisy: at this threshold most of it takes more than the minimum.
    const auto lit = std::count_if(samples.begin() + 16 * 8, samples.end(),
                                   [](float n) { return n > 8.0f; });
    EXPECT_GT(lit, 16 * 4 / 2);
}

TEST(AdaptiveSampling, SameImageForAnyThreadCountTileSizeAndPacketWidth) {
    const SceneDesc desc = corner(24);
    const AdaptiveSampling a = adaptive(0.02f, 4);
    const Film reference = renderFilm(desc, {.aovs = {AovKind::Samples}, .threads = 1,
                                             .tile = 32, .adaptive = a});
    const std::vector<float> samples = reference.resolveAov(AovKind::Samples);
    ASSERT_LT(*std::min_element(samples.begin(), samples.end()), 24.0f);  // it did adapt
    for (const auto& [threads, tile, packets] :
         {std::tuple{2, 5, PacketMode::Single}, std::tuple{2, 8, PacketMode::Packet8},
          std::tuple{2, 3, PacketMode::Packet16}}) {
        const Film film = renderFilm(desc, {.aovs = {AovKind::Samples}, .threads = threads,
                                            .tile = tile, .packets = packets, .adaptive = a});
        EXPECT_EQ(film.resolveBeauty(), reference.resolveBeauty()) << threads << " " << tile;
        EXPECT_EQ(film.resolveAov(AovKind::Samples), samples) << threads << " " << tile;
    }
}

TEST(AdaptiveSampling, AStoppedAndResumedRenderEqualsOneUninterrupted) {
    const SceneDesc desc = corner(32);
    const AdaptiveSampling a = adaptive(0.02f, 4);
    const Film whole = renderFilm(desc, {.aovs = {AovKind::Samples}, .threads = 2,
                                         .adaptive = a});

    const BuiltScene scene = buildScene(desc, BuildOptions{});
    const Camera camera = buildCamera(scene.camera, 16, 12);
    const auto integrator =
        makeIntegrator("path", scene.world, buildIntegratorOptions(desc, camera));
    Film first(16, 12, PixelRect{0, 0, 16, 12}, {AovKind::Samples});
    first.trackConvergence();
    RenderOptions options;
    options.threads = 2;
    options.spp = 32;
    options.seed = desc.render.seed;
    options.adaptive = a;
    options.passDone = [](int done) { return done < 9; };  // stop after pass 9, past 5 decisions
    const RenderStats stopped = renderImage(scene.world, camera, *integrator, first, options);
    ASSERT_TRUE(stopped.stoppedEarly);
    ASSERT_EQ(stopped.completedPasses, 9);

    // Through the checkpoint state into a new film, as --resume does.
    std::stringstream state;
    first.writeState(state);
    Film resumed(16, 12, PixelRect{0, 0, 16, 12}, {AovKind::Samples});
    resumed.trackConvergence();
    resumed.readState(state, "checkpoint");
    options.passDone = nullptr;
    const RenderStats rest = renderImage(scene.world, camera, *integrator, resumed, options);
    EXPECT_FALSE(rest.stoppedEarly);
    EXPECT_EQ(resumed.resolveBeauty(), whole.resolveBeauty());
    EXPECT_EQ(resumed.resolveAov(AovKind::Samples), whole.resolveAov(AovKind::Samples));
}

// Cancels the render after `tiles` tiles: in the middle of a pass.
struct CancelAfterTiles final : ProgressSink {
    explicit CancelAfterTiles(uint64_t tiles) : left(tiles) {}
    void begin(const std::string&, uint64_t) override {}
    void advance(uint64_t amount) override {
        left = left > amount ? left - amount : 0;
        if (left == 0) cancel = true;
    }
    void end() override {}
    std::atomic<uint64_t> left;
    std::atomic<bool> cancel{false};
};

TEST(AdaptiveSampling, ARenderCancelledInTheMiddleOfAPassResumesExactly) {
    const SceneDesc desc = corner(32);
    const AdaptiveSampling a = adaptive(0.02f, 4);
    const Film whole = renderFilm(desc, {.aovs = {AovKind::Samples}, .threads = 1, .tile = 4,
                                         .adaptive = a});
    const BuiltScene scene = buildScene(desc, BuildOptions{});
    const Camera camera = buildCamera(scene.camera, 16, 12);
    const auto integrator =
        makeIntegrator("path", scene.world, buildIntegratorOptions(desc, camera));
    Film film(16, 12, PixelRect{0, 0, 16, 12}, {AovKind::Samples});
    film.trackConvergence();
    RenderOptions options;
    options.threads = 1;  // so the cut falls after exactly this many tiles
    options.tileSize = 4;  // 12 tiles a pass
    options.spp = 32;
    options.seed = desc.render.seed;
    options.adaptive = a;
    CancelAfterTiles cut(12 * 6 + 5);  // 5 tiles into the 7th pass
    options.progress = &cut;
    options.cancel = &cut.cancel;
    const RenderStats stopped = renderImage(scene.world, camera, *integrator, film, options);
    ASSERT_TRUE(stopped.cancelled);
    options.progress = nullptr;
    options.cancel = nullptr;
    renderImage(scene.world, camera, *integrator, film, options);
    EXPECT_EQ(film.resolveBeauty(), whole.resolveBeauty());
    EXPECT_EQ(film.resolveAov(AovKind::Samples), whole.resolveAov(AovKind::Samples));
}

TEST(AdaptiveSampling, TheImageAgreesWithFixedSampling) {
    const SceneDesc desc = corner(64);
    const Film fixed = renderFilm(desc, {.threads = 2});
    const Film adapted = renderFilm(desc, {.threads = 2, .adaptive = adaptive(0.02f, 8)});
    const double a = test::channelSum(fixed.resolveBeauty());
    const double b = test::channelSum(adapted.resolveBeauty());
    EXPECT_NEAR(b / a, 1.0, 0.02);
}

TEST(AdaptiveSampling, TheRendererRefusesAFilmThatDoesNotMatch) {
    const SceneDesc desc = corner(8);
    const BuiltScene scene = buildScene(desc, BuildOptions{});
    const Camera camera = buildCamera(scene.camera, 16, 12);
    const auto integrator = makeIntegrator("path", scene.world, buildIntegratorOptions(desc, camera));
    Film plain(16, 12, PixelRect{0, 0, 16, 12}, {});
    RenderOptions options;
    options.spp = 8;
    options.adaptive = adaptive(0.01f, 4);
    EXPECT_THROW(renderImage(scene.world, camera, *integrator, plain, options), Error);
    Film tracking(16, 12, PixelRect{0, 0, 16, 12}, {});
    tracking.trackConvergence();
    options.sampleOffset = 8;
    EXPECT_THROW(renderImage(scene.world, camera, *integrator, tracking, options), Error);
}

}  // namespace
}  // namespace strahl
