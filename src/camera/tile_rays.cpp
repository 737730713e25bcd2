#include "strahl/camera/tile_rays.h"

namespace strahl {

Vec2 TileRayGenerator::cameraSample(int px, int py, int s, Sampler& sampler, Vec2& lens) const {
    sampler = Sampler(seed_, px, py, static_cast<uint32_t>(s));
    // The first two pairs of dimensions always go to the camera (filter offset,
    // lens point), so the integrator's dimensions start at the same place
    // whatever the camera and the spp.
    // A pair whose values would not be used is skipped, not drawn (the later
    // pairs are the same either way): the filter offset with one sample per
    // pixel (its centre), the lens sample of a pinhole. Drawing them was most
    // of this function's time in eyelight renders.
    Vec2 offset(0.0f);
    if (spp_ > 1)
        offset = filter_.sample(sampler.get2D());
    else
        sampler.skip2D();
    lens = Vec2(0.5f);
    if (camera_.apertureRadius() > 0.0f)
        lens = sampler.get2D();
    else
        sampler.skip2D();
    return Vec2(static_cast<float>(px) + 0.5f + offset.x, static_cast<float>(py) + 0.5f + offset.y);
}

Ray TileRayGenerator::sampleRay(int px, int py, int s, Sampler& sampler) const {
    Vec2 lens;
    const Vec2 raster = cameraSample(px, py, s, sampler, lens);
    Ray ray = camera_.generateRay(raster.x, raster.y, lens);
    if (motion_) ray.time = camera_.shutter().timeAt(sampler.get1D());
    return ray;
}

}  // namespace strahl
