#pragma once
// The naive tracer: the textbook image-order algorithm taken literally. Every
// query tests the ray against every primitive of every shape and keeps the
// nearest hit — O(n) per ray in the number of primitives, no build step, no
// acceleration structure. It is strahl's correctness oracle (tests compare
// Embree's answers with it) and the baseline the benchmarks beat.
//
// It implements the same Accel interface over the same AccelScene as
// buildEmbreeAccel (instances: the ray is mapped into the prototype's object
// space and the prototype's shapes are looped over), with the same IDs (geomID = position in the list, primID =
// triangle or primitive index) and the same hit conventions:
//  - triangles go through the watertight test (watertight_triangle.h), which
//    reports u, v and Ng exactly as Embree's triangle does;
//  - user shapes are asked through UserShape::intersect/occluded — the very
//    code Embree's user-geometry callbacks call — with the ray's tfar shrunk to
//    the closest hit so far, as Embree would pass it.
// Ties at equal t keep the first hit found (lowest geomID, then lowest primID),
// so results are deterministic. Packet queries loop over the active lanes.
//
// The shapes must outlive the Accel; memoryBytes() counts only the shape list.

#include <memory>
#include <span>

#include "strahl/accel/accel.h"

namespace strahl {

std::unique_ptr<Accel> buildNaiveAccel(const AccelScene& scene);
// The same without instancing.
std::unique_ptr<Accel> buildNaiveAccel(std::span<const ShapeRef> shapes);
// The same for a list of meshes only.
std::unique_ptr<Accel> buildNaiveAccel(std::span<const TriangleMesh* const> meshes);

}  // namespace strahl
