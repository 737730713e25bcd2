#pragma once
// The watertight ray-triangle test of Woop, Benthin and Wald, "Watertight
// Ray/Triangle Intersection", JCGT 2(1), 2013. A ray that passes through a
// shared edge or vertex of a closed mesh hits at least one of the triangles
// around it — never slips through a crack — and no epsilon is involved. The
// naive tracer uses it for every triangle; the math is explained next to the
// code in src/reference/watertight_triangle.cpp.
//
// Results follow Embree's triangle exactly, so hits compare field by field:
//  - hit.u, hit.v are the barycentric weights of vertices 1 and 2
//    (point = (1 - u - v) * p0 + u * p1 + v * p2);
//  - hit.Ng = (p1 - p0) x (p2 - p0), unnormalised (front = counter-clockwise);
//  - hits are reported for both faces, with tnear < t < tfar.

#include "strahl/core/ray.h"

namespace strahl {

// The per-ray half of the test: the axis permutation and the shear that map
// the ray to the +z axis from the origin. Computed once, reused for every
// triangle the ray is tested against.
struct WatertightRay {
    explicit WatertightRay(const Ray& ray);

    Vec3 origin;
    int kx = 0, ky = 1, kz = 2;  // permuted axes: kz is the dominant direction axis
    float shearX = 0.0f, shearY = 0.0f, scaleZ = 1.0f;  // Sx, Sy, Sz of the paper
};

// Tests triangle (p0, p1, p2) for a hit with tnear < t < tfar. On a hit writes
// hit.t, hit.u, hit.v and hit.Ng and returns true; the IDs are the caller's job.
// On a miss leaves `hit` untouched. Degenerate triangles (zero area seen from
// the ray) and rays parallel to the plane never hit.
bool intersectTriangleWatertight(const WatertightRay& ray, float tnear, float tfar, const Vec3& p0,
                                 const Vec3& p1, const Vec3& p2, Hit& hit);

// One-off form that prepares the ray itself.
inline bool intersectTriangleWatertight(const Ray& ray, const Vec3& p0, const Vec3& p1,
                                        const Vec3& p2, Hit& hit) {
    return intersectTriangleWatertight(WatertightRay(ray), ray.tnear, ray.tfar, p0, p1, p2, hit);
}

}  // namespace strahl
