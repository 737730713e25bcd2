#pragma once
// Cutout: the alpha cut-out of a triangle mesh, which hits on it count. The
// world implements it from the mesh's materials (their opacity, docs/
// materials.md); every accelerator consults it for every candidate hit —
// Embree through intersection and occlusion filter functions, the naive
// tracer in its loop — so both find the same surfaces. Called from many
// threads and from inside Embree: const, lock-free and noexcept.

#include <cstdint>

namespace strahl {

class Cutout {
public:
    virtual ~Cutout() = default;
    // Whether a hit on triangle `prim` at barycentrics (u, v) (Embree's: the
    // point is (1 - u - v) p0 + u p1 + v p2) is on the solid part.
    virtual bool solid(uint32_t prim, float u, float v) const noexcept = 0;
};

}  // namespace strahl
