#include "strahl/camera/tile_rays.h"

namespace strahl {

Ray TileRayGenerator::sampleRay(int px, int py, int s, Sampler& sampler) const {
    sampler = Sampler(seed_, px, py, static_cast<uint32_t>(s));
    // The first two pairs of dimensions always go to the camera (filter offset,
    // lens point), so the integrator's dimensions start at the same place
    // whatever the camera and the spp.
    const Vec2 pixel = sampler.get2D();
    // A pinhole ignores its lens sample: the pair is skipped, not drawn (the
    // later pairs are the same either way; a third of this function's time
    // in eyelight renders went into drawing it).
    Vec2 lens(0.5f);
    if (camera_.apertureRadius() > 0.0f)
        lens = sampler.get2D();
    else
        sampler.skip2D();
    Vec2 offset(0.0f);  // one sample: the pixel centre
    if (spp_ > 1) offset = filter_.sample(pixel);
    Ray ray = camera_.generateRay(static_cast<float>(px) + 0.5f + offset.x,
                                  static_cast<float>(py) + 0.5f + offset.y, lens);
    if (motion_) ray.time = camera_.shutter().timeAt(sampler.get1D());
    return ray;
}

}  // namespace strahl
