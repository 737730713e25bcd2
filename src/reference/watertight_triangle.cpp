// Watertight ray-triangle intersection (Woop, Benthin, Wald, JCGT 2013).
//
// Derivation. Translate the triangle so the ray origin is at 0, then apply the
// affine map M that sends the ray direction d to the unit +z axis:
//  1. permute the axes so z is the dominant axis of d (kz = argmax |d_i|); this
//     makes d_kz the largest divisor below, and swapping kx and ky when d_kz < 0
//     keeps the permutation's handedness so the winding seen along the ray is
//     preserved;
//  2. shear x and y by Sx = d_kx / d_kz, Sy = d_ky / d_kz and scale z by
//     Sz = 1 / d_kz, i.e. a point a maps to (a_x - Sx a_z, a_y - Sy a_z, Sz a_z).
// In that space the ray is the z axis and the ray parameter t is simply z. The
// question "does the ray pierce the triangle" becomes the 2-D question "is the
// origin inside the projected triangle A, B, C", answered by the three edge
// functions (twice the signed areas of the sub-triangles the origin cuts off):
//     U = Cx By - Cy Bx   (edge B->C, opposite A = p0)
//     V = Ax Cy - Ay Cx   (edge C->A, opposite B = p1)
//     W = Bx Ay - By Ax   (edge A->B, opposite C = p2)
// The origin is inside iff U, V, W share a sign (zeros allowed: edges and
// vertices are inside). det = U + V + W is twice the projected area; U/det,
// V/det, W/det are the barycentric weights of p0, p1, p2, so Embree's
// (u, v) = (V, W) / det, and t is the barycentric blend of the vertices' z:
// t = (U Az + V Bz + W Cz) / det.
//
// Why it is watertight. The transformed coordinates of a vertex depend only on
// the vertex and the ray, so two triangles sharing an edge compute bit-identical
// endpoints, and the edge function of the shared edge evaluates to exactly
// opposite values (products commute exactly and round-to-nearest is odd), so at
// most one side rejects. A nonzero float edge function also has the true sign:
// rounding is monotone, so fl(ab) >= fl(cd) whenever ab >= cd. Only an exact 0
// is ambiguous — the origin may be on the edge or the float subtraction may have
// cancelled — and then all three are recomputed in double, where the product of
// two floats is exact (24 + 24 significant bits < 53), so the one rounding of the
// difference keeps the exact sign. No epsilon appears anywhere.
//
// Rejected alternatives: Moeller-Trumbore (Embree's default triangle test;
// RTC_SCENE_FLAG_ROBUST switches it to a watertight Pluecker test) computes each
// triangle's barycentrics from its own edge vectors, so neighbours disagree by
// rounding and rays can slip through shared edges; always
// computing the edge functions in double is as robust but hides the paper's
// structure (cheap float, rare exact fallback) that this oracle documents.
//
// The float edge functions must be evaluated exactly as written: a fused
// multiply-add rounds one product but not the other, which breaks both the
// exact antisymmetry and the sign argument above. GCC contracts a*b - c*d into
// an FMA by default whenever the target has one (-mfma, -march=native): built
// that way without the pragma below, 76 of the 64,008 edge rays of the
// icosphere test in tests/reference slip through. The pragma switches
// contraction off for this file.

#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "strahl/reference/watertight_triangle.h"

#include <algorithm>
#include <cmath>

namespace strahl {

WatertightRay::WatertightRay(const Ray& ray) : origin(ray.origin) {
    const Vec3 absDir = glm::abs(ray.dir);
    kz = absDir.x > absDir.y ? (absDir.x > absDir.z ? 0 : 2) : (absDir.y > absDir.z ? 1 : 2);
    kx = (kz + 1) % 3;
    ky = (kx + 1) % 3;
    if (ray.dir[kz] < 0.0f) std::swap(kx, ky);
    shearX = ray.dir[kx] / ray.dir[kz];
    shearY = ray.dir[ky] / ray.dir[kz];
    scaleZ = 1.0f / ray.dir[kz];
}

namespace {

// A vertex in ray space: x, y after the shear, z = its ray parameter.
struct RaySpaceVertex {
    float x, y, z;
};

RaySpaceVertex toRaySpace(const WatertightRay& ray, const Vec3& p) {
    // A plain array indexes with a load; glm's operator[] is a switch per
    // access, which made the whole test 3-4 times slower.
    const Vec3 relative = p - ray.origin;
    const float a[3] = {relative.x, relative.y, relative.z};
    return {a[ray.kx] - ray.shearX * a[ray.kz], a[ray.ky] - ray.shearY * a[ray.kz],
            ray.scaleZ * a[ray.kz]};
}

// Edge function of the 2-D edge p->q at the origin, in float and exactly.
float edgeFunction(const RaySpaceVertex& p, const RaySpaceVertex& q) {
    return p.x * q.y - p.y * q.x;
}
float edgeFunctionExact(const RaySpaceVertex& p, const RaySpaceVertex& q) {
    return static_cast<float>(static_cast<double>(p.x) * static_cast<double>(q.y) -
                              static_cast<double>(p.y) * static_cast<double>(q.x));
}

// A bound on the rounding error of t near 0 (pbrt-v4, Triangle::Intersect,
// "ensure that computed triangle t is conservatively greater than zero"): the
// errors of the ray-space z's, of the edge functions and of their blend, each
// bounded with gamma(n). A t below it may really be ≤ 0 — typically a shadow
// ray whose origin lies exactly in the plane of the triangle it leaves, which
// a float t of +1e-9 would otherwise report as its own occluder.
float conservativeTZero(const RaySpaceVertex& a, const RaySpaceVertex& b, const RaySpaceVertex& c,
                        float e0, float e1, float e2, float det) {
    const float maxZ = std::max({std::abs(a.z), std::abs(b.z), std::abs(c.z)});
    const float maxX = std::max({std::abs(a.x), std::abs(b.x), std::abs(c.x)});
    const float maxY = std::max({std::abs(a.y), std::abs(b.y), std::abs(c.y)});
    const float deltaZ = gammaBound(3) * maxZ;
    const float deltaX = gammaBound(5) * (maxX + maxZ);
    const float deltaY = gammaBound(5) * (maxY + maxZ);
    const float deltaE = 2.0f * (gammaBound(2) * maxX * maxY + deltaY * maxX + deltaX * maxY);
    const float maxE = std::max({std::abs(e0), std::abs(e1), std::abs(e2)});
    return 3.0f * (gammaBound(3) * maxE * maxZ + deltaE * maxZ + deltaZ * maxE) / std::abs(det);
}

}  // namespace

bool intersectTriangleWatertight(const WatertightRay& ray, float tnear, float tfar, const Vec3& p0,
                                 const Vec3& p1, const Vec3& p2, Hit& hit) {
    const RaySpaceVertex a = toRaySpace(ray, p0);
    const RaySpaceVertex b = toRaySpace(ray, p1);
    const RaySpaceVertex c = toRaySpace(ray, p2);

    float edgeU = edgeFunction(c, b);
    float edgeV = edgeFunction(a, c);
    float edgeW = edgeFunction(b, a);
    if (edgeU == 0.0f || edgeV == 0.0f || edgeW == 0.0f) {
        edgeU = edgeFunctionExact(c, b);
        edgeV = edgeFunctionExact(a, c);
        edgeW = edgeFunctionExact(b, a);
    }

    // Both faces count: reject only if the signs are mixed. A NaN (from a zero
    // or non-finite direction) fails every comparison here but poisons det and t
    // below, which then fail the range test.
    const bool anyNegative = edgeU < 0.0f || edgeV < 0.0f || edgeW < 0.0f;
    const bool anyPositive = edgeU > 0.0f || edgeV > 0.0f || edgeW > 0.0f;
    if (anyNegative && anyPositive) return false;

    const float det = edgeU + edgeV + edgeW;
    if (det == 0.0f) return false;  // ray parallel to the plane, or a degenerate triangle

    // The paper compares T against det * tfar to avoid the division; dividing
    // first tests the very t that is reported, so tnear < hit.t < tfar holds
    // exactly, as the Accel contract promises.
    const float scaledT = edgeU * a.z + edgeV * b.z + edgeW * c.z;
    const float t = scaledT / det;
    if (!(t > tnear && t < tfar)) return false;
    if (t <= conservativeTZero(a, b, c, edgeU, edgeV, edgeW, det)) return false;

    hit.t = t;
    hit.u = edgeV / det;
    hit.v = edgeW / det;
    hit.Ng = glm::cross(p1 - p0, p2 - p0);
    return true;
}

}  // namespace strahl
