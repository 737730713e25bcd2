#include "strahl/geometry/user_shape.h"

namespace strahl {

Bounds3 UserShape::bounds() const {
    Bounds3 b;
    for (uint32_t i = 0, n = primitiveCount(); i < n; ++i) b.expand(primitiveBounds(i));
    return b;
}

std::vector<ShapeRef> meshShapeRefs(std::span<const TriangleMesh* const> meshes) {
    std::vector<ShapeRef> refs;
    refs.reserve(meshes.size());
    for (const TriangleMesh* mesh : meshes) refs.push_back(ShapeRef{mesh, nullptr});
    return refs;
}

}  // namespace strahl
