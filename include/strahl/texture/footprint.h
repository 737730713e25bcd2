#pragma once
// The texture footprint: the width, in texture-coordinate units, of the patch
// of surface a ray sample covers, which selects the mip level of a lookup.

#include "strahl/core/math.h"

namespace strahl {

// Converts a world-space footprint width at a hit (e.g. the width of a ray
// cone there) into uv units through the parameterisation's derivatives: one
// uv unit covers sqrt(|dpdu x dpdv|) world units on average, so the result is
// worldWidth / sqrt(|dpdu x dpdv|). Isotropic: stretched parameterisations get
// their mean scale. A degenerate parameterisation (zero area, non-finite
// derivatives) or a non-positive or NaN width gives 0, the finest MIP level;
// an infinite width gives infinity (lookups clamp it to the whole image).
float uvFootprint(float worldWidth, const Vec3& dpdu, const Vec3& dpdv);

}  // namespace strahl
