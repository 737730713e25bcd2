#include "transform_parser.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace strahl::scene_detail {

namespace {

// |det| / (product of the column lengths) lies in [0, 1] (Hadamard's inequality):
// 1 for orthogonal axes (any rotation and scale), 0 for a matrix that flattens
// space. Below this the transform is singular.
constexpr double kMinDeterminantRatio = 1e-6;

Mat4 parseTransformOp(const JsonValue& op) {
    if (!op.raw().is_object() || op.raw().size() != 1)
        op.fail("expected an object with exactly one of translate, scale, rotate, matrix, got ",
                op.raw().is_object() ? concat("an object with ", op.raw().size(), " keys")
                                     : op.describe());
    op.requireKeys({"translate", "scale", "rotate", "matrix"});
    const std::string key = op.raw().begin().key();
    const JsonValue arg = op.get(key);
    const Mat4 identity(1.0f);
    if (key == "translate") return glm::translate(identity, arg.vec3());
    if (key == "scale") {
        if (!arg.raw().is_number() && !arg.raw().is_array())
            arg.fail("expected a number or an array of 3 numbers, got ", arg.describe());
        const Vec3 s = arg.raw().is_number() ? Vec3(arg.number()) : arg.vec3();
        if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f)
            arg.fail("must be non-zero, got ", arg.raw().dump());
        return glm::scale(identity, s);
    }
    if (key == "rotate") {
        arg.requireKeys({"axis", "angle"});
        const JsonValue axisValue = arg.get("axis");
        const Vec3 axis = axisValue.vec3();
        if (axis == Vec3(0.0f)) axisValue.fail("must be non-zero");
        const float degrees = arg.get("angle").number();
        return glm::rotate(identity, glm::radians(degrees), unitVector(axis));
    }
    // "matrix": 16 numbers, row-major; glm indexes m[column][row].
    if (arg.size() != 16) arg.fail("expected an array of 16 numbers, got an array of ", arg.size());
    Mat4 m;
    for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 4; ++col) m[col][row] = arg.at(size_t(4 * row + col)).number();
    }
    if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f)
        arg.fail("must be affine: the last row must be 0 0 0 1, got ", m[0][3], " ", m[1][3], " ",
                 m[2][3], " ", m[3][3]);
    return m;
}

}  // namespace

Mat4 parseTransform(const JsonValue& v) {
    Mat4 m(1.0f);
    for (size_t i = 0; i < v.size(); ++i) m = parseTransformOp(v.at(i)) * m;
    for (int col = 0; col < 4; ++col) {
        if (!isFinite(Vec3(m[col]))) v.fail("the composed transform exceeds the float range");
    }
    const glm::dmat3 linear{Mat3(m)};
    const double det = glm::determinant(linear);
    const double scale = glm::length(linear[0]) * glm::length(linear[1]) * glm::length(linear[2]);
    if (!(std::abs(det) > kMinDeterminantRatio * scale))
        v.fail("the composed transform is singular (determinant ", det, ")");
    return m;
}

}  // namespace strahl::scene_detail
