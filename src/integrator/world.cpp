#include "strahl/integrator/world.h"

namespace strahl {

Bounds3 World::bounds() const {
    Bounds3 b;
    for (const SceneShape& s : shapes) b.expand(s.ref().bounds());
    return b;
}

std::vector<ShapeRef> World::shapeRefs() const {
    std::vector<ShapeRef> refs;
    refs.reserve(shapes.size());
    for (const SceneShape& s : shapes) refs.push_back(s.ref());
    return refs;
}

size_t World::triangleCount() const {
    size_t n = 0;
    for (const SceneShape& s : shapes) n += s.mesh.triangleCount();
    return n;
}

size_t World::userPrimitiveCount() const {
    size_t n = 0;
    for (const SceneShape& s : shapes)
        if (s.user) n += s.user->primitiveCount();
    return n;
}

size_t World::shapeMemoryBytes() const {
    size_t n = 0;
    for (const SceneShape& s : shapes) n += s.user ? s.user->memoryBytes() : s.mesh.memoryBytes();
    return n;
}

}  // namespace strahl
