#pragma once
// Internal: one triangle prepared for rasterization, in two steps that match
// the rasterizer's two passes — its pixel bounds (projected into the camera
// frame and clipped against the plane where camera rays start) for binning,
// then its three edge functions with the tie rule and its plane for the
// per-pixel test. The math and the reasons for it are in triangle_setup.cpp
// and docs/rasterizer.md.

#include <glm/glm.hpp>

#include "strahl/camera/camera.h"
#include "strahl/core/pixel_rect.h"
#include "strahl/core/ray.h"

namespace strahl::raster {

using DVec3 = glm::dvec3;

// The camera as the rasterizer needs it: the frame that vertices are projected
// into and the window coordinates of the pixel centres, computed exactly as
// Camera::generateRay computes them.
class RasterView {
public:
    explicit RasterView(const Camera& camera);

    // (along u, along v, along w) relative to the eye; the camera looks down -w.
    // Out of line, so every vertex is transformed by the same rounding rules.
    DVec3 toCamera(const Vec3& world) const;
    // Window coordinates (on the image plane) of the centre of column px / row py.
    double centreU(int px) const;
    double centreV(int py) const;

    bool perspective() const { return perspective_; }
    double focalDistance() const { return d_; }
    // Depth along -w where camera rays start: the image plane (d) for perspective
    // rays, the eye plane (0) for orthographic ones. Nothing nearer is visible.
    double nearDepth() const { return perspective_ ? d_ : 0.0; }

    // The pixels whose centres may lie in window rectangle [u0, u1] x [v0, v1],
    // clipped to `limit` (empty if none can).
    PixelRect pixelsOf(double u0, double u1, double v0, double v1, const PixelRect& limit) const;

private:
    DVec3 e_, u_, v_, w_;  // the camera frame, converted once
    bool perspective_;
    double d_;
    float l_, t_;    // window left and top
    float du_, dv_;  // window extent per pixel, as in Camera: (r - l) / nx, (b - t) / ny
    double columnsPerU_, rowsPerV_;  // 1 / du_, 1 / dv_
};

// The pixels (inside `limit`) whose centres the triangle with camera-space
// vertices cam[0..2] may cover, widened by less than a pixel for rounding.
// Returns false if it cannot cover any: zero area as seen from the camera
// (degenerate or edge-on), wholly nearer than view.nearDepth(), or outside.
bool trianglePixels(const RasterView& view, const DVec3 cam[3], const PixelRect& limit,
                    PixelRect& pixels);

// E(u, v) = a u + b v + c at window position (u, v), scaled so that the inside
// is E > 0; a centre with E == 0 belongs to the edge only if it owns ties (see
// the tie rule in triangle_setup.cpp).
struct EdgeFunction {
    double a = 0.0, b = 0.0, c = 0.0;
    bool ownsTies = false;

    double at(double u, double v) const { return a * u + b * v + c; }
};

// The coverage test of a triangle: edge k is the edge opposite vertex k —
// (1, 2), (2, 0), (0, 1).
struct TriangleCoverage {
    EdgeFunction edges[3];

    // Whether the pixel centre at window position (u, v) is inside, with the
    // tie rule. If so, weights[k] receives E_k: proportional to the barycentric
    // weight of vertex k, with a positive sum.
    bool covers(double u, double v, double weights[3]) const {
        for (int k = 0; k < 3; ++k) {
            const double e = edges[k].at(u, v);
            if (e < 0.0 || (e == 0.0 && !edges[k].ownsTies)) return false;
            weights[k] = e;
        }
        return true;
    }
};

// For a triangle that trianglePixels accepted.
TriangleCoverage triangleCoverage(const RasterView& view, const DVec3 cam[3]);

// The triangle's plane in world space, for the depth of a covered pixel.
struct TrianglePlane {
    DVec3 p0;      // vertex 0
    DVec3 normal;  // (p1 - p0) x (p2 - p0)

    explicit TrianglePlane(const Vec3 world[3]);
    // The parameter t at which `ray` meets the plane (in units of |ray.dir|);
    // not finite if the ray runs parallel to it.
    double rayParameter(const Ray& ray) const;
};

}  // namespace strahl::raster
