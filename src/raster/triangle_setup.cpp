// Triangle setup of the rasterizer: edge functions that sample exactly what the
// ray tracer's camera rays sample.
//
// Edge functions from the pixel rays. The camera ray through window position
// (u, v) has, in the camera frame (axes u, v, w; the camera looks down -w),
//     perspective:  the line through the eye with direction D = (u, v, -d),
//     orthographic: the line through O = (u, v, 0) with direction D = (0, 0, -1).
// For camera-space vertices P_i, P_j the edge function is the triple product
//     E_ij = D . ((P_i - O) x (P_j - O))           (O = 0 for perspective),
// the side of the oriented edge the line passes; E_12, E_20, E_01 are
// proportional to the barycentric weights of P_0, P_1, P_2 where the line meets
// the plane, with sum D . N, N = (P_1 - P_0) x (P_2 - P_0). Each is affine in
// (u, v):
//     perspective:  K = P_i x P_j,  E = K.x u + K.y v - d K.z
//     orthographic: E = (y_j - y_i) u + (x_i - x_j) v + (y_i x_j - x_i y_j)
// This is homogeneous rasterization (Olano and Greer 1997): no vertex is ever
// divided by its depth, so triangles that reach behind the eye need no special
// case. The line meets the triangle iff the three E_k share a sign; which sign
// is a forward hit is the orientation s:
//     perspective:  s = sign(P_0 . (P_1 x P_2)) — a forward hit has
//                   t = P_0 . N / (D . N) > 0, so D . N, the sum, has the sign
//                   of P_0 . N = P_0 . (P_1 x P_2); rays that meet the plane
//                   behind the eye have all E_k of sign -s and are rejected
//                   by the coverage test itself;
//     orthographic: s = sign(D . N) = sign(-N.z), the same for every pixel.
// Every coefficient is multiplied by s, so inside is E > 0 for every triangle,
// front or back facing. s = 0 is a triangle seen edge-on (or degenerate): the
// ray tracer never hits it either.
//
// Shared edges are covered exactly once. Two triangles on opposite sides of a
// shared edge compute its coefficients from the same camera-space vertices in
// the opposite order; every coefficient is a difference of products, and
// a*b - c*d and c*d - a*b round to exact negatives (products commute,
// round-to-nearest is odd); so do a u + b v + c and (-a) u + (-b) v + (-c) at
// the same (u, v). After the scaling by s both triangles see E and -E, bit for bit,
// at every pixel centre. The tie rule gives a centre with E == 0 to exactly
// one of them: an edge owns its ties if its inward gradient (a, b) points to
// +u, or along +v when a == 0 — the top-left rule of hardware rasterizers,
// stated in window coordinates (it is the left/bottom rule there, v pointing
// up). Because the whole test is in double precision, the three edges around
// a shared vertex pass through it to about 1e-16 relative: a pixel centre
// would have to lie that close to a vertex to fall between two triangles.
// Rejected: fixed-point snapping of projected vertices (exact, but samples
// vertices moved by up to 1/256 pixel, so it disagrees with the ray tracer
// near every edge) and exact predicates (exact at vertices too, but several
// times the code for a case that only constructed input reaches).
//
// The near plane. A camera ray starts where the image plane (perspective, depth
// d) or the eye plane (orthographic, depth 0) meets it, so the ray tracer sees
// nothing nearer. The triangle is clipped against that plane
// (Sutherland-Hodgman, at most four vertices) to find the pixels it may cover;
// each of those pixels then intersects its own camera ray with the triangle's
// plane and keeps the hit only if t > 0 — the very test the ray tracer applies
// at the same boundary, rather than a second, clipped edge that would round
// differently.
//
// The products must round as written: a fused multiply-add would round one
// product of a*b - c*d and not the other, which breaks the exact
// antisymmetry above, so contraction is off in this file.

#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "triangle_setup.h"

#include <algorithm>
#include <cmath>

namespace strahl::raster {

RasterView::RasterView(const Camera& camera)
    : e_(camera.frame().e),
      u_(camera.frame().u),
      v_(camera.frame().v),
      w_(camera.frame().w),
      perspective_(camera.projection() == Projection::Perspective),
      d_(camera.focalDistance()),
      l_(camera.window().l),
      t_(camera.window().t),
      // The same float expressions as Camera's du_ and dv_, so that the centres
      // below are the very window positions generateRay starts from.
      du_((camera.window().r - camera.window().l) / static_cast<float>(camera.width())),
      dv_((camera.window().b - camera.window().t) / static_cast<float>(camera.height())),
      columnsPerU_(1.0 / du_),
      rowsPerV_(1.0 / dv_) {}

DVec3 RasterView::toCamera(const Vec3& world) const {
    const DVec3 p = DVec3(world) - e_;  // exact: both are floats of similar size
    return {glm::dot(p, u_), glm::dot(p, v_), glm::dot(p, w_)};
}

double RasterView::centreU(int px) const {
    return static_cast<double>(l_ + du_ * (static_cast<float>(px) + 0.5f));
}

double RasterView::centreV(int py) const {
    return static_cast<double>(t_ + dv_ * (static_cast<float>(py) + 0.5f));
}

namespace {

// glm::cross, spelled out here so that this file's no-contraction rule governs
// it: an inline template instantiated in another file could be the copy the
// linker keeps.
DVec3 crossProduct(const DVec3& a, const DVec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// The orientation s of the top of the file, unscaled; 0 means edge-on or
// degenerate (and NaN cannot occur: the coordinates are finite).
double orientationOf(const RasterView& view, const DVec3 cam[3]) {
    if (view.perspective()) return glm::dot(cam[0], crossProduct(cam[1], cam[2]));
    return -crossProduct(cam[1] - cam[0], cam[2] - cam[0]).z;
}

// Clamps before converting, so that far-off or huge bounds cannot overflow int.
int clampToInt(double x, int lo, int hi) {
    return static_cast<int>(std::clamp(x, static_cast<double>(lo), static_cast<double>(hi)));
}

// The half-open range of pixel indices i whose centre coordinate
// origin + (i + 0.5) / perIndex may lie in [a, b] (perIndex of either sign).
// floor and ceil of the computed positions include every centre as long as
// their rounding error stays below a pixel — it is about 1e-12 pixel — so the
// range is at most one pixel too wide on each side, and the coverage test
// makes the exact decision.
void indexRange(double a, double b, double origin, double perIndex, int limit0, int limit1, int& i0,
                int& i1) {
    const double ia = (a - origin) * perIndex - 0.5;
    const double ib = (b - origin) * perIndex - 0.5;
    i0 = clampToInt(std::floor(std::min(ia, ib)), limit0, limit1);
    i1 = clampToInt(std::ceil(std::max(ia, ib)) + 1.0, limit0, limit1);  // half-open
}

// Sutherland-Hodgman against depth (-z) >= nearDepth. Returns the vertex count
// (0, 3 or 4); a vertex exactly on the plane counts as in front.
int clipToNear(const DVec3 cam[3], double nearDepth, DVec3 out[4]) {
    int n = 0;
    for (int k = 0; k < 3; ++k) {
        const DVec3& p = cam[k];
        const DVec3& q = cam[(k + 1) % 3];
        const double dp = -p.z - nearDepth, dq = -q.z - nearDepth;
        if (dp >= 0.0) out[n++] = p;
        if ((dp >= 0.0) != (dq >= 0.0)) {
            DVec3 x = p + (q - p) * (dp / (dp - dq));
            x.z = -nearDepth;  // on the plane exactly, whatever the rounding above
            out[n++] = x;
        }
    }
    return n;
}

}  // namespace

PixelRect RasterView::pixelsOf(double u0, double u1, double v0, double v1,
                               const PixelRect& limit) const {
    PixelRect r;
    indexRange(u0, u1, l_, columnsPerU_, limit.x0, limit.x1, r.x0, r.x1);
    indexRange(v0, v1, t_, rowsPerV_, limit.y0, limit.y1, r.y0, r.y1);
    return r;
}

bool trianglePixels(const RasterView& view, const DVec3 cam[3], const PixelRect& limit,
                    PixelRect& pixels) {
    if (orientationOf(view, cam) == 0.0) return false;
    DVec3 polygon[4];
    const int corners = clipToNear(cam, view.nearDepth(), polygon);
    if (corners == 0) return false;
    double u0 = kInfinity, u1 = -kInfinity, v0 = kInfinity, v1 = -kInfinity;
    for (int k = 0; k < corners; ++k) {
        // Depth >= d > 0 here, so the perspective divide is safe.
        const double scale = view.perspective() ? view.focalDistance() / -polygon[k].z : 1.0;
        u0 = std::min(u0, scale * polygon[k].x);
        u1 = std::max(u1, scale * polygon[k].x);
        v0 = std::min(v0, scale * polygon[k].y);
        v1 = std::max(v1, scale * polygon[k].y);
    }
    pixels = view.pixelsOf(u0, u1, v0, v1, limit);
    return !pixels.empty();
}

TriangleCoverage triangleCoverage(const RasterView& view, const DVec3 cam[3]) {
    const double s = orientationOf(view, cam) > 0.0 ? 1.0 : -1.0;
    TriangleCoverage coverage;
    for (int k = 0; k < 3; ++k) {
        const DVec3& pi = cam[(k + 1) % 3];
        const DVec3& pj = cam[(k + 2) % 3];
        EdgeFunction& edge = coverage.edges[k];
        if (view.perspective()) {
            const DVec3 normal = crossProduct(pi, pj);  // of the plane through the eye and the edge
            edge.a = s * normal.x;
            edge.b = s * normal.y;
            edge.c = s * (-view.focalDistance() * normal.z);
        } else {
            edge.a = s * (pj.y - pi.y);
            edge.b = s * (pi.x - pj.x);
            edge.c = s * (pi.y * pj.x - pi.x * pj.y);
        }
        edge.ownsTies = edge.a > 0.0 || (edge.a == 0.0 && edge.b > 0.0);
    }
    return coverage;
}

TrianglePlane::TrianglePlane(const Vec3 world[3])
    : p0(world[0]), normal(crossProduct(DVec3(world[1]) - p0, DVec3(world[2]) - p0)) {}

double TrianglePlane::rayParameter(const Ray& ray) const {
    return glm::dot(normal, p0 - DVec3(ray.origin)) / glm::dot(normal, DVec3(ray.dir));
}

}  // namespace strahl::raster
