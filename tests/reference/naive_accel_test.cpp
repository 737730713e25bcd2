// The naive tracer and its watertight triangle test: hand-computed hits, no
// cracks at shared edges and vertices of closed meshes, agreement with Embree
// on random rays (meshes and user shapes), occlusion vs. intersection, packet
// vs. single-ray queries, and deterministic ties.

#include "strahl/reference/naive_accel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "strahl/core/rng.h"
#include "strahl/reference/watertight_triangle.h"
#include "sanitizers/sanitized.h"
#include "test_scene_pieces.h"

namespace strahl {
namespace {

// ---------------------------------------------------------------------------
// Scene pieces built in the test.


// A box with half-extents `halfSize` along a tilted orthonormal frame, 12
// triangles wound outwards.
TriangleMesh orientedBox(const Vec3& centre, const Vec3& halfSize) {
    Vec3 axisX, axisY;
    const Vec3 axisZ = glm::normalize(Vec3(1.0f, 2.0f, 3.0f));
    orthonormalBasis(axisZ, axisX, axisY);
    TriangleMesh m;
    for (int corner = 0; corner < 8; ++corner) {
        m.positions.push_back(centre + (corner & 1 ? halfSize.x : -halfSize.x) * axisX +
                              (corner & 2 ? halfSize.y : -halfSize.y) * axisY +
                              (corner & 4 ? halfSize.z : -halfSize.z) * axisZ);
    }
    // Corner index bits: x = 1, y = 2, z = 4. Each face as a quad, outward CCW.
    const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces)
        m.indices.insert(m.indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
    m.reservePadding();
    return m;
}

// Small random triangles scattered in a cube of side 4 around `offset`.
TriangleMesh randomSoup(int triangles, const Vec3& offset, uint64_t seed) {
    Pcg32 rng(seed, 1);
    TriangleMesh m;
    for (int t = 0; t < triangles; ++t) {
        const Vec3 c(rng.nextFloat() * 4 - 2, rng.nextFloat() * 4 - 2, rng.nextFloat() * 4 - 2);
        for (int k = 0; k < 3; ++k) {
            m.positions.push_back(offset + c +
                                  0.4f * Vec3(rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f,
                                              rng.nextFloat() - 0.5f));
            m.indices.push_back(static_cast<uint32_t>(m.positions.size() - 1));
        }
    }
    m.reservePadding();
    return m;
}

// A height field z = f(x, y) over [-3, 3]^2 on a cells x cells grid.
TriangleMesh wavyGrid(int cells, float zOffset) {
    TriangleMesh m;
    for (int j = 0; j <= cells; ++j) {
        for (int i = 0; i <= cells; ++i) {
            const float x = -3.0f + 6.0f * static_cast<float>(i) / static_cast<float>(cells);
            const float y = -3.0f + 6.0f * static_cast<float>(j) / static_cast<float>(cells);
            m.positions.emplace_back(x, y,
                                     zOffset + 0.4f * std::sin(2.1f * x) * std::cos(1.7f * y));
        }
    }
    const auto row = static_cast<uint32_t>(cells + 1);
    for (uint32_t j = 0; j < static_cast<uint32_t>(cells); ++j) {
        for (uint32_t i = 0; i < static_cast<uint32_t>(cells); ++i) {
            const uint32_t v00 = j * row + i, v10 = v00 + 1, v01 = v00 + row, v11 = v01 + 1;
            m.indices.insert(m.indices.end(), {v00, v10, v11, v00, v11, v01});
        }
    }
    m.reservePadding();
    return m;
}

// A user shape of analytic spheres, one primitive each, that counts its calls
// and remembers the last tfar it was asked with.
class SphereSet final : public UserShape {
public:
    struct Sphere {
        Vec3 centre;
        float radius;
    };
    explicit SphereSet(std::vector<Sphere> spheres) : spheres_(std::move(spheres)) {}

    uint32_t primitiveCount() const override { return static_cast<uint32_t>(spheres_.size()); }
    Bounds3 primitiveBounds(uint32_t prim) const override {
        const Sphere& s = spheres_[prim];
        return Bounds3{s.centre - Vec3(s.radius), s.centre + Vec3(s.radius)};
    }

    // Both roots of |o + t d - c|^2 = r^2 in increasing order, with the
    // cancellation-free form of the quadratic formula.
    bool intersect(const Ray& ray, uint32_t prim, Hit& hit) const noexcept override {
        ++intersectCalls;
        lastTfar = ray.tfar;
        const Sphere& s = spheres_[prim];
        const Vec3 oc = ray.origin - s.centre;
        const float a = glm::dot(ray.dir, ray.dir);
        const float halfB = glm::dot(oc, ray.dir);
        const float c = glm::dot(oc, oc) - s.radius * s.radius;
        const float discriminant = halfB * halfB - a * c;
        if (discriminant < 0.0f) return false;
        const float q = -(halfB + std::copysign(std::sqrt(discriminant), halfB));
        const float r0 = q / a, r1 = c / q;
        for (const float t : {std::min(r0, r1), std::max(r0, r1)}) {
            if (t > ray.tnear && t < ray.tfar) {
                const Vec3 n = ray.at(t) - s.centre;
                hit.t = t;
                hit.u = 0.5f + 0.5f * n.x / s.radius;  // any shape-defined parameters
                hit.v = 0.5f + 0.5f * n.y / s.radius;
                hit.Ng = n;
                return true;
            }
        }
        return false;
    }
    bool occluded(const Ray& ray, uint32_t prim) const noexcept override {
        ++occludedCalls;
        Hit hit;
        return intersect(ray, prim, hit);
    }

    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const override {
        SurfaceInteraction si;
        si.p = ray.at(hit.t);
        si.pError = gammaBound(5) * glm::abs(si.p);
        si.Ng = glm::normalize(hit.Ng);
        si.Ns = si.Ng;
        si.uv = Vec2(hit.u, hit.v);
        return si;
    }
    size_t memoryBytes() const override { return spheres_.capacity() * sizeof(Sphere); }

    mutable std::atomic<int> intersectCalls{0};
    mutable std::atomic<int> occludedCalls{0};
    mutable std::atomic<float> lastTfar{0.0f};

private:
    std::vector<Sphere> spheres_;
};

SphereSet randomSpheres(int count, uint64_t seed) {
    Pcg32 rng(seed, 7);
    std::vector<SphereSet::Sphere> spheres;
    for (int i = 0; i < count; ++i) {
        spheres.push_back(
            {Vec3(rng.nextFloat() * 6 - 3, rng.nextFloat() * 6 - 3, rng.nextFloat() * 6 - 3),
             0.1f + 0.4f * rng.nextFloat()});
    }
    return SphereSet(std::move(spheres));
}

Vec3 randomDirection(Pcg32& rng) {
    const float z = 1.0f - 2.0f * rng.nextFloat();
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPi * rng.nextFloat();
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// Rays aimed at random points of `bounds` from a sphere around it, plus rays
// starting inside it in random directions, some with a finite tfar.
std::vector<Ray> randomRays(const Bounds3& bounds, int count, uint64_t seed) {
    Pcg32 rng(seed, 3);
    const Vec3 centre = bounds.center(), extent = bounds.diagonal();
    const float outerRadius = glm::length(extent);
    auto pointInBounds = [&] {
        return bounds.min + extent * Vec3(rng.nextFloat(), rng.nextFloat(), rng.nextFloat());
    };
    std::vector<Ray> rays(static_cast<size_t>(count));
    for (size_t i = 0; i < rays.size(); ++i) {
        Ray& ray = rays[i];
        if (i % 4 == 3) {
            ray.origin = pointInBounds();
            ray.dir = randomDirection(rng);
        } else {
            ray.origin = centre + outerRadius * randomDirection(rng);
            ray.dir = pointInBounds() - ray.origin;  // deliberately not normalised
        }
        if (i % 5 == 4) ray.tfar = outerRadius * rng.nextFloat();
    }
    return rays;
}

std::vector<ShapeRef> meshRefs(std::initializer_list<const TriangleMesh*> meshes) {
    std::vector<ShapeRef> refs;
    for (const TriangleMesh* m : meshes) refs.push_back(ShapeRef{m, nullptr});
    return refs;
}

Ray rayFrom(const Vec3& origin, const Vec3& dir) {
    Ray ray;
    ray.origin = origin;
    ray.dir = dir;
    return ray;
}

// ---------------------------------------------------------------------------
// The watertight triangle test on hand-computed cases.

TEST(WatertightTriangle, HitsWithEmbreeBarycentricsAndNormal) {
    const Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(0, 1, 0);
    Hit hit;
    ASSERT_TRUE(
        intersectTriangleWatertight(rayFrom({0.25f, 0.5f, 1.0f}, {0, 0, -1}), p0, p1, p2, hit));
    EXPECT_FLOAT_EQ(hit.t, 1.0f);
    EXPECT_FLOAT_EQ(hit.u, 0.25f);     // weight of p1 = x
    EXPECT_FLOAT_EQ(hit.v, 0.5f);      // weight of p2 = y
    EXPECT_EQ(hit.Ng, Vec3(0, 0, 1));  // (p1 - p0) x (p2 - p0)
    EXPECT_EQ(hit.geomID, kInvalidId) << "IDs are the caller's job";

    // The back face is hit too, with the same (winding-order) normal.
    Hit back;
    ASSERT_TRUE(
        intersectTriangleWatertight(rayFrom({0.25f, 0.5f, -2.0f}, {0, 0, 1}), p0, p1, p2, back));
    EXPECT_FLOAT_EQ(back.t, 2.0f);
    EXPECT_FLOAT_EQ(back.u, 0.25f);
    EXPECT_FLOAT_EQ(back.v, 0.5f);
    EXPECT_EQ(back.Ng, Vec3(0, 0, 1));
}

TEST(WatertightTriangle, ObliqueRayOnTiltedTriangle) {
    // Plane x + y/2 + z/3 = 1 through (1,0,0), (0,2,0), (0,0,3). The ray from the
    // origin along (1,1,1) meets it at t = 6/11, at the point (6,6,6)/11 =
    // 6/11 p0 + 3/11 p1 + 2/11 p2; Ng = (-1,2,0) x (-1,0,3) = (6,3,2).
    const Vec3 p0(1, 0, 0), p1(0, 2, 0), p2(0, 0, 3);
    Hit hit;
    ASSERT_TRUE(intersectTriangleWatertight(rayFrom({0, 0, 0}, {1, 1, 1}), p0, p1, p2, hit));
    EXPECT_NEAR(hit.t, 6.0f / 11.0f, 1e-6f);
    EXPECT_NEAR(hit.u, 3.0f / 11.0f, 1e-6f);
    EXPECT_NEAR(hit.v, 2.0f / 11.0f, 1e-6f);
    EXPECT_EQ(hit.Ng, Vec3(6, 3, 2));
    // A longer direction vector scales t, not the hit.
    Hit scaled;
    ASSERT_TRUE(intersectTriangleWatertight(rayFrom({0, 0, 0}, {2, 2, 2}), p0, p1, p2, scaled));
    EXPECT_NEAR(scaled.t, 3.0f / 11.0f, 1e-6f);
    EXPECT_NEAR(scaled.u, hit.u, 1e-6f);
}

TEST(WatertightTriangle, EdgesAndVerticesAreInside) {
    const Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(0, 1, 0), p3(1, 1, 0);
    // (0.5, 0.5) lies exactly on the shared edge p1-p2: the float edge function
    // is exactly 0 and the double fallback decides; both triangles report it.
    const Ray onEdge = rayFrom({0.5f, 0.5f, 1.0f}, {0, 0, -1});
    Hit first, second;
    ASSERT_TRUE(intersectTriangleWatertight(onEdge, p0, p1, p2, first));
    ASSERT_TRUE(intersectTriangleWatertight(onEdge, p1, p3, p2, second));
    EXPECT_FLOAT_EQ(first.u, 0.5f);
    EXPECT_FLOAT_EQ(first.v, 0.5f);
    EXPECT_FLOAT_EQ(first.t, second.t);

    Hit atVertex;
    ASSERT_TRUE(intersectTriangleWatertight(rayFrom({1, 0, 1}, {0, 0, -1}), p0, p1, p2, atVertex));
    EXPECT_FLOAT_EQ(atVertex.u, 1.0f);
    EXPECT_FLOAT_EQ(atVertex.v, 0.0f);
}

TEST(WatertightTriangle, CancellationToZeroIsDecidedInDouble) {
    // Edge B-C passes 5e-15 beside the ray (the z axis). Its float edge
    // function cancels to exactly 0 (both products round to 1 + 2^-22) while
    // the exact value is 2^-46: the double fallback must put the ray on the
    // correct side, so of the two triangles sharing the edge exactly one, the
    // one containing the ray, is hit.
    const Vec3 b(-1.0f, 1.0f + 0x1p-23f, 0.0f), c(1.0f + 0x1p-23f, -(1.0f + 0x1p-22f), 0.0f);
    const Vec3 containing(-5.0f, -5.0f, 0.0f), beside(5.0f, 5.0f, 0.0f);
    const Ray ray = rayFrom({0, 0, -1}, {0, 0, 1});
    Hit hit;
    EXPECT_TRUE(intersectTriangleWatertight(ray, containing, b, c, hit));
    EXPECT_FALSE(intersectTriangleWatertight(ray, beside, c, b, hit));
}

TEST(WatertightTriangle, MissesLeaveTheHitUntouched) {
    const Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(0, 1, 0);
    Hit hit;
    hit.t = 42.0f;
    hit.u = 0.125f;
    auto expectMiss = [&](const Ray& ray, const char* why) {
        EXPECT_FALSE(intersectTriangleWatertight(ray, p0, p1, p2, hit)) << why;
        EXPECT_EQ(hit.t, 42.0f) << why;
        EXPECT_EQ(hit.u, 0.125f) << why;
    };
    expectMiss(rayFrom({0.6f, 0.6f, 1}, {0, 0, -1}), "outside the hypotenuse");
    expectMiss(rayFrom({-0.1f, 0.5f, 1}, {0, 0, -1}), "outside edge p0-p2");
    expectMiss(rayFrom({0.25f, 0.25f, 1}, {0, 0, 1}), "pointing away");
    expectMiss(rayFrom({0.25f, 0.25f, 1}, {1, 0, 0}), "parallel to the plane");
    expectMiss(rayFrom({0.25f, 0.25f, 0}, {1, 1, 0}), "in the plane");
    expectMiss(rayFrom({0.25f, 0.25f, 1}, {0, 0, 0}), "zero direction");

    Ray limited = rayFrom({0.25f, 0.25f, 1}, {0, 0, -1});
    limited.tfar = 1.0f;  // the hit at t = 1 is excluded: t < tfar is strict
    expectMiss(limited, "t == tfar");
    limited.tfar = kInfinity;
    limited.tnear = 1.0f;  // and tnear < t is strict as well
    expectMiss(limited, "t == tnear");

    const Vec3 q(0.5f, 0.5f, 0.0f);
    EXPECT_FALSE(intersectTriangleWatertight(rayFrom({0.5f, 0.5f, 1}, {0, 0, -1}), q, q, p1, hit))
        << "degenerate triangle";
}

// ---------------------------------------------------------------------------
// Watertightness: no ray slips through a shared edge or vertex of a closed mesh.

// Counts the rays through (points near) every edge and vertex of `mesh` that
// miss it: from `inside` outwards, and from outside towards `inside` with a
// random lateral offset. The targets on each edge are 7 evenly spaced points
// and `randomPerEdge` random ones, rounded to float, so they lie within
// rounding error of the edge — the hardest case. Every ray must hit a closed,
// convex mesh.
int raysThroughEdgesThatMiss(const TriangleMesh& mesh, const Vec3& inside, int randomPerEdge,
                             int* raysShot) {
    const TriangleMesh* meshes[] = {&mesh};
    const auto accel = buildNaiveAccel(meshes);
    std::map<std::pair<uint32_t, uint32_t>, int> edgeUses;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        for (size_t k = 0; k < 3; ++k) {
            ++edgeUses[std::minmax(mesh.indices[3 * t + k], mesh.indices[3 * t + (k + 1) % 3])];
        }
    }
    Pcg32 rng(17, 5);
    const float size = glm::length(mesh.bounds().diagonal());
    int misses = 0;
    auto shoot = [&](const Vec3& target) {
        const Ray fromInside = rayFrom(inside, target - inside);
        const Vec3 outside =
            target + 2.0f * (target - inside) +
            0.2f * size * (Vec3(rng.nextFloat(), rng.nextFloat(), rng.nextFloat()) - Vec3(0.5f));
        const Ray fromOutside = rayFrom(outside, target - outside);
        misses += !accel->intersect(fromInside).valid();
        misses += !accel->intersect(fromOutside).valid();
        misses += !accel->occluded(fromInside);
        misses += !accel->occluded(fromOutside);
        *raysShot += 4;
    };
    for (const auto& [edge, uses] : edgeUses) {
        EXPECT_EQ(uses, 2) << "the test mesh must be closed";
        const Vec3& a = mesh.positions[edge.first];
        const Vec3& b = mesh.positions[edge.second];
        for (int step = 1; step < 8; ++step) shoot(a + (static_cast<float>(step) / 8.0f) * (b - a));
        for (int i = 0; i < randomPerEdge; ++i) shoot(a + rng.nextFloat() * (b - a));
    }
    for (const Vec3& vertex : mesh.positions) shoot(vertex);
    return misses;
}

TEST(NaiveAccel, NoRaySlipsThroughTheEdgesOfAnIcosphere) {
    const Vec3 centre(0.37f, -1.21f, 2.9f);
    const TriangleMesh sphere = test::icosphere(3, centre, 1.7f);
    int rays = 0;
    EXPECT_EQ(raysThroughEdgesThatMiss(sphere, centre, 1, &rays), 0) << "of " << rays << " rays";
    EXPECT_GT(rays, 20000);
}

TEST(NaiveAccel, NoRaySlipsThroughTheEdgesOfAFarAwayTiltedBox) {
    // Far from the origin the coordinates carry few fraction bits, so rounding
    // in the ray-space transform is as large as it gets.
    const Vec3 centre(1000.3f, -200.7f, 55.1f);
    const TriangleMesh cube = orientedBox(centre, Vec3(0.5f, 0.25f, 0.75f));
    int rays = 0;
    EXPECT_EQ(raysThroughEdgesThatMiss(cube, centre, 400, &rays), 0) << "of " << rays << " rays";
}

// ---------------------------------------------------------------------------
// Agreement with Embree.

struct Agreement {
    int rays = 0, hits = 0, mismatches = 0, unexplained = 0;
    double maxTError = 0, minNormalCosine = 1, maxUvError = 0;
};

// How close a triangle hit is to the triangle's boundary, in barycentric units.
float distanceToTriangleEdge(const Hit& hit) {
    return std::min({hit.u, hit.v, 1.0f - hit.u - hit.v});
}

// How far two correct float triangle tests may disagree on u and v. The
// rounding of the ray-space transform moves the hit by ~2^-24 of the largest
// coordinate involved (origin or hit point); in barycentric units that is
// divided by the triangle's size and, for grazing rays, by |cos| of the
// incidence angle. Measured disagreements stay below 3 such units; allow 16.
double barycentricTolerance(const Ray& ray, const Hit& hit) {
    const Vec3 p = ray.at(hit.t);
    const float magnitude = std::max(glm::length(ray.origin), glm::length(p));
    const float size = std::sqrt(glm::length(hit.Ng));  // |Ng| is twice the area
    const float cosine = std::abs(glm::dot(glm::normalize(hit.Ng), glm::normalize(ray.dir)));
    return 16.0 * 0x1p-24 * magnitude / (double(size) * cosine);
}

// Traces `rays` through both accelerators over `shapes` and collects how far
// they disagree. A hit on different primitives (or on one side only) is a
// mismatch, and it must be explained by rounding: either the two hits are a
// tie in t, or the hit the other side passed over lies within float error of
// its triangle's edge (Embree's triangle test is not watertight, and neither
// test is exact for points that close to an edge).
//
// t is compared relative to the hit distance, but never finer than relative to
// the scene size: float positions resolve the scene to ~1e-7 of its size, so a
// hit 1e-4 units from the origin cannot have a better relative t than that.
Agreement compareWithEmbree(std::span<const ShapeRef> shapes, const Accel& naive,
                            const Accel& embree, const std::vector<Ray>& rays) {
    const float sceneSize = glm::length(naive.bounds().diagonal());
    Agreement a;
    for (const Ray& ray : rays) {
        const Hit ours = naive.intersect(ray);
        const Hit theirs = embree.intersect(ray);
        ++a.rays;
        if (!ours.valid() && !theirs.valid()) continue;
        ++a.hits;
        const float tScale = std::max(std::min(ours.t, theirs.t), sceneSize / glm::length(ray.dir));
        if (ours.valid() != theirs.valid() || ours.geomID != theirs.geomID ||
            ours.primID != theirs.primID) {
            ++a.mismatches;
            const bool tie =
                ours.valid() && theirs.valid() && std::abs(ours.t - theirs.t) <= 1e-5f * tScale;
            // The nearer hit is the one the other tracer passed over.
            const Hit& skipped =
                !ours.valid() || (theirs.valid() && theirs.t < ours.t) ? theirs : ours;
            const bool onEdge =
                shapes[skipped.geomID].mesh && distanceToTriangleEdge(skipped) < 1e-4f;
            if (!tie && !onEdge) {
                ++a.unexplained;
                ADD_FAILURE() << "unexplained mismatch: ours geomID " << ours.geomID << " primID "
                              << ours.primID << " t " << ours.t << ", Embree's geomID "
                              << theirs.geomID << " primID " << theirs.primID << " t " << theirs.t;
            }
            continue;
        }
        a.maxTError = std::max(a.maxTError, double(std::abs(ours.t - theirs.t) / tScale));
        const float cosine = glm::dot(glm::normalize(ours.Ng), glm::normalize(theirs.Ng));
        a.minNormalCosine = std::min(a.minNormalCosine, double(cosine));
        if (shapes[ours.geomID].mesh) {  // a user shape's u, v are its own business
            const double uvError =
                std::max(std::abs(ours.u - theirs.u), std::abs(ours.v - theirs.v));
            a.maxUvError = std::max(a.maxUvError, uvError / barycentricTolerance(ray, ours));
        }
    }
    return a;
}

// t agrees to 1e-5 of the hit distance on Embree's triangles; its quad test
// (Möller–Trumbore from the four corners, where the triangle leaves hold
// precomputed edges) rounds t more coarsely — measured 1.1e-5 against 4.3e-6 —
// while u, v, from which shading rebuilds the hit point, agree as closely.
void expectAgreement(const Agreement& a, int minHits, double tTolerance = 1e-5) {
    SCOPED_TRACE(testing::Message()
                 << a.hits << " hits of " << a.rays << " rays, " << a.mismatches
                 << " mismatched; max relative dt " << a.maxTError << ", min cos(Ng) "
                 << a.minNormalCosine << ", max u, v error / tolerance " << a.maxUvError);
    EXPECT_GE(a.hits, minHits) << "the test exercised real hits";
    EXPECT_LE(double(a.mismatches), 1e-4 * a.hits);  // same IDs for >= 99.99% of hits
    EXPECT_EQ(a.unexplained, 0);
    EXPECT_LE(a.maxTError, tTolerance);
    EXPECT_GE(a.minNormalCosine, 1.0 - 1e-5);  // parallel, same sign
    EXPECT_LE(a.maxUvError, 1.0);
}

TEST(NaiveAccel, AgreesWithEmbreeOnRandomRaysAgainstMeshes) {
    const TriangleMesh soup = randomSoup(600, Vec3(0.5f, 0.0f, 0.0f), 11);
    const TriangleMesh sphere = test::icosphere(2, Vec3(-1.0f, 1.5f, 0.5f), 1.2f);
    const TriangleMesh grid = wavyGrid(20, -1.5f);
    const TriangleMesh* meshes[] = {&soup, &sphere, &grid};
    const std::vector<ShapeRef> shapes = meshRefs({&soup, &sphere, &grid});
    const auto naive = buildNaiveAccel(meshes);
    // A third of the rays under the sanitizers (tests/sanitizers/sanitized.h):
    // the naive tracer tests all 1,400 triangles per ray.
    const int rayCount = test::fullOrSanitized(40000, 13000);
    const auto rays = randomRays(naive->bounds(), rayCount, 23);
    // The grid's and the icosphere's triangles pair up: traced as Embree
    // quads when asked to (by default only meshes of 2^19 triangles are).
    for (bool quads : {true, false}) {
        SCOPED_TRACE(quads ? "quads" : "triangles only");
        AccelBuildOptions options;
        options.quads = quads ? QuadPolicy::Always : QuadPolicy::Never;
        const auto embree = buildEmbreeAccel(meshes, options);
        expectAgreement(compareWithEmbree(shapes, *naive, *embree, rays), rayCount / 2,
                        quads ? 2e-5 : 1e-5);
    }
}

TEST(NaiveAccel, AgreesWithEmbreeOnMeshesAndUserShapes) {
    const TriangleMesh sphere = test::icosphere(2, Vec3(1.0f, -0.5f, 0.0f), 1.5f);
    const TriangleMesh soup = randomSoup(300, Vec3(0.0f), 5);
    const SphereSet balls = randomSpheres(60, 9);
    const std::vector<ShapeRef> shapes = {{&sphere, nullptr}, {nullptr, &balls}, {&soup, nullptr}};
    const auto naive = buildNaiveAccel(shapes);
    const auto embree = buildEmbreeAccel(std::span<const ShapeRef>(shapes), {});
    const auto rays = randomRays(naive->bounds(), 30000, 31);
    expectAgreement(compareWithEmbree(shapes, *naive, *embree, rays), 12000);

    // Both tracers ran the same sphere code, so its hits agree bit for bit.
    int userHits = 0;
    for (const Ray& ray : rays) {
        const Hit ours = naive->intersect(ray);
        if (ours.geomID != 1) continue;
        ++userHits;
        const Hit theirs = embree->intersect(ray);
        if (theirs.geomID != 1 || theirs.primID != ours.primID) continue;  // counted above
        EXPECT_EQ(ours.t, theirs.t);
        EXPECT_EQ(ours.u, theirs.u);
        EXPECT_EQ(ours.v, theirs.v);
        EXPECT_EQ(ours.Ng, theirs.Ng);
    }
    EXPECT_GT(userHits, 3000);
}

// ---------------------------------------------------------------------------
// Internal consistency of the naive tracer.

TEST(NaiveAccel, OccludedAgreesWithIntersect) {
    const TriangleMesh soup = randomSoup(800, Vec3(0.0f), 3);
    const TriangleMesh grid = wavyGrid(12, 0.0f);
    const SphereSet balls = randomSpheres(20, 4);
    const std::vector<ShapeRef> shapes = {{&soup, nullptr}, {nullptr, &balls}, {&grid, nullptr}};
    const auto naive = buildNaiveAccel(shapes);
    int hits = 0, misses = 0;
    for (Ray ray : randomRays(naive->bounds(), 4000, 8)) {
        const Hit hit = naive->intersect(ray);
        EXPECT_EQ(naive->occluded(ray), hit.valid());
        if (!hit.valid()) {
            ++misses;
            continue;
        }
        ++hits;
        EXPECT_GT(hit.t, ray.tnear);
        EXPECT_LT(hit.t, ray.tfar);
        // The segment ending exactly at the closest hit holds no other hit.
        ray.tfar = hit.t;
        EXPECT_FALSE(naive->occluded(ray));
    }
    EXPECT_GT(hits, 1000);
    EXPECT_GT(misses, 100);
    EXPECT_GT(balls.occludedCalls.load(), 0) << "occluded() asks the user shape's occluded()";
}

template <int N>
void expectPacketsMatchSingleRays() {
    const TriangleMesh soup = randomSoup(500, Vec3(0.0f), 13);
    const SphereSet balls = randomSpheres(15, 2);
    const std::vector<ShapeRef> shapes = {{&soup, nullptr}, {nullptr, &balls}};
    const auto naive = buildNaiveAccel(shapes);
    const auto rays = randomRays(naive->bounds(), 200 * N, 19);
    int hits = 0, misses = 0;
    for (size_t first = 0; first + N <= rays.size(); first += N) {
        RayHitPacket<N> packet;
        alignas(64) int valid[N];
        for (int lane = 0; lane < N; ++lane) {
            packet.setRay(lane, rays[first + lane]);
            valid[lane] = lane % 5 == 2 ? 0 : -1;  // some inactive lanes
        }
        const RayHitPacket<N> before = packet;
        naive->intersectPacket(valid, packet, RayCoherence::Incoherent);
        for (int lane = 0; lane < N; ++lane) {
            if (!valid[lane]) {
                EXPECT_EQ(packet.geomID[lane], kInvalidId) << "inactive lanes are untouched";
                EXPECT_EQ(packet.tfar[lane], before.tfar[lane]);
                continue;
            }
            const Hit single = naive->intersect(rays[first + lane]);
            const Hit fromPacket = packet.hit(lane);
            ASSERT_EQ(single.valid(), fromPacket.valid());
            if (!single.valid()) {
                ++misses;
                EXPECT_EQ(packet.tfar[lane], before.tfar[lane]) << "a miss leaves tfar";
                continue;
            }
            ++hits;
            EXPECT_EQ(fromPacket.geomID, single.geomID);
            EXPECT_EQ(fromPacket.primID, single.primID);
            EXPECT_EQ(fromPacket.t, single.t);
            EXPECT_EQ(fromPacket.u, single.u);
            EXPECT_EQ(fromPacket.v, single.v);
            EXPECT_EQ(fromPacket.Ng, single.Ng);
        }
    }
    EXPECT_GT(hits, 25 * N);
    EXPECT_GT(misses, 5 * N);
}

TEST(NaiveAccel, Packets8MatchSingleRays) {
    expectPacketsMatchSingleRays<8>();
}
TEST(NaiveAccel, Packets16MatchSingleRays) {
    expectPacketsMatchSingleRays<16>();
}

// ---------------------------------------------------------------------------
// User shapes, nearest hit across shape kinds, ties.

TEST(NaiveAccel, CallsUserShapesAndPicksTheNearestAcrossKinds) {
    const TriangleMesh plane = test::unitQuad(0.0f);           // geomID 0
    const SphereSet balls({{{0, 0, -3}, 1.0f},       // primID 0: behind the quad
                           {{3, 0, 0}, 0.5f},        // primID 1: beside it
                           {{0, 0.5f, 2}, 0.25f}});  // primID 2: in front of it
    const std::vector<ShapeRef> shapes = {{&plane, nullptr}, {nullptr, &balls}};  // balls: geomID 1
    const auto naive = buildNaiveAccel(shapes);

    Hit hit = naive->intersect(rayFrom({3, 0, 10}, {0, 0, -1}));
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.geomID, 1u);
    EXPECT_EQ(hit.primID, 1u);
    EXPECT_FLOAT_EQ(hit.t, 9.5f);
    EXPECT_GT(hit.Ng.z, 0.0f);

    hit = naive->intersect(rayFrom({0, 0.5f, 10}, {0, 0, -1}));
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.geomID, 1u);
    EXPECT_EQ(hit.primID, 2u);
    EXPECT_FLOAT_EQ(hit.t, 7.75f);

    // The quad (tested first) is nearer than sphere 0: the spheres are asked
    // with tfar already shrunk to the quad's t, as Embree would pass it.
    balls.intersectCalls = 0;
    hit = naive->intersect(rayFrom({0, 0, 10}, {0, 0, -1}));
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.geomID, 0u);
    EXPECT_FLOAT_EQ(hit.t, 10.0f);
    EXPECT_EQ(balls.intersectCalls.load(), 3) << "every primitive is asked";
    EXPECT_EQ(balls.lastTfar.load(), 10.0f);

    // From below, sphere 0 is nearer than the quad and wins over it.
    hit = naive->intersect(rayFrom({0, 0, -10}, {0, 0, 1}));
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.geomID, 1u);
    EXPECT_EQ(hit.primID, 0u);
    EXPECT_FLOAT_EQ(hit.t, 6.0f);
    EXPECT_LT(hit.Ng.z, 0.0f);

    EXPECT_FALSE(naive->intersect(rayFrom({5, 5, 10}, {0, 0, -1})).valid());
}

TEST(NaiveAccel, EmbreeAgreesOnUserShapesAndNearestAcrossKinds) {
    const TriangleMesh plane = test::unitQuad(0.0f);
    const SphereSet balls({{{0, 0, -3}, 1.0f}, {{3, 0, 0}, 0.5f}, {{0, 0.5f, 2}, 0.25f}});
    const std::vector<ShapeRef> shapes = {{&plane, nullptr}, {nullptr, &balls}};
    const auto naive = buildNaiveAccel(shapes);
    const auto embree = buildEmbreeAccel(std::span<const ShapeRef>(shapes), {});
    const Ray rays[] = {rayFrom({3, 0, 10}, {0, 0, -1}),       rayFrom({0, 0.5f, 10}, {0, 0, -1}),
                        rayFrom({0, 0, 10}, {0, 0, -1}),       rayFrom({0, 0, -10}, {0, 0, 1}),
                        rayFrom({0.1f, 0.2f, -10}, {0, 0, 1}), rayFrom({5, 5, 10}, {0, 0, -1})};
    for (const Ray& ray : rays) {
        SCOPED_TRACE(testing::Message() << "ray from (" << ray.origin.x << ", " << ray.origin.y
                                        << ", " << ray.origin.z << ")");
        const Hit ours = naive->intersect(ray);
        const Hit theirs = embree->intersect(ray);
        ASSERT_EQ(ours.valid(), theirs.valid());
        if (!ours.valid()) continue;
        EXPECT_EQ(ours.geomID, theirs.geomID);
        EXPECT_EQ(ours.primID, theirs.primID);
        EXPECT_FLOAT_EQ(ours.t, theirs.t);
        EXPECT_GT(glm::dot(ours.Ng, theirs.Ng), 0.0f);
        EXPECT_EQ(naive->occluded(ray), embree->occluded(ray));
    }
}

TEST(NaiveAccel, TiesKeepTheFirstHitFound) {
    const TriangleMesh first = test::unitQuad(0.0f), copy = test::unitQuad(0.0f);
    const std::vector<ShapeRef> meshes = meshRefs({&first, &copy});
    const auto naive = buildNaiveAccel(meshes);
    // On the diagonal both triangles of both quads are hit at exactly t = 1.
    const Hit hit = naive->intersect(rayFrom({0.5f, 0.5f, 1}, {0, 0, -1}));
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.geomID, 0u);
    EXPECT_EQ(hit.primID, 0u);

    const SphereSet twins({{{0, 0, 0}, 1.0f}, {{0, 0, 0}, 1.0f}});
    const SphereSet twin({{{0, 0, 0}, 1.0f}});
    const std::vector<ShapeRef> users = {{nullptr, &twins}, {nullptr, &twin}};
    const Hit userHit = buildNaiveAccel(users)->intersect(rayFrom({0, 0, 5}, {0, 0, -1}));
    ASSERT_TRUE(userHit.valid());
    EXPECT_EQ(userHit.geomID, 0u);
    EXPECT_EQ(userHit.primID, 0u);
}

TEST(NaiveAccel, BoundsWidthAndMemory) {
    const TriangleMesh low = test::unitQuad(-2.0f);
    const TriangleMesh soup = randomSoup(5000, Vec3(0.0f), 1);
    const SphereSet ball({{{0, 0, 10}, 1.0f}});
    const std::vector<ShapeRef> shapes = {{&low, nullptr}, {&soup, nullptr}, {nullptr, &ball}};
    const auto naive = buildNaiveAccel(shapes);
    Bounds3 expected = soup.bounds();
    expected.expand(low.bounds());
    expected.expand(ball.bounds());
    EXPECT_EQ(naive->bounds().min, expected.min);
    EXPECT_EQ(naive->bounds().max, expected.max);
    EXPECT_EQ(naive->bounds().max.z, 11.0f);
    EXPECT_EQ(naive->nativePacketWidth(), 1);
    EXPECT_GT(naive->memoryBytes(), 0u);
    EXPECT_LT(naive->memoryBytes(), soup.memoryBytes() / 10) << "the shapes are not copied";

    const auto empty = buildNaiveAccel(std::span<const ShapeRef>());
    EXPECT_TRUE(empty->bounds().empty());
    EXPECT_FALSE(empty->intersect(rayFrom({0, 0, 0}, {0, 0, 1})).valid());
    EXPECT_FALSE(empty->occluded(rayFrom({0, 0, 0}, {0, 0, 1})));
}

TEST(NaiveAccel, MeshOverloadMatchesShapeRefs) {
    const TriangleMesh a = randomSoup(300, Vec3(0.0f), 21), b = wavyGrid(8, 0.5f);
    const TriangleMesh* meshes[] = {&a, &b};
    const auto fromMeshes = buildNaiveAccel(meshes);
    const auto fromRefs = buildNaiveAccel(meshRefs({&a, &b}));
    for (const Ray& ray : randomRays(fromMeshes->bounds(), 500, 4)) {
        const Hit x = fromMeshes->intersect(ray), y = fromRefs->intersect(ray);
        EXPECT_EQ(x.geomID, y.geomID);
        EXPECT_EQ(x.primID, y.primID);
        EXPECT_EQ(x.t, y.t);
    }
}

}  // namespace
}  // namespace strahl
