#pragma once
// Object-order rendering: a z-buffer rasterizer for triangle meshes that finds
// the same first hits as the ray tracer's camera rays and shades them with the
// same integrators (`strahl render --algorithm raster`).
//
// Each pixel is sampled once, at its centre, on the Camera's own rays; a
// triangle covers a centre if the centre's ray passes through it (edge
// functions with a top-left style tie rule, so shared edges are covered
// exactly once), and only beyond the ray's start (the image plane for
// perspective cameras). Depth is the ray parameter t of that ray; the nearest
// wins, exact ties go to the smaller (geomID, primID). Every covered pixel gets
// an Embree-style Hit (t, u, v, Ng, geomID, primID) shaded by
// Integrator::shade exactly as the ray tracer shades it.
//
// Triangles are binned into screen tiles, tiles are rasterized in parallel
// (oneTBB), and the result is the same for any thread count or tile size.
// It takes the ray tracer's RenderOptions: threads, tileSize, spp (must be 1),
// seed (the integrator's per-pixel generator) and progress (a "raster" phase
// of one unit per tile, advanced from the worker threads); the pixel filter,
// packets, cancel, passDone and the sample offset do not apply to one sample
// at each pixel centre.
// Algorithm, sampling rule and where the image differs from the ray-traced one:
// docs/rasterizer.md.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "strahl/camera/camera.h"
#include "strahl/core/pixel_rect.h"
#include "strahl/core/ray.h"
#include "strahl/film/film.h"
#include "strahl/integrator/integrator.h"
#include "strahl/integrator/world.h"
#include "strahl/render/renderer.h"

namespace strahl {

struct RasterStats {
    double seconds = 0.0;
    uint64_t triangles = 0;        // mesh triangles set up
    uint64_t trianglesInView = 0;  // of those, the ones that may cover a pixel centre
    uint64_t fragments = 0;        // (triangle, pixel) coverages in front of the image plane
    uint64_t coveredPixels = 0;    // pixels whose centre sees a triangle
};

// The integrators the rasterizer can shade: those that look only at the first
// hit (eyelight, normal, depth, primid).
std::span<const std::string_view> rasterIntegratorNames();

// Throws strahl::Error unless `integrator` is in rasterIntegratorNames() and
// spp is 1; cheap, for checking a command line before loading a scene.
void requireRasterSettings(std::string_view integrator, int spp);

// Throws strahl::Error naming the first shape the rasterizer cannot draw: a
// user shape (implicit surface...), or any instance.
void requireRasterizable(const World& world);

// The first hit of every pixel centre of `crop`, row by row from its top left;
// an invalid Hit where nothing is seen. For tests and tools; no shading.
std::vector<Hit> rasterizeHits(const World& world, const Camera& camera, const PixelRect& crop,
                               const RenderOptions& options, RasterStats* stats = nullptr);

// Rasterizes film.crop() and shades every pixel into `film` (beauty and AOVs).
// Checks everything above first and throws strahl::Error before touching the
// film.
RasterStats rasterizeImage(const World& world, const Camera& camera, const Integrator& integrator,
                           Film& film, const RenderOptions& options);

}  // namespace strahl
