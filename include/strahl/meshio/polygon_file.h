#pragma once
// Polygon meshes from Wavefront OBJ files, faces kept as polygons: the control
// cages of subdivision surfaces (geometry/catmull_clark.h), which the mesh
// loaders (mesh_file.h) would split into triangles.
//
// Read: `v x y z`, `vt u v`, `f a b c …` with the forms a, a/t, a/t/n and
// a//n, negative (relative) indices included; every other statement (`vn`,
// `o`, `g`, `s`, `usemtl`, `mtllib`, comments) is skipped. The uvs are kept
// per position when every face gives one and each position always gets the
// same one (no seams); otherwise there are none. A malformed number, an index
// out of range, a face of fewer than 3 or more than `maxFaceSize` vertices or
// a file without faces throws strahl::Error with "file:line: what".

#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/vec2.hpp>

#include "strahl/core/point3.h"

namespace strahl {

struct PolygonFile {
    std::vector<DVec3> positions;
    std::vector<glm::dvec2> uvs;  // one per position, or empty
    std::vector<uint32_t> faceSizes;
    std::vector<uint32_t> indices;
};

PolygonFile loadObjPolygons(const std::filesystem::path& file, uint32_t maxFaceSize);

}  // namespace strahl
