#pragma once
// Affine transforms (glm::mat4 with last row 0 0 0 1) applied to points, vectors,
// normals, boxes and rays — what instancing needs to move queries into a
// prototype's object space and results back out.

#include "strahl/core/bounds.h"
#include "strahl/core/math.h"
#include "strahl/core/ray.h"

namespace strahl {

inline Vec3 transformPoint(const Mat4& m, const Vec3& p) { return Vec3(m * Vec4(p, 1.0f)); }
inline Vec3 transformVector(const Mat4& m, const Vec3& v) { return Mat3(m) * v; }

// The matrix that maps normals: the inverse transpose of the linear part.
inline Mat3 normalMatrix(const Mat4& m) { return glm::transpose(glm::inverse(Mat3(m))); }

// The box around the 8 transformed corners (conservative for any affine map).
Bounds3 transformBounds(const Mat4& m, const Bounds3& b);

// The ray in the transformed space: origin and direction mapped, direction not
// renormalised, so t (tnear, tfar and every hit's t) means the same point on
// both sides of the map.
inline Ray transformRay(const Mat4& m, const Ray& ray) {
    Ray r = ray;
    r.origin = transformPoint(m, ray.origin);
    r.dir = transformVector(m, ray.dir);
    return r;
}

// Bound on the error of transformPoint(m, p) when p itself is known only up to
// ±pError per axis: the mapped input error, plus the rounding of the 3 products
// and 3 sums per row (pbrt-v4, Transform::operator()(Point3fi), section 6.8.6).
Vec3 transformPointError(const Mat4& m, const Vec3& p, const Vec3& pError);

}  // namespace strahl
