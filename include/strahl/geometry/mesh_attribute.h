#pragma once
// Named per-vertex or per-face values a mesh file may carry (PLY properties
// such as color_0 color_1 color_2; docs/mesh-files.md), and what a material
// reads of them at a hit (a texture's "attribute" source; docs/materials.md).

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/core/math.h"

namespace strahl {

struct MeshAttribute {
    enum class Scope { Vertex, Face };
    std::string name;  // "vertex_color", "face_weight", ... (Mitsuba's names)
    Scope scope = Scope::Vertex;
    int channels = 1;  // 1 to 4
    // channels values per vertex, or per triangle for Face (a polygon's
    // values repeated for each triangle of its fan).
    std::vector<float> values;
};

struct TriangleMesh;

// The attributes of the mesh a ray hit, at the hit: interpolated with the
// barycentrics for vertex attributes, the triangle's own for face ones.
struct MeshAttributePoint {
    const TriangleMesh* mesh = nullptr;  // null: not a mesh, or one without attributes
    uint32_t triangle = 0;
    Vec2 barycentric{0.0f};  // Embree's (u, v): the weights of the triangle's 2nd and 3rd vertex

    // The attribute called `name`, or null.
    const MeshAttribute* find(std::string_view name) const;
    // Its value here as (r, g, b, a): one channel is grey (v, v, v, 1), two
    // are (x, y, 0, 1), three (r, g, b, 1). A missing attribute reads 0.
    Vec4 value(std::string_view name) const;
};

}  // namespace strahl
