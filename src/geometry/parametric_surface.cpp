#include "strahl/geometry/parametric_surface.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "double_box.h"
#include "strahl/core/error.h"

namespace strahl {

namespace {

using geometry_detail::isFiniteD;

DVec3 toVec(const Point3<double>& p) { return DVec3(p.x, p.y, p.z); }

}  // namespace

DVec3 ParametricSurface::point(uint32_t patch, double u, double v) const {
    return toVec(evaluate(patch, u, v));
}

SurfacePoint ParametricSurface::automaticPartials(uint32_t patch, double u, double v) const {
    const Point3<Dual2> f = evaluate(patch, Dual2::variable(u, 0), Dual2::variable(v, 1));
    SurfacePoint s;
    s.p = DVec3(f.x.v, f.y.v, f.z.v);
    s.dpdu = DVec3(f.x.d[0], f.y.d[0], f.z.d[0]);
    s.dpdv = DVec3(f.x.d[1], f.y.d[1], f.z.d[1]);
    return s;
}

std::optional<DVec3> ParametricSurface::regularNormal(const SurfacePoint& s) {
    // A cross product shorter than this fraction of |∂u f|·|∂v f| (partials
    // parallel to 8 digits), or with a zero partial, is a singular point: its
    // direction is rounding noise.
    constexpr double kSingular = 1e-8;
    const DVec3 n = glm::cross(s.dpdu, s.dpdv);
    const double len = glm::length(n);
    const double scale = glm::length(s.dpdu) * glm::length(s.dpdv);
    if (isFiniteD(n) && len > kSingular * scale && len > 0.0) return n / len;
    return std::nullopt;
}

DVec3 ParametricSurface::normal(uint32_t patch, double u, double v) const {
    const ParamDomain& dom = domain();
    const double cu = 0.5 * (dom.u0 + dom.u1), cv = 0.5 * (dom.v0 + dom.v1);
    // At a singular point take the limit from inside. Steps towards the
    // centre, as a fraction of the way there: the first is small enough that
    // the normal of a smooth surface moves by ~1e-6, the later ones get away
    // from a singular curve (a cone's apex circle) that the first did not leave.
    for (const double step : {0.0, 1e-6, 1e-4, 1e-2})
        if (const auto n = regularNormal(partials(patch, u + step * (cu - u), v + step * (cv - v))))
            return *n;
    return DVec3(0.0);
}

void ParametricSurface::setTextureFrame(SurfaceInteraction& si, const SurfacePoint& s, double u,
                                        double v, const glm::dmat3& linear) const {
    const ParamDomain& dom = domain();
    si.uv = Vec2(static_cast<float>((u - dom.u0) / dom.width()),
                 static_cast<float>((v - dom.v0) / dom.height()));
    const DVec3 dpds = linear * (dom.width() * s.dpdu);
    const DVec3 dpdt = linear * (dom.height() * s.dpdv);
    if (isFiniteD(dpds)) si.dpdu = Vec3(dpds);
    if (isFiniteD(dpdt)) si.dpdv = Vec3(dpdt);
    const double area = glm::length(glm::cross(dpds, dpdt));
    // Zero area (a pole, where ∂φ f vanishes) or overflow: density unknown.
    if (area > 0.0 && std::isfinite(area)) si.uvDensity = static_cast<float>(1.0 / std::sqrt(area));
}

double parametricExtent(const ParametricSurface& surface) {
    const ParamDomain& d = surface.domain();
    DVec3 lo(num::kInf), hi(-num::kInf);
    for (uint32_t p = 0; p < surface.patchCount(); ++p)
        for (int j = 0; j <= 4; ++j)
            for (int i = 0; i <= 4; ++i) {
                const DVec3 x = surface.point(p, d.u0 + d.width() * i / 4, d.v0 + d.height() * j / 4);
                lo = glm::min(lo, x);
                hi = glm::max(hi, x);
            }
    return std::max(glm::length(hi - lo), 1e-300);
}

void validateParametricSurface(const ParametricSurface& surface) {
    const ParamDomain& d = surface.domain();
    if (!(std::isfinite(d.u0) && std::isfinite(d.u1) && std::isfinite(d.v0) && std::isfinite(d.v1)))
        fail(surface.describe(), ": the domain is not finite");
    if (!(d.u0 < d.u1)) fail(surface.describe(), ": the domain of u is empty or inverted [", d.u0, ", ", d.u1, "]");
    if (!(d.v0 < d.v1)) fail(surface.describe(), ": the domain of v is empty or inverted [", d.v0, ", ", d.v1, "]");
    if (surface.patchCount() == 0) fail(surface.describe(), ": no patches");
    // A 17 x 17 grid per patch (corners, edges, centre and between) catches a
    // formula that is undefined on a whole line of its domain or at a corner.
    constexpr int kSamples = 16;
    for (uint32_t patch = 0; patch < surface.patchCount(); ++patch)
        for (int j = 0; j <= kSamples; ++j)
            for (int i = 0; i <= kSamples; ++i) {
                const double u = d.u0 + d.width() * i / kSamples;
                const double v = d.v0 + d.height() * j / kSamples;
                const SurfacePoint s = surface.partials(patch, u, v);
                if (!isFiniteD(s.p) || !isFiniteD(s.dpdu) || !isFiniteD(s.dpdv))
                    fail(surface.describe(), ": not finite at (u, v) = (", u, ", ", v, ")",
                         surface.patchCount() > 1 ? concat(" of patch ", patch) : std::string());
            }
}

}  // namespace strahl
