// Alpha cut-outs from material opacity (docs/materials.md, "Opacity"): the
// Cutout of a mesh whose materials have an opacity, and World::prepareCutouts.
//
// The decision at a hit: opacity o read at the hit's uv, footprint 0. With a
// cutoff c, solid where o >= c. Otherwise o >= 1 is solid, o <= 0 (or NaN) a
// hole, and in between the hit is solid when a hash of the hit
// (triangle and barycentrics, bit for bit) falls below o. The hash is a fixed
// function of the point, not a random stream, so every tracer, thread and
// tile order sees the same surface; as hits land on continuous (u, v), the
// fraction of solid hits over any area is o (a stochastic opacity, as
// Cycles and pbrt-v4 treat partial alpha).

#include <bit>
#include <cstring>
#include <mutex>

#include "strahl/core/error.h"
#include "strahl/integrator/world.h"

namespace strahl {

namespace {

// splitmix64's finaliser (Steele, Lea & Flood 2014): a bijective mix whose
// every output bit depends on every input bit.
uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

class MaterialCutout final : public Cutout {
public:
    MaterialCutout(const TriangleMesh& mesh, const std::vector<uint32_t>& materialOfSlot,
                   const Material* materials, const TextureSystem* textures,
                   CutoutErrors& errors)
        : mesh_(mesh), materialOfSlot_(materialOfSlot), materials_(materials),
          textures_(textures), errors_(errors) {}

    bool solid(uint32_t prim, float u, float v) const noexcept override {
        try {
            const uint32_t slot = mesh_.faceMaterials.empty() ? 0 : mesh_.faceMaterials[prim];
            const Material& material = materials_[materialOfSlot_[slot]];
            if (!material.cutsOut()) return true;
            const float opacity = opacityAt(material, uvAt(prim, u, v), textures_);
            if (material.opacityCutoff >= 0.0f) return opacity >= material.opacityCutoff;
            if (opacity >= 1.0f) return true;
            if (!(opacity > 0.0f)) return false;
            const uint64_t key = (uint64_t(std::bit_cast<uint32_t>(u)) << 32) |
                                 std::bit_cast<uint32_t>(v);
            const uint64_t h = mix64(key ^ mix64(prim + 0x9e3779b97f4a7c15ull));
            // The top 24 bits as a float in [0, 1).
            return float(h >> 40) * 0x1p-24f < opacity;
        } catch (...) {
            errors_.record(std::current_exception());
            return true;
        }
    }

private:
    Vec2 uvAt(uint32_t prim, float u, float v) const {
        if (mesh_.uvs.empty()) return Vec2(0.0f);
        const uint32_t* tri = &mesh_.indices[3 * size_t(prim)];
        return (1.0f - u - v) * mesh_.uvs[tri[0]] + u * mesh_.uvs[tri[1]] + v * mesh_.uvs[tri[2]];
    }

    const TriangleMesh& mesh_;
    const std::vector<uint32_t>& materialOfSlot_;
    const Material* materials_;  // World::materials' data, stable once final
    const TextureSystem* textures_;
    CutoutErrors& errors_;
};

// Gives the meshes of `shapes` whose materials cut out their Cutout; refuses
// user shapes with such a material.
void prepareShapes(std::vector<SceneShape>& shapes, const World& world, CutoutErrors& errors) {
    for (SceneShape& shape : shapes) {
        bool cutsOut = false, textured = false;
        for (uint32_t m : shape.materialOfSlot) {
            const Material& material = world.materials[m];
            cutsOut = cutsOut || material.cutsOut();
            textured = textured || (material.cutsOut() && material.opacity.texture.valid());
        }
        shape.cutout = nullptr;
        if (!cutsOut) continue;
        if (!shape.isMesh())
            fail("shape '", shape.name, "': its material has an opacity, and cut-outs are "
                 "supported on triangle meshes only (not on ", shape.user->describe(), ")");
        if (textured && shape.mesh.uvs.empty())
            fail("shape '", shape.name, "': its material's opacity is a texture, which needs "
                 "texture coordinates, and the mesh has none");
        shape.cutout = std::make_shared<MaterialCutout>(shape.mesh, shape.materialOfSlot,
                                                        world.materials.data(),
                                                        world.textures.get(), errors);
    }
}

}  // namespace

void CutoutErrors::record(std::exception_ptr error) noexcept {
    std::lock_guard lock(mutex_);
    if (!first_) first_ = error;
    failed_.store(true, std::memory_order_release);
}

void CutoutErrors::rethrow() const {
    if (!failed_.load(std::memory_order_acquire)) return;
    std::lock_guard lock(mutex_);
    std::rethrow_exception(first_);
}

void World::prepareCutouts() {
    if (!cutoutErrors_) cutoutErrors_ = std::make_unique<CutoutErrors>();
    prepareShapes(shapes, *this, *cutoutErrors_);
    for (Prototype& p : prototypes) prepareShapes(p.shapes, *this, *cutoutErrors_);
}

void World::rethrowCutoutError() const {
    if (cutoutErrors_) cutoutErrors_->rethrow();
}

}  // namespace strahl
