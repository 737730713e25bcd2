#pragma once
// SurfaceHit: the closest hit of a ray, with the full surface interaction
// computed on first use and at most once (the second phase of two-phase
// intersection). Integrators that need only a normal or the IDs never pay for
// fetching the triangle's vertices, which on large meshes are cache misses.

#include <optional>

#include "strahl/core/ray.h"
#include "strahl/integrator/world.h"

namespace strahl {

class SurfaceHit {
public:
    SurfaceHit(const World& world, const Ray& ray, const Hit& hit)
        : world_(world), ray_(ray), hit_(hit) {}

    const Ray& ray() const { return ray_; }
    const Hit& hit() const { return hit_; }

    const SurfaceInteraction& interaction() const {
        if (!si_) si_ = world_.interaction(ray_, hit_);
        return *si_;
    }
    const Material& material() const { return world_.material(hit_, interaction()); }

    // Unit shading normal. For meshes without vertex normals it is the
    // accelerator's geometric normal, normalised, with no vertex fetch.
    Vec3 shadingNormal() const {
        const SceneShape& shape = world_.shape(hit_);
        if (!si_ && shape.isMesh() && shape.mesh.normals.empty()) {
            const SceneInstance* instance = world_.instance(hit_);
            // An instanced hit's Ng is in object space (a moving instance's
            // map depends on the time: the interaction knows it).
            if (!instance || !instance->moves()) {
                const Vec3 ng = instance ? instance->normalToWorld * hit_.Ng : hit_.Ng;
                const float len = glm::length(ng);
                if (len > 0.0f) return ng / len;
            }
        }
        return interaction().Ns;
    }

private:
    const World& world_;
    const Ray& ray_;
    const Hit& hit_;
    mutable std::optional<SurfaceInteraction> si_;
};

}  // namespace strahl
