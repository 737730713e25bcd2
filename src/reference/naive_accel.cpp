// NaiveAccel: every ray against every primitive (see naive_accel.h).
//
// Invariants:
//  - geomID == index into shapes_ (or into an instanced prototype's list, with
//    instID = shapes_.size() + instance index), primID == triangle / primitive
//    index — the same numbering Embree reports, so the two compare hit for hit.
//  - An instance is tested by mapping the ray into its object space, exactly
//    as Embree does: t keeps its meaning and Ng stays in object space.
//  - The nearest-hit search only ever shrinks tfar, and accepts a candidate
//    only if it is strictly nearer (the triangle test and UserShape::intersect
//    both require t < tfar), so of several hits at the same t the first in
//    (geomID, primID) order wins: answers do not depend on anything but the
//    input.
//  - A triangle hit on a hole of its mesh's Cutout is skipped, as Embree's
//    filter functions skip it.
//  - Nothing is precomputed per triangle; the per-ray shear of the watertight
//    test is computed once per query. That is the point of a baseline: its cost
//    is exactly the textbook loop.

#include "strahl/reference/naive_accel.h"

#include <vector>

#include "strahl/core/error.h"
#include "strahl/core/transform.h"
#include "strahl/reference/watertight_triangle.h"

namespace strahl {

namespace {

// One instance as the naive loop needs it: the query goes into object space
// (a moving instance's at the ray's time).
struct NaiveInstance {
    const std::vector<ShapeRef>* shapes;  // the prototype's
    Mat4 worldToObject;
    uint32_t instID;
    const AccelInstance* placement;  // its keyframes, when it moves

    Ray toObject(const Ray& ray) const {
        if (!placement->moves()) return transformRay(worldToObject, ray);
        return transformRay(glm::inverse(placement->objectToWorldAt(ray.time)), ray);
    }
};

class NaiveAccel final : public Accel {
public:
    explicit NaiveAccel(const AccelScene& scene)
        : shapes_(scene.shapes), prototypes_(scene.prototypes), placements_(scene.instances) {
        for (const ShapeRef& shape : shapes_) bounds_.expand(shape.bounds());
        instances_.reserve(scene.instances.size());
        for (size_t k = 0; k < scene.instances.size(); ++k) {
            const AccelInstance& instance = placements_[k];
            if (instance.prototype >= prototypes_.size())
                fail("instance ", k, ": prototype ", instance.prototype, " does not exist (",
                     prototypes_.size(), " prototypes)");
            const std::vector<ShapeRef>& prototype = prototypes_[instance.prototype];
            instances_.push_back(NaiveInstance{&prototype, glm::inverse(instance.objectToWorld),
                                               scene.instanceId(k), &instance});
            for (const ShapeRef& shape : prototype) bounds_.expand(instance.boundsOf(shape.bounds()));
        }
    }

    Hit intersect(const Ray& ray) const override {
        Hit closest;
        float tfar = ray.tfar;  // the closest hit so far bounds every later test
        intersectShapes(shapes_, ray, kInvalidId, tfar, closest);
        for (const NaiveInstance& instance : instances_) {
            // Like Embree: the ray is mapped into object space, t keeps its
            // meaning, and Ng is reported in object space.
            intersectShapes(*instance.shapes, instance.toObject(ray), instance.instID, tfar, closest);
        }
        return closest;
    }

    bool occluded(const Ray& ray) const override {
        if (anyHit(shapes_, ray)) return true;
        for (const NaiveInstance& instance : instances_) {
            if (anyHit(*instance.shapes, instance.toObject(ray))) return true;
        }
        return false;
    }

    void intersect8(const int* valid, RayHitPacket8& packet, RayCoherence) const override {
        intersectLanes(valid, packet);
    }
    void intersect16(const int* valid, RayHitPacket16& packet, RayCoherence) const override {
        intersectLanes(valid, packet);
    }

    int nativePacketWidth() const override { return 1; }
    Bounds3 bounds() const override { return bounds_; }
    size_t memoryBytes() const override {
        size_t bytes = sizeof(*this) + shapes_.capacity() * sizeof(ShapeRef) +
                       instances_.capacity() * sizeof(NaiveInstance);
        for (const std::vector<ShapeRef>& prototype : prototypes_)
            bytes += sizeof(prototype) + prototype.capacity() * sizeof(ShapeRef);
        return bytes;
    }

private:
    // A vertex of triangle `tri` where it is at the ray's time (a deforming
    // mesh's, interpolated as Embree interpolates its time steps).
    static Vec3 vertex(const TriangleMesh& mesh, size_t tri, size_t corner, float time) {
        const uint32_t v = mesh.indices[3 * tri + corner];
        return mesh.deforms() ? mesh.positionAt(v, time) : mesh.positions[v];
    }

    // Whether a triangle hit is on the solid part of its mesh's cut-out.
    static bool solid(const Cutout* cutout, size_t tri, const Hit& hit) {
        return !cutout || cutout->solid(static_cast<uint32_t>(tri), hit.u, hit.v);
    }

    // The nearest hit of `ray` on `shapes` closer than tfar, if any, replaces
    // `closest` (IDs included) and shrinks tfar.
    static void intersectShapes(const std::vector<ShapeRef>& shapes, const Ray& ray,
                                uint32_t instID, float& tfar, Hit& closest) {
        const WatertightRay rayInRaySpace(ray);
        for (size_t geom = 0; geom < shapes.size(); ++geom) {
            const auto geomID = static_cast<uint32_t>(geom);
            if (const TriangleMesh* mesh = shapes[geom].mesh) {
                const size_t triangles = mesh->triangleCount();
                const Cutout* cutout = shapes[geom].cutout;
                for (size_t tri = 0; tri < triangles; ++tri) {
                    Hit candidate;
                    if (intersectTriangleWatertight(rayInRaySpace, ray.tnear, tfar,
                                                    vertex(*mesh, tri, 0, ray.time), vertex(*mesh, tri, 1, ray.time),
                                                    vertex(*mesh, tri, 2, ray.time), candidate) &&
                        solid(cutout, tri, candidate)) {
                        closest = candidate;
                        tfar = closest.t;
                        closest.geomID = geomID;
                        closest.primID = static_cast<uint32_t>(tri);
                        closest.instID = instID;
                    }
                }
            } else {
                const UserShape& user = *shapes[geom].user;
                Ray shrunk = ray;
                for (uint32_t prim = 0, n = user.primitiveCount(); prim < n; ++prim) {
                    shrunk.tfar = tfar;
                    Hit candidate;
                    if (user.intersect(shrunk, prim, candidate)) {
                        closest = candidate;
                        tfar = candidate.t;
                        closest.geomID = geomID;
                        closest.primID = prim;
                        closest.instID = instID;
                    }
                }
            }
        }
    }

    static bool anyHit(const std::vector<ShapeRef>& shapes, const Ray& ray) {
        const WatertightRay rayInRaySpace(ray);
        for (const ShapeRef& shape : shapes) {
            if (const TriangleMesh* mesh = shape.mesh) {
                const size_t triangles = mesh->triangleCount();
                for (size_t tri = 0; tri < triangles; ++tri) {
                    Hit candidate;
                    if (intersectTriangleWatertight(rayInRaySpace, ray.tnear, ray.tfar,
                                                    vertex(*mesh, tri, 0, ray.time), vertex(*mesh, tri, 1, ray.time),
                                                    vertex(*mesh, tri, 2, ray.time), candidate) &&
                        solid(shape.cutout, tri, candidate))
                        return true;
                }
            } else {
                for (uint32_t prim = 0, n = shape.user->primitiveCount(); prim < n; ++prim) {
                    if (shape.user->occluded(ray, prim)) return true;
                }
            }
        }
        return false;
    }

    // One single-ray query per active lane, written back in the packet layout
    // of accel.h: a hit sets tfar, u, v, Ng and the IDs; a miss sets geomID to
    // kInvalidId and leaves the ray (tfar included) as it was. Inactive lanes
    // are not touched.
    template <int N>
    void intersectLanes(const int* valid, RayHitPacket<N>& packet) const {
        for (int lane = 0; lane < N; ++lane) {
            if (valid[lane] == -1) packet.setHit(lane, intersect(packet.ray(lane)));
        }
    }

    std::vector<ShapeRef> shapes_;
    std::vector<std::vector<ShapeRef>> prototypes_;
    std::vector<AccelInstance> placements_;  // owned: NaiveInstance points into it
    std::vector<NaiveInstance> instances_;
    Bounds3 bounds_;
};

}  // namespace

std::unique_ptr<Accel> buildNaiveAccel(const AccelScene& scene) {
    return std::make_unique<NaiveAccel>(scene);
}

std::unique_ptr<Accel> buildNaiveAccel(std::span<const ShapeRef> shapes) {
    return buildNaiveAccel(AccelScene{{shapes.begin(), shapes.end()}, {}, {}});
}

std::unique_ptr<Accel> buildNaiveAccel(std::span<const TriangleMesh* const> meshes) {
    return buildNaiveAccel(meshShapeRefs(meshes));
}

}  // namespace strahl
