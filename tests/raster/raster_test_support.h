#pragma once
// Shared by the rasterizer tests: scenes from JSON text, and the ray tracer's
// first hits at the pixel centres — the reference the rasterizer must match.

#include <string>
#include <vector>

#include "strahl/camera/tile_rays.h"
#include "strahl/raster/rasterizer.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::test {

struct TestScene {
    SceneDesc desc;
    World world;
    Camera camera;

    TestScene(SceneDesc d, AccelKind accel)
        : desc(std::move(d)),
          world(buildWorld(desc, withAccel(accel))),
          camera(buildCamera(desc.camera, desc.film.width, desc.film.height)) {}

    PixelRect fullImage() const { return {0, 0, desc.film.width, desc.film.height}; }
    int width() const { return desc.film.width; }

private:
    static BuildOptions withAccel(AccelKind accel) {
        BuildOptions options;
        options.accel = accel;
        return options;
    }
};

inline TestScene sceneFromText(const std::string& json, AccelKind accel = AccelKind::Naive) {
    return TestScene(parseSceneText(json, "raster_test.json"), accel);
}

// The closest hit of every pixel centre's camera ray (the ray the renderer
// traces with one sample per pixel), row by row.
inline std::vector<Hit> traceHits(const TestScene& scene) {
    const TileRayGenerator rays(scene.camera, 0, 1);
    std::vector<Hit> hits;
    for (int y = 0; y < scene.desc.film.height; ++y)
        for (int x = 0; x < scene.desc.film.width; ++x) {
            Sampler rng;
            hits.push_back(scene.world.accel->intersect(rays.sampleRay(x, y, 0, rng)));
        }
    return hits;
}

inline std::vector<Hit> rasterHits(const TestScene& scene, RasterStats* stats = nullptr,
                                   int threads = 0, int tileSize = 32) {
    RenderOptions options;
    options.threads = threads;
    options.tileSize = tileSize;
    return rasterizeHits(scene.world, scene.camera, scene.fullImage(), options, stats);
}

inline bool sameSurface(const Hit& a, const Hit& b) {
    return a.geomID == b.geomID && a.primID == b.primID;
}

}  // namespace strahl::test
