#pragma once
// Tangent-space normal maps, OpenGL convention: n = 2 rgb - 1 in the frame
// (tangent along +u, bitangent along +v, normal), so red tilts the normal
// towards +u, green towards +v and blue is "out of the surface". Maps baked
// DirectX-style (green towards -v) need their green channel flipped
// (g -> 1 - g) before use.

#include "strahl/core/math.h"

namespace strahl {

// `encoded` is the map's RGB in [0, 1] (registered as TextureEncoding::Data),
// ns the interpolated shading normal and dpdu the surface tangent along u.
// The frame is ns, the tangent t = dpdu made orthogonal to ns (Gram-Schmidt)
// and the bitangent ns x t. Returns the perturbed unit normal. A zero dpdu, or
// one parallel to ns, gives an arbitrary tangent perpendicular to ns (the
// result is still a unit vector). An encoded value of (0.5, 0.5, 0.5), which
// decodes to no direction, returns ns normalised; a zero or non-finite ns is
// returned unchanged.
// Mirrored UVs (dpdu x dpdv against ns) are not detected: their green tilts
// the wrong way.
Vec3 applyNormalMap(const Vec3& encoded, const Vec3& ns, const Vec3& dpdu);

}  // namespace strahl
