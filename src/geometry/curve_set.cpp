// CurveSet: validation, Bézier form, bounds and interactions of curves; the
// reference intersectors are in curve_intersectors.cpp. Definitions in
// include/strahl/geometry/curve_set.h, math in docs/geometry.md.

#include "strahl/geometry/curve_set.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "curve_math.h"
#include "strahl/core/error.h"

namespace strahl {

using curve::DVec4;

namespace {

DVec3 xyz(const DVec4& v) { return DVec3(v.x, v.y, v.z); }

// How far a segment's first point lies after its predecessor's when both
// belong to one strand.
uint32_t strandStep(CurveBasis basis) { return basis == CurveBasis::Bezier ? 3u : 1u; }

// Float bounds that contain the double box [lo, hi]: rounded outwards by a
// relative 2^-20, far above float's rounding.
Bounds3 outward(const DVec3& lo, const DVec3& hi) {
    const DVec3 pad = (glm::abs(lo) + glm::abs(hi)) * 0x1p-20 + 1e-30;
    Bounds3 b;
    b.min = Vec3(lo - pad);
    b.max = Vec3(hi + pad);
    return b;
}

}  // namespace

const char* curveBasisName(CurveBasis basis) {
    switch (basis) {
        case CurveBasis::Linear: return "linear";
        case CurveBasis::Bezier: return "bezier";
        case CurveBasis::BSpline: return "bspline";
        case CurveBasis::CatmullRom: return "catmull_rom";
    }
    return "?";
}

const char* curveTypeName(CurveType type) {
    switch (type) {
        case CurveType::Round: return "round";
        case CurveType::Flat: return "flat";
        case CurveType::Oriented: return "oriented";
    }
    return "?";
}

int curveBasisPoints(CurveBasis basis) { return basis == CurveBasis::Linear ? 2 : 4; }

std::vector<uint32_t> curveSegmentsOfStrands(std::span<const uint32_t> strandPointCounts, CurveBasis basis,
                                             const std::string& name) {
    const uint32_t need = static_cast<uint32_t>(curveBasisPoints(basis));
    const uint32_t step = strandStep(basis);
    std::vector<uint32_t> segments;
    uint64_t first = 0;
    for (size_t k = 0; k < strandPointCounts.size(); ++k) {
        const uint32_t n = strandPointCounts[k];
        if (n < need)
            fail("curves '", name, "': strand ", k, " has ", n, " control points, but a ", curveBasisName(basis),
                 " segment needs ", need);
        if (basis == CurveBasis::Bezier && (n - 1) % 3 != 0)
            fail("curves '", name, "': strand ", k, " has ", n,
                 " control points; a strand of Bezier segments has 3k + 1 (4, 7, 10, ...)");
        for (uint32_t i = 0; i + need <= n; i += step) segments.push_back(static_cast<uint32_t>(first + i));
        first += n;
        if (first > UINT32_MAX) fail("curves '", name, "': more than 2^32 control points");
    }
    return segments;
}

CurveSet::CurveSet(CurveSetDesc desc) : desc_(std::move(desc)) {
    const std::string& name = desc_.name;
    if (desc_.segments.empty()) fail("curves '", name, "': no segments");
    if (desc_.flatSegments < 1 || desc_.flatSegments > 64)
        fail("curves '", name, "': flat_segments must lie in 1..64 (got ", desc_.flatSegments, ")");
    for (size_t i = 0; i < desc_.points.size(); ++i) {
        const Vec4& p = desc_.points[i];
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
            fail("curves '", name, "': control point ", i, " is not finite");
        if (!std::isfinite(p.w) || p.w < 0.0f)
            fail("curves '", name, "': control point ", i, " has radius ", p.w, " (must be finite and >= 0)");
    }
    if (desc_.type == CurveType::Oriented) {
        if (desc_.basis == CurveBasis::Linear)
            fail("curves '", name, "': oriented ribbons need a cubic basis (bezier, bspline or catmull_rom)");
        if (desc_.normals.size() != desc_.points.size())
            fail("curves '", name, "': an oriented ribbon needs one normal per control point (", desc_.points.size(),
                 " points, ", desc_.normals.size(), " normals)");
        for (size_t i = 0; i < desc_.normals.size(); ++i)
            if (!isFinite(desc_.normals[i]) || !(glm::length(desc_.normals[i]) > 0.0f))
                fail("curves '", name, "': normal ", i, " is zero or not finite");
    } else if (!desc_.normals.empty()) {
        fail("curves '", name, "': normals are only for oriented ribbons");
    }
    const uint64_t span = static_cast<uint64_t>(curveBasisPoints(desc_.basis));
    for (size_t s = 0; s < desc_.segments.size(); ++s) {
        if (desc_.segments[s] + span > desc_.points.size())
            fail("curves '", name, "': segment ", s, " starts at control point ", desc_.segments[s], " and needs ",
                 span, ", but there are ", desc_.points.size());
        if (desc_.type == CurveType::Oriented) {
            DVec4 b[4];
            bezierOf(static_cast<uint32_t>(s), b);
            curve::OrientedFrame frame;
            if (!orientedFrameOf(static_cast<uint32_t>(s), b, frame))
                fail("curves '", name, "': segment ", s,
                     " has a normal parallel to the curve at an end (an oriented ribbon lies across its normals)");
        }
        if (desc_.basis == CurveBasis::CatmullRom) {
            DVec4 b[4];
            bezierOf(static_cast<uint32_t>(s), b);
            // The radius is a cubic too; its Bézier coefficients bound it.
            if (std::min({b[0].w, b[1].w, b[2].w, b[3].w}) < 0.0)
                fail("curves '", name, "': segment ", s,
                     " interpolates a negative radius (Catmull-Rom overshoots; smooth the radii)");
        }
    }
}

bool CurveSet::hasLeftNeighbour(uint32_t prim) const {
    return prim > 0 && desc_.segments[prim - 1] + strandStep(desc_.basis) == desc_.segments[prim];
}

void CurveSet::bezierOf(uint32_t prim, DVec4 b[4]) const {
    const Vec4* q = desc_.points.data() + desc_.segments[prim];
    toBezier(desc_.basis, [&](int i) { return DVec4(q[i]); }, b);
}

bool CurveSet::orientedFrameOf(uint32_t prim, const DVec4 b[4], curve::OrientedFrame& frame) const {
    // The normal curve in the same basis, at the segment's ends.
    const Vec3* n = desc_.normals.data() + desc_.segments[prim];
    DVec4 nb[4];
    toBezier(desc_.basis, [&](int i) { return DVec4(DVec3(n[i]), 0.0); }, nb);
    return curve::orientedFrame(b, nb, frame);
}

template <class ControlPoint>
void CurveSet::toBezier(CurveBasis basis, const ControlPoint& d, DVec4 b[4]) {
    switch (basis) {
        case CurveBasis::Linear:
            b[0] = d(0), b[3] = d(1);
            b[1] = (2.0 * d(0) + d(1)) / 3.0, b[2] = (d(0) + 2.0 * d(1)) / 3.0;
            return;
        case CurveBasis::Bezier:
            for (int i = 0; i < 4; ++i) b[i] = d(i);
            return;
        case CurveBasis::BSpline:
            // The uniform cubic B-spline's Bézier points.
            b[0] = (d(0) + 4.0 * d(1) + d(2)) / 6.0;
            b[1] = (2.0 * d(1) + d(2)) / 3.0;
            b[2] = (d(1) + 2.0 * d(2)) / 3.0;
            b[3] = (d(1) + 4.0 * d(2) + d(3)) / 6.0;
            return;
        case CurveBasis::CatmullRom:
            // Through p1 and p2 with tangents (p2 − p0)/2 and (p3 − p1)/2.
            b[0] = d(1), b[3] = d(2);
            b[1] = d(1) + (d(2) - d(0)) / 6.0;
            b[2] = d(2) - (d(3) - d(1)) / 6.0;
            return;
    }
}

Bounds3 CurveSet::primitiveBounds(uint32_t prim) const {
    // Convex hull of the Bézier points, grown by the largest radius (the
    // radius is a Bézier too, so it never exceeds its largest coefficient;
    // an oriented ribbon's edges b_i -+ r_i k lie within it as well).
    DVec4 b[4];
    bezierOf(prim, b);
    DVec3 lo = xyz(b[0]), hi = lo;
    double r = 0.0;
    for (const DVec4& p : b) {
        lo = glm::min(lo, xyz(p));
        hi = glm::max(hi, xyz(p));
        r = std::max(r, p.w);
    }
    return outward(lo - r, hi + r);
}

bool CurveSet::intersect(const Ray& ray, uint32_t prim, Hit& hit) const noexcept {
    const curve::DRay r{DVec3(ray.origin), DVec3(ray.dir), ray.tnear, ray.tfar};
    curve::RefHit h;
    bool found = false;
    if (desc_.basis == CurveBasis::Linear) {
        const DVec4 p0(desc_.points[desc_.segments[prim]]), p1(desc_.points[desc_.segments[prim] + 1]);
        found = desc_.type == CurveType::Round ? curve::intersectRoundLinear(r, p0, p1, h)
                                               : curve::intersectFlatLinear(r, p0, p1, h);
    } else {
        DVec4 b[4];
        bezierOf(prim, b);
        curve::OrientedFrame frame;
        switch (desc_.type) {
            case CurveType::Round: found = curve::intersectRoundCubic(r, b, h); break;
            case CurveType::Flat: found = curve::intersectFlatCubic(r, b, desc_.flatSegments, h); break;
            case CurveType::Oriented:
                found = orientedFrameOf(prim, b, frame) && curve::intersectOrientedCubic(r, b, frame, h);
                break;
        }
    }
    // The float t must still lie inside (tnear, tfar) after rounding (and be
    // a float at all: a ray of a tiny direction can meet a curve beyond it).
    if (!found || !(h.t < double(std::numeric_limits<float>::max()))) return false;
    const float t = static_cast<float>(h.t);
    if (!(t > ray.tnear && t < ray.tfar)) return false;
    const double ngLength = glm::length(h.Ng);
    hit.t = t;
    hit.u = static_cast<float>(h.u);
    hit.v = static_cast<float>(h.v);
    hit.Ng = ngLength > 0.0 ? Vec3(h.Ng / ngLength) : Vec3(0.0f);  // unit: a double beyond float's range stays finite
    return true;
}

SurfaceInteraction CurveSet::interaction(const Ray& ray, const Hit& hit) const {
    DVec4 b[4];
    bezierOf(hit.primID, b);
    const DVec3 d = glm::normalize(DVec3(ray.dir));
    DVec3 x = DVec3(ray.origin) + double(hit.t) * DVec3(ray.dir);
    double u = std::clamp(double(hit.u), 0.0, 1.0);
    SurfaceInteraction si;
    DVec3 Ng, Ns;
    double v01 = 0.5;
    curve::Eval e;  // the curve at the hit's u, evaluated once
    if (desc_.type == CurveType::Round && desc_.basis == CurveBasis::Linear) {
        const DVec4 p0(desc_.points[desc_.segments[hit.primID]]), p1(desc_.points[desc_.segments[hit.primID] + 1]);
        double s;
        curve::roundLinearDistance(x, p0, p1, s);
        const DVec3 c = xyz(p0) + s * xyz(p1 - p0);
        Ng = glm::normalize(x - c);
        x = c + (p0.w + s * (p1.w - p0.w)) * Ng;  // back onto the surface
        u = s;
        Ns = Ng;
        si.fibreAxis = Vec3(c);
        si.fibreRadius = float(p0.w + s * (p1.w - p0.w));
        e = curve::evalBezier(b, u);
    } else if (desc_.type == CurveType::Round) {
        e = curve::evalBezier(b, u);
        const DVec3 C1 = xyz(e.dp);
        DVec3 R = x - xyz(e.p);
        R -= C1 * (glm::dot(R, C1) / glm::dot(C1, C1));
        const DVec3 Rn = glm::normalize(R);
        x = xyz(e.p) + e.p.w * Rn;
        Ng = glm::normalize(glm::dot(C1, C1) * Rn - e.dp.w * C1);
        Ns = Ng;
        si.fibreAxis = Vec3(xyz(e.p));
        si.fibreRadius = float(e.p.w);
    } else if (desc_.type == CurveType::Oriented) {
        // The ribbon's own surface: s from the hit point (whatever v the
        // tracer reported), the normal S_u x S_s.
        e = curve::evalBezier(b, u);
        curve::OrientedFrame frame;
        orientedFrameOf(hit.primID, b, frame);  // checked when the set was made
        DVec3 dW;
        const DVec3 W = curve::orientedWidth(frame, u, &dW);
        const double w2 = glm::dot(W, W);
        const double s = w2 > 0.0 ? std::clamp(glm::dot(x - xyz(e.p), W) / w2, -1.0, 1.0) : 0.0;
        x = xyz(e.p) + s * W;
        const DVec3 n = glm::cross(xyz(e.dp) + s * dW, W);
        Ng = glm::length(n) > 0.0 ? glm::normalize(n) : -d;
        Ns = Ng;
        v01 = 0.5 * (s + 1.0);
    } else {
        // A ribbon facing the ray: the geometric normal faces it; the shading
        // normal turns across the ribbon as a cylinder's would, so that a flat
        // strand shades like a round one (v = ±1 at its edges).
        e = curve::evalBezier(b, u);
        const DVec3 T = glm::normalize(xyz(e.dp));
        DVec3 facing = -d + T * glm::dot(d, T);
        if (glm::dot(facing, facing) <= 0.0) facing = glm::abs(T.x) < 0.9 ? glm::cross(T, DVec3(1, 0, 0)) : glm::cross(T, DVec3(0, 1, 0));
        Ng = glm::normalize(facing);
        const DVec3 across = glm::normalize(glm::cross(Ng, T));  // the v = −1 side: C' × d, d ≈ −Ng
        const double v = e.p.w > 0.0 ? std::clamp(-glm::dot(x - xyz(e.p), across) / e.p.w, -1.0, 1.0) : 0.0;
        Ns = glm::normalize(std::sqrt(std::max(0.0, 1.0 - v * v)) * Ng - v * across);
        v01 = 0.5 * (v + 1.0);
    }
    // u along the whole strand: segment k of n covers [k/n, (k+1)/n].
    uint32_t first = hit.primID, last = hit.primID;
    while (hasLeftNeighbour(first)) --first;
    while (last + 1 < primitiveCount() && hasLeftNeighbour(last + 1)) ++last;
    const double strandU = (double(hit.primID - first) + u) / double(last - first + 1);

    si.p = Vec3(x);
    // Curve hits come from float Newton iterations (Embree) or bisection
    // (reference): bound the error by 2^-16 of the coordinates' scale — far
    // above both — plus a thousandth of the radius.
    const double scale = std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    si.pError = Vec3(float(scale * 0x1p-16 + 1e-3 * e.p.w));
    si.Ng = Vec3(Ng);
    si.Ns = Vec3(Ns);
    si.uv = Vec2(float(strandU), float(v01));
    si.dpdu = Vec3(xyz(e.dp) / double(last - first + 1));
    si.dpdv = Vec3(glm::cross(Ng, xyz(e.dp)) * (2.0 * e.p.w / std::max(glm::length(xyz(e.dp)), 1e-300)));
    return si;
}

std::string CurveSet::describe() const {
    return concat("curves '", desc_.name, "': ", curveTypeName(desc_.type), " ", curveBasisName(desc_.basis));
}

size_t CurveSet::memoryBytes() const {
    return desc_.points.capacity() * sizeof(Vec4) + desc_.segments.capacity() * sizeof(uint32_t) +
           desc_.normals.capacity() * sizeof(Vec3);
}

}  // namespace strahl
