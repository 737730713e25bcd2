// The rasterized image agrees with the ray-traced one on the repository's
// mesh-only regression scenes (scenes/regression/, the implicit one excluded),
// with each scene's integrator switched to eyelight, normal, depth and primid
// and one sample per pixel:
//  - the first hit, (geomID, primID) or nothing, is the same on >= 99.9 % of
//    the pixels, for Embree's BVH and for the naive tracer;
//  - where the hits agree, the beauty and the normal and depth AOVs agree to
//    1e-4 (both shade with the same Integrator::shade; t, u, v and Ng come
//    from different float formulas).
// Where may they differ? Only at pixel centres that lie on an edge or within
// float rounding of one (docs/rasterizer.md, "Differences at edges"):
//  - on a silhouette edge the ray tracer's triangles are closed (an edge
//    counts as inside), the rasterizer's tie rule keeps only the left/bottom
//    edges, so such a centre may be a hit in one and a miss in the other;
//  - on an edge shared by two triangles both ray tracers report whichever t
//    rounds smaller (Embree's test is not watertight: it may even miss both),
//    the rasterizer gives the centre to the one triangle that owns the edge;
//  - within rounding of an edge, the float ray (normalised direction, origin on
//    the image plane) and the rasterizer's double-precision edge functions may
//    fall on different sides.
// None of these touches more than a few pixels per scene; the test reports
// how many.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "raster_test_support.h"
#include "strahl/render/renderer.h"
#include "test_support.h"

namespace strahl {
namespace {

using test::sameSurface;
using test::TestScene;

constexpr double kMinAgreeingFraction = 0.999;
constexpr float kValueTolerance = 1e-4f;

SceneDesc regressionScene(const std::string& name) {
    SceneDesc desc = parseSceneFile(test::sourceDir() / "scenes/regression" / (name + ".json"));
    desc.render.spp = 1;
    return desc;
}

class RasterAgreement : public ::testing::TestWithParam<std::string> {};

TEST_P(RasterAgreement, SameFirstHitsAsBothRayTracers) {
    for (AccelKind accel : {AccelKind::Embree, AccelKind::Naive}) {
        SCOPED_TRACE(accelName(accel));
        const TestScene scene(regressionScene(GetParam()), accel);
        RasterStats stats;
        const std::vector<Hit> raster = test::rasterHits(scene, &stats);
        const std::vector<Hit> traced = test::traceHits(scene);
        ASSERT_EQ(raster.size(), traced.size());
        size_t agreeing = 0, hits = 0;
        for (size_t p = 0; p < raster.size(); ++p) {
            agreeing += sameSurface(raster[p], traced[p]);
            hits += traced[p].valid();
        }
        const double fraction = double(agreeing) / double(raster.size());
        EXPECT_GE(fraction, kMinAgreeingFraction)
            << raster.size() - agreeing << " of " << raster.size() << " pixels differ";
        EXPECT_GT(hits, raster.size() / 4) << "the scene should be mostly in view";
        EXPECT_EQ(stats.coveredPixels,
                  uint64_t(std::count_if(raster.begin(), raster.end(),
                                         [](const Hit& h) { return h.valid(); })));
        std::printf("[ %s / %s ] %zu of %zu pixels see the same triangle\n", GetParam().c_str(),
                    accelName(accel), agreeing, raster.size());
    }
}

struct Images {
    std::vector<float> beauty, normal, depth;
};

Images resolve(const Film& film) {
    return {film.resolveBeauty(), film.resolveAov(AovKind::Normal),
            film.resolveAov(AovKind::Depth)};
}

// `values` has `channels` floats per pixel; pixels not in `compare` are skipped.
void expectClose(const std::vector<float>& a, const std::vector<float>& b, int channels,
                 const std::vector<bool>& compare, const char* what) {
    ASSERT_EQ(a.size(), b.size()) << what;
    int differing = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!compare[i / size_t(channels)]) continue;
        // Both infinite: the depth AOV of a pixel nothing was seen in.
        if (a[i] == b[i]) continue;
        if (std::abs(a[i] - b[i]) <= kValueTolerance) continue;
        if (++differing <= 5)
            ADD_FAILURE() << what << ": pixel " << i / size_t(channels) << " channel "
                          << i % size_t(channels) << ": raster " << a[i] << " vs traced " << b[i];
    }
    EXPECT_EQ(differing, 0) << what;
}

TEST_P(RasterAgreement, SameImageWithEveryFirstHitIntegrator) {
    const TestScene scene(regressionScene(GetParam()), AccelKind::Embree);
    const std::vector<Hit> raster = test::rasterHits(scene);
    const std::vector<Hit> traced = test::traceHits(scene);
    std::vector<bool> agree(raster.size());
    for (size_t p = 0; p < raster.size(); ++p) agree[p] = sameSurface(raster[p], traced[p]);

    const int w = scene.desc.film.width, h = scene.desc.film.height;
    for (std::string_view name : rasterIntegratorNames()) {
        SCOPED_TRACE(std::string(name));
        const auto integrator = makeIntegrator(name, scene.world);
        const std::vector<AovKind> aovs = {AovKind::Normal, AovKind::Depth};

        Film rasterFilm(w, h, scene.fullImage(), aovs);
        RenderOptions rasterOptions;
        rasterOptions.seed = scene.desc.render.seed;
        const RasterStats stats =
            rasterizeImage(scene.world, scene.camera, *integrator, rasterFilm, rasterOptions);
        EXPECT_GT(stats.coveredPixels, 0u);

        Film tracedFilm(w, h, scene.fullImage(), aovs);
        RenderOptions renderOptions;
        renderOptions.seed = scene.desc.render.seed;
        renderImage(scene.world, scene.camera, *integrator, tracedFilm, renderOptions);

        const Images a = resolve(rasterFilm), b = resolve(tracedFilm);
        expectClose(a.beauty, b.beauty, 3, agree, "beauty");
        expectClose(a.normal, b.normal, 3, agree, "normal AOV");
        expectClose(a.depth, b.depth, 1, agree, "depth AOV");
    }
}

// The scenes of scenes/regression/ whose shapes are all meshes.
INSTANTIATE_TEST_SUITE_P(MeshScenes, RasterAgreement,
                         ::testing::Values("quad_and_box", "cornell_direct", "cornell_ortho_normal",
                                           "cornell_primid"));

}  // namespace
}  // namespace strahl
