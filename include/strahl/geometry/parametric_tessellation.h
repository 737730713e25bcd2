#pragma once
// Tessellated mode of a parametric surface: triangles for an Embree triangle
// BVH, with the way back from a triangle hit to the surface.
//
// tessellateParametric() puts a vertex at every point of a ParametricGrid and
// cuts every grid cell into two triangles along its shorter diagonal, wound so
// that the triangle normal follows ∂u f × ∂v f. It is crack-free:
//  * the grid has no T-junctions (parametric_grid.h);
//  * vertices on patch borders — periodic seams, twisted seams, edges shared by
//    two patches, and poles, where a whole edge collapses to one point — are
//    welded: every border vertex within a tiny distance of an earlier one takes
//    that one's position bit for bit, so both sides of a seam are exactly the
//    same edge for the watertight triangle test;
//  * triangles that welding collapses (at a pole) are dropped.
// Vertices are not shared between patches (each keeps its own (u, v)), only
// positions are.
//
// TessellatedSurface then maps a hit's barycentrics back to (u, v) (the
// barycentric mix of the triangle's corner parameters) and shades with the
// exact normal ∂u f × ∂v f there, or, as an option to compare, with the
// interpolated vertex normals.

#include <cstdint>
#include <vector>

#include "strahl/geometry/parametric_grid.h"
#include "strahl/geometry/parametric_surface.h"
#include "strahl/geometry/triangle_mesh.h"

namespace strahl {

enum class ParametricNormals { Exact, Interpolated };

struct Tessellation {
    TriangleMesh mesh;            // object space; per-vertex normals if interpolated
    std::vector<Vec2> params;     // (u, v) of every vertex
    std::vector<uint32_t> patchFirstTriangle;  // patchCount() + 1 entries
};

// Throws strahl::Error if the grid yields no triangle or a vertex is not finite.
Tessellation tessellateParametric(const ParametricSurface& surface, const ParametricGrid& grid,
                                  ParametricNormals normals);

class TessellatedSurface {
public:
    // `tessellation`'s mesh goes to the caller (the scene keeps it in world
    // space for the accelerator); this keeps the parameters.
    // flipNormals: the front is the other side (the mesh's winding must be
    // turned around to match: TriangleMesh::flipOrientation).
    TessellatedSurface(ParametricSurfacePtr surface, Tessellation&& tessellation,
                       const Mat4& objectToWorld, ParametricNormals normals, bool flipNormals = false);

    // The interaction on triangle `prim` of `worldMesh` (the tessellation's
    // mesh, transformed to world space) at Embree barycentrics (b1, b2): p and Ng
    // from the triangle, Ns exact or interpolated, uv the normalised (u, v).
    SurfaceInteraction interaction(const TriangleMesh& worldMesh, uint32_t prim, float b1,
                                   float b2) const;
    // The surface parameters of that hit, and the patch.
    Vec2 parameters(const TriangleMesh& worldMesh, uint32_t prim, float b1, float b2) const;
    uint32_t patchOf(uint32_t prim) const;

    const ParametricSurface& surface() const { return *surface_; }
    ParametricNormals normals() const { return normals_; }
    size_t memoryBytes() const;

private:
    ParametricSurfacePtr surface_;
    std::vector<Vec2> params_;
    std::vector<uint32_t> patchFirstTriangle_;
    glm::dmat3 linearToWorld_;  // objectToWorld's linear part (tangents)
    Mat3 normalToWorld_;        // its inverse transpose (normals)
    ParametricNormals normals_;
};

}  // namespace strahl
