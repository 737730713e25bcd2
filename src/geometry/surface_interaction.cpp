#include "strahl/geometry/surface_interaction.h"

#include "strahl/core/transform.h"

namespace strahl {

namespace {

Vec3 unitOrZero(const Vec3& v) {
    const float len = glm::length(v);
    return len > 0.0f ? v / len : v;
}

}  // namespace

SurfaceInteraction transformInteraction(const SurfaceInteraction& si, const Mat4& objectToWorld,
                                        const Mat3& normalToWorld) {
    SurfaceInteraction out = si;
    out.p = transformPoint(objectToWorld, si.p);
    out.pError = transformPointError(objectToWorld, si.p, si.pError);
    out.Ng = unitOrZero(normalToWorld * si.Ng);
    out.Ns = unitOrZero(normalToWorld * si.Ns);
    const Mat3 linear(objectToWorld);
    out.dpdu = linear * si.dpdu;
    out.dpdv = linear * si.dpdv;
    // A uniform scale s stretches world lengths by s: uv per world unit / s.
    // For other maps the cube root of |det| is the mean scale.
    const float scale = std::cbrt(std::abs(glm::determinant(linear)));
    if (scale > 0.0f) out.uvDensity = si.uvDensity / scale;
    if (si.fibreRadius > 0.0f) {
        out.fibreAxis = transformPoint(objectToWorld, si.fibreAxis);
        out.fibreRadius = si.fibreRadius * scale;
    }
    return out;
}

}  // namespace strahl
