#include "strahl/integrator/world.h"

#include <algorithm>

#include "strahl/core/motion.h"
#include "strahl/core/transform.h"

namespace strahl {

namespace {

size_t trianglesOf(const std::vector<SceneShape>& shapes) {
    size_t n = 0;
    for (const SceneShape& s : shapes) n += s.mesh.triangleCount();
    return n;
}

size_t userPrimitivesOf(const std::vector<SceneShape>& shapes) {
    size_t n = 0;
    for (const SceneShape& s : shapes)
        if (s.user) n += s.user->primitiveCount();
    return n;
}

size_t memoryOf(const std::vector<SceneShape>& shapes) {
    size_t n = 0;
    for (const SceneShape& s : shapes) {
        n += s.user ? s.user->memoryBytes() : s.mesh.memoryBytes();
        if (s.tessellated) n += s.tessellated->memoryBytes();
    }
    return n;
}

std::vector<ShapeRef> refsOf(const std::vector<SceneShape>& shapes) {
    std::vector<ShapeRef> refs;
    refs.reserve(shapes.size());
    for (const SceneShape& s : shapes) refs.push_back(s.ref());
    return refs;
}

Bounds3 boundsOf(const std::vector<SceneShape>& shapes) {
    Bounds3 b;
    for (const SceneShape& s : shapes) b.expand(s.ref().bounds());
    return b;
}

}  // namespace

SceneInstance::SceneInstance(uint32_t prototypeIndex, const Mat4& toWorld)
    : prototype(prototypeIndex),
      objectToWorld(toWorld),
      worldToObject(glm::inverse(toWorld)),
      normalToWorld(normalMatrix(toWorld)) {}

SceneInstance::SceneInstance(uint32_t prototypeIndex, std::vector<Mat4> keyframes)
    : SceneInstance(prototypeIndex, keyframes.front()) {
    motion = std::move(keyframes);
}

SurfaceInteraction World::interaction(const Ray& ray, const Hit& hit) const {
    const SceneInstance* inst = instance(hit);
    const SceneShape& s = shape(hit);
    const auto local = [&](const Ray& r) {
        if (s.user) return s.user->interaction(r, hit);
        if (s.tessellated) return s.tessellated->interaction(s.mesh, hit.primID, hit.u, hit.v);
        return triangleInteraction(s.mesh, hit.primID, hit.u, hit.v, r.time);
    };
    if (!inst) return local(ray);
    if (inst->moves()) {  // placed where the ray's time finds it, as the accelerator did
        const Mat4 toWorld = keyframeAt(inst->motion, ray.time);
        return transformInteraction(local(transformRay(glm::inverse(toWorld), ray)), toWorld, normalMatrix(toWorld));
    }
    return transformInteraction(local(transformRay(inst->worldToObject, ray)), inst->objectToWorld,
                                inst->normalToWorld);
}

bool World::hasMotion() const {
    const auto deforming = [](const std::vector<SceneShape>& list) {
        return std::any_of(list.begin(), list.end(), [](const SceneShape& s) { return s.isMesh() && s.mesh.deforms(); });
    };
    return std::any_of(instances.begin(), instances.end(), [](const SceneInstance& i) { return i.moves(); }) ||
           deforming(shapes) ||
           std::any_of(prototypes.begin(), prototypes.end(), [&](const Prototype& p) { return deforming(p.shapes); });
}

AccelScene World::accelScene() const {
    AccelScene scene;
    scene.shapes = refsOf(shapes);
    scene.prototypes.reserve(prototypes.size());
    for (const Prototype& p : prototypes) scene.prototypes.push_back(refsOf(p.shapes));
    scene.instances.reserve(instances.size());
    for (const SceneInstance& i : instances)
        scene.instances.push_back(AccelInstance{i.prototype, i.objectToWorld, i.motion});
    return scene;
}

Bounds3 World::bounds() const {
    Bounds3 b = boundsOf(shapes);
    std::vector<Bounds3> prototypeBounds;
    prototypeBounds.reserve(prototypes.size());
    for (const Prototype& p : prototypes) prototypeBounds.push_back(boundsOf(p.shapes));
    for (const SceneInstance& i : instances)
        b.expand(i.moves() ? keyframeBounds(i.motion, prototypeBounds[i.prototype])
                           : transformBounds(i.objectToWorld, prototypeBounds[i.prototype]));
    return b;
}

size_t World::triangleCount() const {
    size_t n = trianglesOf(shapes);
    for (const Prototype& p : prototypes) n += trianglesOf(p.shapes);
    return n;
}

size_t World::userPrimitiveCount() const {
    size_t n = userPrimitivesOf(shapes);
    for (const Prototype& p : prototypes) n += userPrimitivesOf(p.shapes);
    return n;
}

size_t World::instancedTriangleCount() const {
    std::vector<size_t> perPrototype;
    perPrototype.reserve(prototypes.size());
    for (const Prototype& p : prototypes) perPrototype.push_back(trianglesOf(p.shapes));
    size_t n = trianglesOf(shapes);
    for (const SceneInstance& i : instances) n += perPrototype[i.prototype];
    return n;
}

size_t World::shapeMemoryBytes() const {
    size_t n = memoryOf(shapes) + instances.capacity() * sizeof(SceneInstance);
    for (const Prototype& p : prototypes) n += memoryOf(p.shapes);
    return n;
}

}  // namespace strahl
