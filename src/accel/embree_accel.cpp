// EmbreeAccel: triangle meshes and user shapes in one Embree 3 scene.
//
// Invariants:
//  - geomID == index of the shape in its list (rtcAttachGeometryByID): the
//    top-level list or a prototype's, so shading finds a hit's shape without a
//    map. Instance k is attached to the top level as shapes.size() + k, which
//    Embree reports as instID.
//  - Each prototype is its own Embree scene with its own BVH, built once and
//    referenced by RTC_GEOMETRY_TYPE_INSTANCE geometries (one level: the build
//    has RTC_MAX_INSTANCE_LEVEL_COUNT == 1).
//  - Every UserShape goes through one generic user-geometry adapter (the
//    callbacks below), following Embree 3.13's user-geometry contract:
//    callbacks handle any packet width N, read valid[] only, accept a hit only
//    inside (tnear, tfar) — the shape's own intersect() guarantees that — write
//    tfar/u/v/Ng/primID/geomID and instID on a hit and nothing on a miss, and
//    set tfar = -inf for an occlusion. Shapes' intersect() is noexcept, so no
//    exception can cross Embree.
//  - A mesh with a Cutout gets it as its user data and one filter function
//    for both intersection and occlusion, which rejects candidate hits on its
//    holes (Embree then keeps traversing).
//  - A mesh whose triangles pair up (quad_faces.h) becomes Embree quad
//    geometry when the options' QuadPolicy says it pays: its QuadFaces (owned here) give
//    Embree the corners, and the queries (EmbreeSceneAccel) and the cut-out
//    filter turn every quad hit back into a triangle hit.
//  - A CurveSet is the one user shape Embree does not call back for: it
//    becomes Embree's own curve geometry of its type and basis, its control
//    points (x, y, z, r) and segment starts shared as they are (an oriented
//    ribbon's normals copied). Its
//    intersect() is the naive tracer's independent reference.
//  - A SubdivisionSurface likewise becomes Embree's subdivision geometry: its
//    cage (positions copied to float, faces, creases, corners, holes), its
//    boundary mode and a tessellation rate of 2^levels segments per edge, so
//    Embree's grid points are the reference's refined points. A displaced
//    surface gets a displacement function that adds the surface's own offset
//    at each grid point's (face, u, v) (SubdivisionSurface::displacementAt).
//  - A deforming mesh (TriangleMesh::laterPositions) has one vertex buffer per
//    keyframe (rtcSetGeometryTimeStepCount), never quads.
//  - Vertex and index buffers are shared with Embree (zero copy) when the
//    mesh's position vector has the spare element Embree's 16-byte vertex loads
//    need (TriangleMesh::reservePadding); otherwise they are copied once into an
//    Embree-owned buffer — correct, but it costs memory, so the scene builder
//    always pads.
//  - The device, the scene, the ray queries (packets by reinterpret_cast of
//    RayHitPacket<N>, its layout pinned to RTCRayHitN) and the error handling
//    are EmbreeSceneAccel's (embree_scene.h), shared with the sphere baseline.

#include <embree3/rtcore.h>

#include <cstddef>
#include <cstring>
#include <memory>
#include <vector>

#include "embree_scene.h"
#include "strahl/accel/accel.h"
#include "strahl/core/error.h"
#include "strahl/core/transform.h"
#include "strahl/geometry/curve_set.h"
#include "strahl/geometry/subdivision_surface.h"

namespace strahl {

namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(float), "vertex buffers are shared as RTC_FORMAT_FLOAT3");

// ---- the generic user-geometry adapter --------------------------------------

Ray rayFromN(RTCRayN* rays, unsigned N, unsigned i) {
    Ray ray;
    ray.origin = Vec3(RTCRayN_org_x(rays, N, i),
                      RTCRayN_org_y(rays, N, i),
                      RTCRayN_org_z(rays, N, i));
    ray.dir = Vec3(RTCRayN_dir_x(rays, N, i),
                   RTCRayN_dir_y(rays, N, i),
                   RTCRayN_dir_z(rays, N, i));
    ray.tnear = RTCRayN_tnear(rays, N, i);
    ray.tfar = RTCRayN_tfar(rays, N, i);
    ray.time = RTCRayN_time(rays, N, i);
    return ray;
}

void userBounds(const RTCBoundsFunctionArguments* args) {
    const auto* shape = static_cast<const UserShape*>(args->geometryUserPtr);
    const Bounds3 b = shape->primitiveBounds(args->primID);
    args->bounds_o->lower_x = b.min.x;
    args->bounds_o->lower_y = b.min.y;
    args->bounds_o->lower_z = b.min.z;
    args->bounds_o->upper_x = b.max.x;
    args->bounds_o->upper_y = b.max.y;
    args->bounds_o->upper_z = b.max.z;
}

void userIntersect(const RTCIntersectFunctionNArguments* args) {
    const auto* shape = static_cast<const UserShape*>(args->geometryUserPtr);
    const unsigned N = args->N;
    RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, N);
    RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, N);
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        Hit hit;
        if (!shape->intersect(rayFromN(rays, N, i), args->primID, hit)) continue;
        RTCRayN_tfar(rays, N, i) = hit.t;
        RTCHitN_Ng_x(hits, N, i) = hit.Ng.x;
        RTCHitN_Ng_y(hits, N, i) = hit.Ng.y;
        RTCHitN_Ng_z(hits, N, i) = hit.Ng.z;
        RTCHitN_u(hits, N, i) = hit.u;
        RTCHitN_v(hits, N, i) = hit.v;
        RTCHitN_primID(hits, N, i) = args->primID;
        RTCHitN_geomID(hits, N, i) = args->geomID;
        for (unsigned level = 0; level < RTC_MAX_INSTANCE_LEVEL_COUNT; ++level)
            RTCHitN_instID(hits, N, i, level) = args->context->instID[level];
    }
}

void userOccluded(const RTCOccludedFunctionNArguments* args) {
    const auto* shape = static_cast<const UserShape*>(args->geometryUserPtr);
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        if (shape->occluded(rayFromN(args->ray, N, i), args->primID))
            RTCRayN_tfar(args->ray, N, i) = -kInfinity;
    }
}

// ---- cut-outs -------------------------------------------------------------------

// A mesh's cut-out and, when it is traced as quads, its faces: the user data
// of its filter function.
struct MeshFilter {
    const Cutout* cutout = nullptr;
    const QuadFaces* quads = nullptr;
};

// Intersection and occlusion filter of a mesh with a Cutout: a candidate hit
// on a hole is rejected (valid = 0), and Embree goes on looking behind it.
void cutoutFilter(const RTCFilterFunctionNArguments* args) {
    const auto* filter = static_cast<const MeshFilter*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
        float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
        if (filter->quads) toTriangleHit(*filter->quads, prim, u, v);
        if (!filter->cutout->solid(prim, u, v)) args->valid[i] = 0;
    }
}

// Displacement of a SubdivisionSurface: Embree hands over the limit points of
// its tessellation grids with their face parameters (u, v); each moves by the
// surface's own offset there.
void subdivisionDisplacement(const RTCDisplacementFunctionNArguments* args) {
    const auto* surface = static_cast<const SubdivisionSurface*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        const DVec3 d = surface->displacementAt(args->primID, args->u[i], args->v[i]);
        args->P_x[i] += static_cast<float>(d.x);
        args->P_y[i] += static_cast<float>(d.y);
        args->P_z[i] += static_cast<float>(d.z);
    }
}

RTCSubdivisionMode embreeSubdivisionMode(SubdivisionBoundary boundary) {
    switch (boundary) {
        case SubdivisionBoundary::Smooth: return RTC_SUBDIVISION_MODE_SMOOTH_BOUNDARY;
        case SubdivisionBoundary::PinCorners: return RTC_SUBDIVISION_MODE_PIN_CORNERS;
        case SubdivisionBoundary::PinBoundary: return RTC_SUBDIVISION_MODE_PIN_BOUNDARY;
        case SubdivisionBoundary::PinAll: return RTC_SUBDIVISION_MODE_PIN_ALL;
    }
    return RTC_SUBDIVISION_MODE_SMOOTH_BOUNDARY;
}

// ---- the accelerator -----------------------------------------------------------

class EmbreeAccel final : public EmbreeSceneAccel {
public:
    EmbreeAccel(const AccelScene& scene, const AccelBuildOptions& options)
        : EmbreeSceneAccel(options), quads_(options.quads) {
        for (size_t i = 0; i < scene.shapes.size(); ++i) {
            const RTCGeometry geom = newShapeGeometry(scene.shapes[i], 0, static_cast<unsigned>(i));
            attach(geom, static_cast<unsigned>(i), scene.shapes[i].bounds(), "adding a shape");
        }

        std::vector<Bounds3> prototypeBounds;
        for (const std::vector<ShapeRef>& shapes : scene.prototypes) {
            RTCScene prototype = newPrototypeScene();
            Bounds3 bounds;
            for (size_t i = 0; i < shapes.size(); ++i) {
                const RTCGeometry geom = newShapeGeometry(shapes[i], prototypeCount(), static_cast<unsigned>(i));
                attachTo(prototype, geom, static_cast<unsigned>(i), "adding a prototype's shape");
                bounds.expand(shapes[i].bounds());
            }
            commitPrototype(prototype);
            prototypeBounds.push_back(bounds);
        }

        std::vector<uint32_t> prototypeOfInstance;
        prototypeOfInstance.reserve(scene.instances.size());
        for (const AccelInstance& instance : scene.instances) prototypeOfInstance.push_back(instance.prototype);
        setInstances(scene.shapes.size(), std::move(prototypeOfInstance));

        for (size_t k = 0; k < scene.instances.size(); ++k) {
            const AccelInstance& instance = scene.instances[k];
            if (instance.prototype >= prototypeCount())
                fail("instance ", k, ": prototype ", instance.prototype, " does not exist (",
                     prototypeCount(), " prototypes)");
            RTCGeometry geom = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(geom, prototypeScene(instance.prototype));
            // glm::mat4 is column-major with the affine last row 0 0 0 1. A
            // moving instance has one matrix per time step, equally spaced
            // over the ray time [0, 1], which Embree interpolates linearly
            // (core/motion.h does the same for everyone else).
            if (instance.moves()) {
                rtcSetGeometryTimeStepCount(geom, static_cast<unsigned>(instance.motion.size()));
                for (size_t step = 0; step < instance.motion.size(); ++step)
                    rtcSetGeometryTransform(geom, static_cast<unsigned>(step), RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                                            &instance.motion[step][0][0]);
            } else {
                rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &instance.objectToWorld[0][0]);
            }
            attach(geom, scene.instanceId(k), instance.boundsOf(prototypeBounds[instance.prototype]),
                   "adding an instance");
        }
        commit();
    }

private:
    // The Embree geometry of one shape, not yet committed or attached: shape
    // `geomID` of the top level (scene 0) or of prototype scene - 1.
    RTCGeometry newShapeGeometry(const ShapeRef& shape, size_t scene, unsigned geomID) {
        if (shape.mesh) return newMeshGeometry(*shape.mesh, shape.cutout, scene, geomID);
        if (const CurveSet* curves = shape.user->asCurves()) return newCurveGeometry(*curves);
        if (const SubdivisionSurface* surface = shape.user->asSubdivision()) return newSubdivisionGeometry(*surface);
        return newUserGeometry(*shape.user, geomID);
    }

    RTCGeometry newSubdivisionGeometry(const SubdivisionSurface& surface) {
        const SubdivisionCage& cage = surface.cage();
        RTCGeometry geom = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_SUBDIVISION);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                     3 * sizeof(float), cage.positions.size()));
        if (vertices)
            for (size_t i = 0; i < cage.positions.size(); ++i)
                for (int k = 0; k < 3; ++k) vertices[3 * i + k] = static_cast<float>(cage.positions[i][k]);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_FACE, 0, RTC_FORMAT_UINT, cage.faceSizes.data(), 0,
                                   sizeof(uint32_t), cage.faceSizes.size());
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, cage.indices.data(), 0,
                                   sizeof(uint32_t), cage.indices.size());
        if (!cage.creaseWeights.empty()) {
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_EDGE_CREASE_INDEX, 0, RTC_FORMAT_UINT2,
                                       cage.creaseEdges.data(), 0, 2 * sizeof(uint32_t), cage.creaseWeights.size());
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_EDGE_CREASE_WEIGHT, 0, RTC_FORMAT_FLOAT,
                                       cage.creaseWeights.data(), 0, sizeof(float), cage.creaseWeights.size());
        }
        if (!cage.cornerWeights.empty()) {
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX_CREASE_INDEX, 0, RTC_FORMAT_UINT,
                                       cage.cornerVertices.data(), 0, sizeof(uint32_t), cage.cornerVertices.size());
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX_CREASE_WEIGHT, 0, RTC_FORMAT_FLOAT,
                                       cage.cornerWeights.data(), 0, sizeof(float), cage.cornerWeights.size());
        }
        if (!cage.holes.empty())
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_HOLE, 0, RTC_FORMAT_UINT, cage.holes.data(), 0,
                                       sizeof(uint32_t), cage.holes.size());
        rtcSetGeometrySubdivisionMode(geom, 0, embreeSubdivisionMode(cage.boundary));
        rtcSetGeometryTessellationRate(geom, static_cast<float>(surface.tessellationRate()));
        if (surface.displaced()) {
            rtcSetGeometryUserData(geom, const_cast<SubdivisionSurface*>(&surface));
            rtcSetGeometryDisplacementFunction(geom, &subdivisionDisplacement);
        }
        return geom;
    }

    static RTCGeometryType curveGeometryType(CurveType type, CurveBasis basis) {
        if (type == CurveType::Oriented) {
            switch (basis) {
                case CurveBasis::Bezier: return RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BEZIER_CURVE;
                case CurveBasis::BSpline: return RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BSPLINE_CURVE;
                case CurveBasis::CatmullRom: return RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_CATMULL_ROM_CURVE;
                case CurveBasis::Linear: break;  // CurveSet refuses it
            }
            fail("oriented curves need a cubic basis");
        }
        const bool round = type == CurveType::Round;
        switch (basis) {
            case CurveBasis::Linear:
                return round ? RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE : RTC_GEOMETRY_TYPE_FLAT_LINEAR_CURVE;
            case CurveBasis::Bezier:
                return round ? RTC_GEOMETRY_TYPE_ROUND_BEZIER_CURVE : RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE;
            case CurveBasis::BSpline:
                return round ? RTC_GEOMETRY_TYPE_ROUND_BSPLINE_CURVE : RTC_GEOMETRY_TYPE_FLAT_BSPLINE_CURVE;
            case CurveBasis::CatmullRom:
                return round ? RTC_GEOMETRY_TYPE_ROUND_CATMULL_ROM_CURVE : RTC_GEOMETRY_TYPE_FLAT_CATMULL_ROM_CURVE;
        }
        fail("invalid curve basis ", static_cast<int>(basis));
    }

    RTCGeometry newCurveGeometry(const CurveSet& curves) {
        static_assert(sizeof(Vec4) == 4 * sizeof(float), "control points are shared as RTC_FORMAT_FLOAT4");
        const CurveSetDesc& desc = curves.desc();
        RTCGeometry geom = rtcNewGeometry(device(), curveGeometryType(desc.type, desc.basis));
        rtcSetGeometryBuildQuality(geom, quality());
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, desc.points.data(), 0,
                                   sizeof(Vec4), desc.points.size());
        // Segment starts; for the linear basis Embree derives which segments
        // join their left neighbour from them (CurveSet::hasLeftNeighbour).
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, desc.segments.data(), 0,
                                   sizeof(uint32_t), desc.segments.size());
        if (desc.type == CurveType::Flat) rtcSetGeometryTessellationRate(geom, float(desc.flatSegments));
        if (desc.type == CurveType::Oriented) {
            // Copied: Embree reads FLOAT3 buffers with 16-byte loads, which
            // the normals' vector has no spare element for.
            void* normals = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3, sizeof(Vec3),
                                                    desc.normals.size());
            if (normals) std::memcpy(normals, desc.normals.data(), desc.normals.size() * sizeof(Vec3));
        }
        return geom;
    }

    RTCGeometry newMeshGeometry(const TriangleMesh& mesh, const Cutout* cutout, size_t scene, unsigned geomID) {
        const QuadFaces* quads = nullptr;
        std::unique_ptr<QuadFaces> pairs;
        auto pairing = [&]() -> const QuadFaces& {
            if (!pairs) pairs = std::make_unique<QuadFaces>(pairTriangles(mesh));
            return *pairs;
        };
        // A deforming mesh stays triangles: its pairs need not stay planar.
        if (!mesh.deforms() && tracesAsQuads(quads_, mesh.triangleCount(), pairing))
            quads = quadFaces_.emplace_back(std::move(pairs)).get();
        RTCGeometry geom = rtcNewGeometry(device(), quads ? RTC_GEOMETRY_TYPE_QUAD : RTC_GEOMETRY_TYPE_TRIANGLE);
        // The scene's quality picks its builder, the geometry's how the mesh's
        // own triangles are split: spatial splits (high) need both.
        rtcSetGeometryBuildQuality(geom, quality());
        const size_t nv = mesh.vertexCount(), nt = mesh.triangleCount();
        // A deforming mesh has one vertex buffer per time step, equally
        // spaced over the ray time [0, 1] (core/motion.h interpolates the same).
        if (mesh.deforms()) rtcSetGeometryTimeStepCount(geom, static_cast<unsigned>(mesh.keyframeCount()));
        for (size_t step = 0; step < mesh.keyframeCount(); ++step) {
            const std::vector<Vec3>& positions = mesh.keyframePositions(step);
            const auto slot = static_cast<unsigned>(step);
            if (mesh.isPadded()) {
                rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, slot, RTC_FORMAT_FLOAT3, positions.data(), 0,
                                           sizeof(Vec3), nv);
            } else {
                void* dst = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, slot, RTC_FORMAT_FLOAT3,
                                                    sizeof(Vec3), nv);
                if (dst) std::memcpy(dst, positions.data(), nv * sizeof(Vec3));
            }
        }
        if (quads) {
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, quads->corners.data(), 0,
                                       4 * sizeof(uint32_t), quads->faceCount);
            traceAsQuads(scene, geomID, quads);
        } else {
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                       mesh.indices.data(), 0, 3 * sizeof(uint32_t), nt);
        }
        if (cutout) {
            MeshFilter* filter = filters_.emplace_back(std::make_unique<MeshFilter>(MeshFilter{cutout, quads})).get();
            rtcSetGeometryUserData(geom, filter);
            rtcSetGeometryIntersectFilterFunction(geom, &cutoutFilter);
            rtcSetGeometryOccludedFilterFunction(geom, &cutoutFilter);
        }
        return geom;
    }

    RTCGeometry newUserGeometry(const UserShape& shape, unsigned geomID) {
        // Embree silently drops or mistraverses primitives with NaN or empty
        // boxes: check them all first.
        const uint32_t count = shape.primitiveCount();
        for (uint32_t prim = 0; prim < count; ++prim) {
            const Bounds3 b = shape.primitiveBounds(prim);
            if (b.empty() || !isFinite(b.min) || !isFinite(b.max))
                fail("shape ", geomID, ": primitive ", prim, " has no finite bounds");
        }
        RTCGeometry geom = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, count);
        rtcSetGeometryUserData(geom, const_cast<UserShape*>(&shape));
        rtcSetGeometryBoundsFunction(geom, &userBounds, nullptr);
        rtcSetGeometryIntersectFunction(geom, &userIntersect);
        rtcSetGeometryOccludedFunction(geom, &userOccluded);
        return geom;
    }

    QuadPolicy quads_;  // AccelBuildOptions::quads
    std::vector<std::unique_ptr<QuadFaces>> quadFaces_;  // of the meshes traced as quads
    std::vector<std::unique_ptr<MeshFilter>> filters_;   // of the meshes with cut-outs
};

}  // namespace

std::unique_ptr<Accel> buildEmbreeAccel(const AccelScene& scene, const AccelBuildOptions& options) {
    return std::make_unique<EmbreeAccel>(scene, options);
}

std::unique_ptr<Accel> buildEmbreeAccel(std::span<const ShapeRef> shapes,
                                        const AccelBuildOptions& options) {
    return buildEmbreeAccel(AccelScene{{shapes.begin(), shapes.end()}, {}, {}}, options);
}

std::unique_ptr<Accel> buildEmbreeAccel(std::span<const TriangleMesh* const> meshes,
                                        const AccelBuildOptions& options) {
    return buildEmbreeAccel(meshShapeRefs(meshes), options);
}

const char* embreeVersion() { return RTC_VERSION_STRING; }

const char* bvhQualityName(BvhQuality quality) {
    switch (quality) {
        case BvhQuality::Low: return "low";
        case BvhQuality::Medium: return "medium";
        case BvhQuality::High: return "high";
    }
    fail("invalid BvhQuality value ", static_cast<int>(quality));
}

BvhQuality bvhQualityFromName(const std::string& name) {
    for (BvhQuality q : {BvhQuality::Low, BvhQuality::Medium, BvhQuality::High})
        if (name == bvhQualityName(q)) return q;
    fail("unknown BVH quality '", name, "' (choose low, medium or high)");
}

}  // namespace strahl
