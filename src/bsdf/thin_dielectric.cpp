// A thin dielectric sheet (docs/materials.md, "Thin dielectric").

#include <cmath>

#include "lobe_sampling.h"
#include "strahl/bsdf/bsdf_models.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/local_frame.h"

namespace strahl::bsdf_models {

float ThinDielectricModel::reflectance(float cosTheta) const {
    // Light entering the sheet reflects R at each face and passes 1 - R; the
    // rays bouncing inside sum to R' = R + (1 - R)^2 R / (1 - R^2) = 2R / (1 + R)
    // reflected and 1 - R' transmitted. Both faces see the same angle.
    const float r = fresnelDielectric(std::abs(cosTheta), eta);
    return r < 1.0f ? 2.0f * r / (1.0f + r) : 1.0f;
}

std::optional<BsdfSample> ThinDielectricModel::sample(const Vec3& wo, float uLobe,
                                                      const Vec2&) const {
    if (wo.z == 0.0f) return std::nullopt;
    const float r = reflectance(wo.z);
    if (uLobe < r) return deltaReflection(wo, tint, r);
    BsdfSample s;
    s.specular = true;
    s.wi = -wo;
    s.f = tint * ((1.0f - r) / std::abs(s.wi.z));
    s.pdf = 1.0f - r;
    s.transmission = true;
    s.eta = 1.0f;  // undeviated, back in the medium it came from
    return s;
}

}  // namespace strahl::bsdf_models
