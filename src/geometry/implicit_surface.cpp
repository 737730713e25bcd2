#include "strahl/geometry/implicit_surface.h"

namespace strahl {

using num::Gradient3;
using num::Interval;
using num::RayDual;

Interval ImplicitSurface::range(const Bounds3& box) const {
    return evaluate(IntervalBox{Interval(box.min.x, box.max.x), Interval(box.min.y, box.max.y),
                                Interval(box.min.z, box.max.z)});
}

DVec3 ImplicitSurface::automaticGradient(const DVec3& x) const {
    const Gradient3 f = evaluate(Point3<Gradient3>{Gradient3::variable(x.x, 0),
                                                   Gradient3::variable(x.y, 1),
                                                   Gradient3::variable(x.z, 2)});
    return DVec3(f.d[0], f.d[1], f.d[2]);
}

RayDual ImplicitSurface::alongRay(const DVec3& o, const DVec3& d, const Interval& t) const {
    // x(t) = o + t·d, dx/dt = d: one tangent direction, seeded per axis.
    auto axis = [&](double oi, double di) {
        return RayDual(Interval(oi) + t * Interval(di), {Interval(di)});
    };
    return evaluate(Point3<RayDual>{axis(o.x, d.x), axis(o.y, d.y), axis(o.z, d.z)});
}

}  // namespace strahl
