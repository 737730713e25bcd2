// World::prepareLights: gathers the explicit lights, the background sky and
// the area lights. Every triangle whose material has a uniform emission, or
// one textured through the uvs, becomes one triangle light in world space,
// once per placement (top level, and once per instance of a prototype), so
// next-event estimation can sample it; the (instID, geomID, primID) -> light
// map lets the path tracer find the light a BSDF-sampled ray hit, for the MIS
// weight. (An emission mapped triplanar is found by BSDF sampling only.)

#include <algorithm>
#include <cmath>
#include <limits>

#include "strahl/core/error.h"
#include "strahl/core/transform.h"
#include "strahl/integrator/world.h"

namespace strahl {

namespace {

uint64_t emitterKey(uint32_t instID, uint32_t geomID) {
    return (static_cast<uint64_t>(instID) << 32) | geomID;
}

// Area lights past this count would make the light table itself the memory
// problem (a Light is about 100 bytes: 2^24 of them take 1.6 GiB); a scene
// that needs more should use fewer emissive instances.
constexpr size_t kMaxAreaLights = size_t(1) << 24;

// Whether next-event estimation samples the material's emission on `shape`:
// uniform, or read through the mesh's uvs (a texture or a checkerboard). A
// tessellated parametric surface's hits take their uv from the exact surface,
// not the mesh, so its patterned emission is left to BSDF sampling; so is an
// emission read from a mesh attribute.
bool lightSampled(const Material& m, const SceneShape& shape) {
    if (!m.emits()) return false;
    if (m.hasUniformEmission()) return true;
    bool attribute = false;  // anywhere in the emission's mixes
    visitTextures(m.emission, TextureEncoding::Color,
                  [&](const TextureRef& t, TextureEncoding) { attribute |= !t.meshAttribute.empty(); });
    return m.mapping.kind == TextureMapping::Kind::UV && !shape.tessellated && !attribute;
}

// The mean of a textured emission's pattern over its image (for the light's
// power, which only weighs the light's choice): the texture's top MIP level,
// or the checkerboard's two colours; 1 for a uniform emission or a mix.
float patternMean(const Material& m, const TextureSystem* textures) {
    const TexturedColor& e = m.emission;
    if (e.mix) return 1.0f;
    if (e.checkerboard)
        return 0.5f * (light_detail::mean(e.checkerboard->color0) + light_detail::mean(e.checkerboard->color1));
    if (e.texture.valid() && textures)
        return light_detail::mean(Color(textures->lookup(e.texture.handle, Vec2(0.5f), 1.0f)));
    return 1.0f;
}

}  // namespace

void World::prepareLights() {
    std::vector<Light> all = lights;
    if (maxComponent(background) > 0.0f) {
        SkyLight sky;
        sky.radiance = background;
        all.push_back(sky);
    }
    // The emitter of each light: its own for the scene's lights and the sky,
    // one per emitting shape (and instance) for triangle lights.
    std::vector<uint32_t> emitterOf(all.size());
    for (size_t i = 0; i < all.size(); ++i) emitterOf[i] = static_cast<uint32_t>(i);
    auto emitters = static_cast<uint32_t>(all.size());
    emitterOffset_.clear();
    areaLightOfPrim_.clear();
    // patternMean per material, computed on first use (NaN: not yet).
    std::vector<float> patternMeans(materials.size(), std::numeric_limits<float>::quiet_NaN());

    const auto addShape = [&](const SceneShape& shape, uint32_t instID, uint32_t geomID,
                              const Mat4* toWorld) {
        // A deforming emitter, like a moving one, is found by BSDF sampling.
        if (!shape.isMesh() || shape.mesh.deforms()) return;
        bool emits = false;
        for (uint32_t m : shape.materialOfSlot) emits |= lightSampled(materials[m], shape);
        if (!emits) return;
        const TriangleMesh& mesh = shape.mesh;
        const uint32_t emitter = emitters++;
        const auto offset = static_cast<uint32_t>(areaLightOfPrim_.size());
        emitterOffset_[emitterKey(instID, geomID)] = offset;
        areaLightOfPrim_.resize(areaLightOfPrim_.size() + mesh.triangleCount(), kInvalidId);
        for (size_t t = 0; t < mesh.triangleCount(); ++t) {
            const uint32_t slot = mesh.faceMaterials.empty() ? 0u : mesh.faceMaterials[t];
            const Material& material = materials[shape.materialOfSlot[slot]];
            if (!lightSampled(material, shape)) continue;
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
            if (!material.hasUniformEmission()) {
                light.textured = &material;
                if (!mesh.uvs.empty()) {  // else the barycentric uvs (0,0), (1,0), (0,1)
                    light.uv0 = mesh.uvs[mesh.indices[3 * t]];
                    light.uv1 = mesh.uvs[mesh.indices[3 * t + 1]];
                    light.uv2 = mesh.uvs[mesh.indices[3 * t + 2]];
                }
                float& mean = patternMeans[shape.materialOfSlot[slot]];
                if (std::isnan(mean)) mean = patternMean(material, textures.get());
                light.textureMean = mean;
            }
            if (all.size() >= kMaxAreaLights)
                fail("the scene has more than ", kMaxAreaLights,
                     " emissive triangles (counting every instance); use fewer emissive"
                     " instances");
            areaLightOfPrim_[offset + t] = static_cast<uint32_t>(all.size());
            all.emplace_back(light);
            emitterOf.push_back(emitter);
        }
    };
    for (size_t g = 0; g < shapes.size(); ++g)
        addShape(shapes[g], kInvalidId, static_cast<uint32_t>(g), nullptr);
    for (size_t i = 0; i < instances.size(); ++i) {
        const SceneInstance& inst = instances[i];
        // A moving emitter is somewhere else at every time: its light is found
        // by the paths that hit it (BSDF sampling), not sampled from a fixed
        // set of triangles.
        if (inst.moves()) continue;
        const auto instID = static_cast<uint32_t>(shapes.size() + i);
        const Prototype& proto = prototypes[inst.prototype];
        for (size_t g = 0; g < proto.shapes.size(); ++g)
            addShape(proto.shapes[g], instID, static_cast<uint32_t>(g), &inst.objectToWorld);
    }
    lightSet = LightSet(std::move(all), bounds(), lightSelection, emitterOf);
    lightsPrepared_ = true;
    emissionReachable_ = !lightSet.infiniteLights().empty() ||
                         std::any_of(materials.begin(), materials.end(),
                                     [](const Material& m) { return m.emits(); });
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
