// NaiveAccel: every ray against every primitive (see naive_accel.h).
//
// Invariants:
//  - geomID == index into shapes_, primID == triangle / primitive index — the
//    same numbering Embree reports, so the two compare hit for hit.
//  - The nearest-hit search only ever shrinks tfar, and accepts a candidate
//    only if it is strictly nearer (the triangle test and UserShape::intersect
//    both require t < tfar), so of several hits at the same t the first in
//    (geomID, primID) order wins: answers do not depend on anything but the
//    input.
//  - Nothing is precomputed per triangle; the per-ray shear of the watertight
//    test is computed once per query. That is the point of a baseline: its cost
//    is exactly the textbook loop.

#include "strahl/reference/naive_accel.h"

#include <vector>

#include "strahl/reference/watertight_triangle.h"

namespace strahl {

namespace {

class NaiveAccel final : public Accel {
public:
    explicit NaiveAccel(std::span<const ShapeRef> shapes) : shapes_(shapes.begin(), shapes.end()) {
        for (const ShapeRef& shape : shapes_) bounds_.expand(shape.bounds());
    }

    Hit intersect(const Ray& ray) const override {
        const WatertightRay rayInRaySpace(ray);
        Hit closest;
        float tfar = ray.tfar;  // the closest hit so far bounds every later test
        for (size_t geom = 0; geom < shapes_.size(); ++geom) {
            const auto geomID = static_cast<uint32_t>(geom);
            if (const TriangleMesh* mesh = shapes_[geom].mesh) {
                const size_t triangles = mesh->triangleCount();
                for (size_t tri = 0; tri < triangles; ++tri) {
                    if (intersectTriangleWatertight(rayInRaySpace, ray.tnear, tfar,
                                                    vertex(*mesh, tri, 0), vertex(*mesh, tri, 1),
                                                    vertex(*mesh, tri, 2), closest)) {
                        tfar = closest.t;
                        closest.geomID = geomID;
                        closest.primID = static_cast<uint32_t>(tri);
                    }
                }
            } else {
                const UserShape& user = *shapes_[geom].user;
                Ray shrunk = ray;
                for (uint32_t prim = 0, n = user.primitiveCount(); prim < n; ++prim) {
                    shrunk.tfar = tfar;
                    Hit candidate;
                    if (user.intersect(shrunk, prim, candidate)) {
                        closest = candidate;
                        tfar = candidate.t;
                        closest.geomID = geomID;
                        closest.primID = prim;
                    }
                }
            }
        }
        return closest;
    }

    bool occluded(const Ray& ray) const override {
        const WatertightRay rayInRaySpace(ray);
        for (const ShapeRef& shape : shapes_) {
            if (const TriangleMesh* mesh = shape.mesh) {
                const size_t triangles = mesh->triangleCount();
                for (size_t tri = 0; tri < triangles; ++tri) {
                    Hit unused;
                    if (intersectTriangleWatertight(rayInRaySpace, ray.tnear, ray.tfar,
                                                    vertex(*mesh, tri, 0), vertex(*mesh, tri, 1),
                                                    vertex(*mesh, tri, 2), unused))
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

    void intersect8(const int* valid, RayHitPacket8& packet, RayCoherence) const override {
        intersectLanes(valid, packet);
    }
    void intersect16(const int* valid, RayHitPacket16& packet, RayCoherence) const override {
        intersectLanes(valid, packet);
    }

    int nativePacketWidth() const override { return 1; }
    Bounds3 bounds() const override { return bounds_; }
    size_t memoryBytes() const override {
        return sizeof(*this) + shapes_.capacity() * sizeof(ShapeRef);
    }

private:
    static const Vec3& vertex(const TriangleMesh& mesh, size_t tri, size_t corner) {
        return mesh.positions[mesh.indices[3 * tri + corner]];
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
    Bounds3 bounds_;
};

}  // namespace

std::unique_ptr<Accel> buildNaiveAccel(std::span<const ShapeRef> shapes) {
    return std::make_unique<NaiveAccel>(shapes);
}

std::unique_ptr<Accel> buildNaiveAccel(std::span<const TriangleMesh* const> meshes) {
    return std::make_unique<NaiveAccel>(meshShapeRefs(meshes));
}

}  // namespace strahl
