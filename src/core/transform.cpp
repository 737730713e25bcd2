#include "strahl/core/transform.h"

namespace strahl {

Bounds3 transformBounds(const Mat4& m, const Bounds3& b) {
    Bounds3 out;
    if (b.empty()) return out;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                     (corner & 4) ? b.max.z : b.min.z);
        out.expand(transformPoint(m, p));
    }
    return out;
}

Vec3 transformPointError(const Mat4& m, const Vec3& p, const Vec3& pError) {
    // glm is column-major: m[col][row].
    constexpr float g3 = gammaBound(3);
    Vec3 error;
    for (int row = 0; row < 3; ++row) {
        const float mappedError = std::abs(m[0][row]) * pError.x + std::abs(m[1][row]) * pError.y +
                                  std::abs(m[2][row]) * pError.z;
        const float magnitude = std::abs(m[0][row] * p.x) + std::abs(m[1][row] * p.y) +
                                std::abs(m[2][row] * p.z) + std::abs(m[3][row]);
        error[row] = (g3 + 1.0f) * mappedError + g3 * magnitude;
    }
    return error;
}

}  // namespace strahl
