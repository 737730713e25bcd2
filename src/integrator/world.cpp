#include "strahl/integrator/world.h"

namespace strahl {

Bounds3 World::bounds() const {
    Bounds3 b;
    for (const MeshGeometry& g : meshes) b.expand(g.mesh.bounds());
    return b;
}

size_t World::triangleCount() const {
    size_t n = 0;
    for (const MeshGeometry& g : meshes) n += g.mesh.triangleCount();
    return n;
}

size_t World::meshMemoryBytes() const {
    size_t n = 0;
    for (const MeshGeometry& g : meshes) n += g.mesh.memoryBytes();
    return n;
}

}  // namespace strahl
