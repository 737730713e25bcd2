#include "strahl/geometry/user_shape.h"

namespace strahl {

Bounds3 UserShape::bounds() const {
    Bounds3 b;
    for (uint32_t i = 0, n = primitiveCount(); i < n; ++i) b.expand(primitiveBounds(i));
    return b;
}

}  // namespace strahl
