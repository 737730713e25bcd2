#pragma once
// Internal to the scene module: the "transform" array of a shape (or of a CSG
// operand) — translate, scale, rotate and matrix operations — as one affine
// matrix. Documented in docs/scene-format.md.

#include "json_reader.h"
#include "strahl/core/math.h"

namespace strahl::scene_detail {

// The operations apply in the order listed, so the first is the rightmost
// factor. Throws (naming the pointer) on a malformed operation, a non-affine
// matrix, or a composed transform that is singular or exceeds the float range.
Mat4 parseTransform(const JsonValue& v);

}  // namespace strahl::scene_detail
