#pragma once
// SurfaceInteraction: everything shading needs about a hit point, computed once
// for the closest hit (the second phase of two-phase intersection) by the shape
// that was hit.

#include <cstdint>

#include "strahl/core/math.h"
#include "strahl/geometry/mesh_attribute.h"

namespace strahl {

struct SurfaceInteraction {
    Vec3 p{0.0f};       // hit point (triangles: rebuilt from barycentrics, not o + t*d)
    Vec3 pError{0.0f};  // conservative per-axis bound on the error of p
    Vec3 Ng{0.0f};      // unit geometric normal (triangles: winding order; implicit: +grad f)
    Vec3 Ns{0.0f};      // unit shading normal, same hemisphere as Ng
    Vec2 uv{0.0f};
    Vec3 dpdu{0.0f};    // tangent along u (texture frame, normal maps); zero if unknown
    Vec3 dpdv{0.0f};    // tangent along v (bump maps); zero if unknown
    float uvDensity = 0.0f;  // uv units per world unit near p (texture footprints); 0 if unknown
    uint32_t materialSlot = 0;  // faceMaterials entry, 0 if the mesh has none
    // A round curve's cross-section through p: the point on its axis and its
    // radius (0 on every other surface). Rays a fibre BSDF scatters leave from
    // the side of the fibre facing their direction (ShadingContext::spawn).
    Vec3 fibreAxis{0.0f};
    float fibreRadius = 0.0f;
    MeshAttributePoint attributes;  // a mesh's named attributes here (none elsewhere)
};

// An interaction computed in an instance's object space, moved to world space:
// p mapped with its error bound widened for the map's rounding, normals mapped
// by `normalToWorld` (the inverse transpose of objectToWorld's linear part) and
// renormalised, dpdu and dpdv by the linear part (uvDensity divided by its mean
// scale), a fibre's axis point as a point and its radius by the mean scale;
// uv, the material slot and the attributes are unchanged.
SurfaceInteraction transformInteraction(const SurfaceInteraction& si, const Mat4& objectToWorld,
                                        const Mat3& normalToWorld);

}  // namespace strahl
