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
        if (!si_)
            if (const std::optional<Vec3> n = normalWithoutInteraction(world_, hit_)) return *n;
        return interaction().Ns;
    }

    // The unit shading normal of a valid hit when it needs no surface
    // interaction: on a mesh without vertex normals, the accelerator's Ng
    // normalised (mapped to world space for an instance at rest); nullopt
    // for everything else (and a zero Ng). Camera packets shade from it too
    // (Integrator::shadeCameraLanes), so both give the same bits.
    static std::optional<Vec3> normalWithoutInteraction(const World& world, const Hit& hit) {
        const SceneShape& shape = world.shape(hit);
        if (!shape.isMesh() || !shape.mesh.normals.empty()) return std::nullopt;
        const SceneInstance* instance = world.instance(hit);
        // An instanced hit's Ng is in object space (a moving instance's
        // map depends on the time: the interaction knows it).
        if (instance && instance->moves()) return std::nullopt;
        const Vec3 ng = instance ? instance->normalToWorld * hit.Ng : hit.Ng;
        const float len = glm::length(ng);
        if (!(len > 0.0f)) return std::nullopt;
        return ng / len;
    }

private:
    const World& world_;
    const Ray& ray_;
    const Hit& hit_;
    mutable std::optional<SurfaceInteraction> si_;
};

}  // namespace strahl
