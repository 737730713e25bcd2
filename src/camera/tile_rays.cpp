#include "strahl/camera/tile_rays.h"

namespace strahl {

Ray TileRayGenerator::sampleRay(int px, int py, int s, SampleRng& rng) const {
    rng = SampleRng(seed_, static_cast<uint32_t>(px), static_cast<uint32_t>(py),
                    static_cast<uint32_t>(s));
    float dx = 0.5f, dy = 0.5f;  // one sample: the pixel centre
    if (spp_ > 1) {
        dx = rng.nextFloat();
        dy = rng.nextFloat();
    }
    return camera_.generateRay(static_cast<float>(px) + dx, static_cast<float>(py) + dy);
}

}  // namespace strahl
