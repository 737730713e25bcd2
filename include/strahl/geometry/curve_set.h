#pragma once
// CurveSet: strands of hair, fur or grass — curves with a radius that varies
// along them — as one shape. Embree intersects them natively (its curve
// geometry, accel/); the naive tracer calls this class's own reference
// intersector, written from the same surface definitions in double precision
// (docs/geometry.md, "Curves", has the math):
//
//  - round, cubic bases: the sweep of a circle of radius r(u) centred on C(u)
//    in the plane normal to the tangent C'(u), open at the segment's ends —
//    the points X with (X − C(u))·T(u) = 0 and |X − C(u)| = r(u);
//  - round, linear basis: the convex hull of the spheres at the two control
//    points (a cone touching both spheres tangentially, capped by them);
//  - flat: a ribbon that always faces the ray: `flatSegments` straight pieces
//    per segment, each a quad C(u) ± r(u)·n(u) with n ⟂ the ray and the
//    curve, at width 2r. Hits closer to the ray's origin than 2r are ignored
//    (Embree's self-intersection avoidance for flat curves);
//  - oriented (cubic bases only): a ribbon lying across given normals, for
//    grass blades and pbrt's "ribbon" curves — Embree's normal-oriented
//    surface C(u) + s·W(u), s ∈ [−1, 1], whose width direction turns from
//    the one at the segment's start to the one at its end (curve_math.h has
//    the construction).
//
// Control points carry (x, y, z, radius). A segment is named by the index of
// its first control point: 2 consecutive points for the linear basis, 4 for
// the cubic ones (Bézier, uniform B-spline, Catmull-Rom). Consecutive
// segments of one strand share points (B-spline: 3, Catmull-Rom: 3, linear:
// 1); a linear segment whose predecessor ends at its first point joins it
// without a cap.
//
// Hit records (Embree's convention): u = the curve parameter in the segment,
// in [0, 1]; v = 0 for round curves, the position across a flat ribbon in
// [−1, 1]; Ng = the surface normal (round) or the tangent (flat).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "strahl/core/math.h"
#include "strahl/core/point3.h"
#include "strahl/geometry/user_shape.h"

namespace strahl {

namespace curve {
struct OrientedFrame;  // geometry-internal (src/geometry/curve_math.h)
}

enum class CurveBasis { Linear, Bezier, BSpline, CatmullRom };
enum class CurveType { Round, Flat, Oriented };

const char* curveBasisName(CurveBasis basis);  // "linear", "bezier", "bspline", "catmull_rom"
const char* curveTypeName(CurveType type);     // "round", "flat", "oriented"
// Control points a segment spans: 2 (linear) or 4.
int curveBasisPoints(CurveBasis basis);

struct CurveSetDesc {
    std::string name;                 // for messages
    CurveBasis basis = CurveBasis::BSpline;
    CurveType type = CurveType::Round;
    std::vector<Vec4> points;         // x, y, z, radius
    std::vector<uint32_t> segments;   // index of each segment's first point
    int flatSegments = 4;             // straight pieces per segment of a flat curve (1..64)
    // Oriented curves only: one normal per control point, interpolated in
    // the curve's basis; the ribbon lies across it (docs/geometry.md).
    std::vector<Vec3> normals;
};

// The segment list of strands given as point counts: strand k spans its
// points consecutively, and every window of curveBasisPoints(basis)
// consecutive points within a strand is a segment. Throws strahl::Error
// naming `name` for a strand with fewer points than the basis needs.
std::vector<uint32_t> curveSegmentsOfStrands(std::span<const uint32_t> strandPointCounts,
                                             CurveBasis basis, const std::string& name);

class CurveSet final : public UserShape {
public:
    // Throws strahl::Error naming desc.name for no segments, a segment
    // reaching past the points, a coordinate or radius that is not finite, a
    // negative radius, a radius that a Catmull-Rom segment overshoots below 0,
    // or flatSegments outside 1..64.
    explicit CurveSet(CurveSetDesc desc);

    uint32_t primitiveCount() const override { return static_cast<uint32_t>(desc_.segments.size()); }
    Bounds3 primitiveBounds(uint32_t prim) const override;
    bool intersect(const Ray& ray, uint32_t prim, Hit& hit) const noexcept override;
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const override;
    std::string describe() const override;
    const char* primitiveNoun() const override { return "curve segments"; }
    size_t memoryBytes() const override;
    const CurveSet* asCurves() const override { return this; }

    const CurveSetDesc& desc() const { return desc_; }
    // Whether segment `prim` continues the previous segment of its strand
    // (linear basis: it starts where that one ends).
    bool hasLeftNeighbour(uint32_t prim) const;
    // The segment as a cubic Bézier in (x, y, z, r) (linear: the line, degree
    // elevated), for evaluation.
    void bezierOf(uint32_t prim, glm::dvec4 out[4]) const;

private:
    // Control points d(0..3) of `basis` as Bézier points.
    template <class ControlPoint>
    static void toBezier(CurveBasis basis, const ControlPoint& d, glm::dvec4 b[4]);
    // An oriented segment's directions across (false: a normal along the curve).
    bool orientedFrameOf(uint32_t prim, const glm::dvec4 b[4], curve::OrientedFrame& frame) const;

    CurveSetDesc desc_;
};

}  // namespace strahl
