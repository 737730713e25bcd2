// World::prepareLights: gathers the explicit lights, the background sky and
// the area lights. Every triangle whose material has uniform (untextured)
// emission becomes one triangle light in world space, once per placement (top
// level, and once per instance of a prototype), so next-event estimation can
// sample it; the (instID, geomID, primID) -> light map lets the path tracer
// find the light a BSDF-sampled ray hit, for the MIS weight.

#include "strahl/core/error.h"
#include "strahl/core/transform.h"
#include "strahl/integrator/world.h"

namespace strahl {

namespace {

uint64_t emitterKey(uint32_t instID, uint32_t geomID) {
    return (static_cast<uint64_t>(instID) << 32) | geomID;
}

// Area lights past this count would make the light table itself the memory
// problem (a Light is 112 bytes: 2^24 of them take 1.75 GiB); a scene that needs more should use
// textured emission or fewer emissive instances.
constexpr size_t kMaxAreaLights = size_t(1) << 24;

}  // namespace

void World::prepareLights() {
    std::vector<Light> all = lights;
    if (maxComponent(background) > 0.0f) {
        SkyLight sky;
        sky.radiance = background;
        all.push_back(sky);
    }
    emitterOffset_.clear();
    areaLightOfPrim_.clear();

    const auto addShape = [&](const SceneShape& shape, uint32_t instID, uint32_t geomID,
                              const Mat4* toWorld) {
        if (!shape.isMesh()) return;
        bool emits = false;
        for (uint32_t m : shape.materialOfSlot) emits |= materials[m].hasUniformEmission();
        if (!emits) return;
        const TriangleMesh& mesh = shape.mesh;
        const auto offset = static_cast<uint32_t>(areaLightOfPrim_.size());
        emitterOffset_[emitterKey(instID, geomID)] = offset;
        areaLightOfPrim_.resize(areaLightOfPrim_.size() + mesh.triangleCount(), kInvalidId);
        for (size_t t = 0; t < mesh.triangleCount(); ++t) {
            const uint32_t slot = mesh.faceMaterials.empty() ? 0u : mesh.faceMaterials[t];
            const Material& material = materials[shape.materialOfSlot[slot]];
            if (!material.hasUniformEmission()) continue;
            TriangleLight light;
            Vec3 p[3];
            for (int k = 0; k < 3; ++k) {
                p[k] = mesh.positions[mesh.indices[3 * t + size_t(k)]];
                if (toWorld) p[k] = transformPoint(*toWorld, p[k]);
            }
            light.p0 = p[0];
            light.p1 = p[1];
            light.p2 = p[2];
            // Zero-area triangles emit nothing and cannot be sampled.
            if (glm::length(glm::cross(p[1] - p[0], p[2] - p[0])) <= 0.0f) continue;
            light.radiance = material.emission.value;
            light.twoSided = material.twoSidedEmission;
            if (all.size() >= kMaxAreaLights)
                fail("the scene has more than ", kMaxAreaLights,
                     " emissive triangles (counting every instance); use fewer emissive"
                     " instances or a textured emission, which is not light-sampled");
            areaLightOfPrim_[offset + t] = static_cast<uint32_t>(all.size());
            all.emplace_back(light);
        }
    };
    for (size_t g = 0; g < shapes.size(); ++g)
        addShape(shapes[g], kInvalidId, static_cast<uint32_t>(g), nullptr);
    for (size_t i = 0; i < instances.size(); ++i) {
        const SceneInstance& inst = instances[i];
        const auto instID = static_cast<uint32_t>(shapes.size() + i);
        const Prototype& proto = prototypes[inst.prototype];
        for (size_t g = 0; g < proto.shapes.size(); ++g)
            addShape(proto.shapes[g], instID, static_cast<uint32_t>(g), &inst.objectToWorld);
    }
    lightSet = LightSet(std::move(all), bounds());
    lightsPrepared_ = true;
}

uint32_t World::areaLightOf(const Hit& hit) const {
    if (emitterOffset_.empty()) return kInvalidId;
    const auto it = emitterOffset_.find(emitterKey(hit.instID, hit.geomID));
    if (it == emitterOffset_.end()) return kInvalidId;
    return areaLightOfPrim_[it->second + hit.primID];
}

Color World::escapedRadiance(const Vec3& dir) const {
    Color L(0.0f);
    for (uint32_t i : lightSet.infiniteLights()) L += infiniteLe(lightSet.lights()[i], dir);
    return L;
}

}  // namespace strahl
