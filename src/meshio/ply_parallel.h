#pragma once
// Parallel decoding of binary PLY elements straight into the mesh arrays
// (ply_parallel.cpp; the design is in docs/mesh-files.md, "Loading large
// files"). Each function either decodes the whole element, or throws the error
// the generic reader (ply_sequential.h) would throw first, or declines and
// leaves the mesh as it was, for the generic reader to take over.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "ply_header.h"
#include "strahl/geometry/triangle_mesh.h"

namespace strahl::meshio::ply {

// Where a binary body lives and how to read it.
struct BinaryBody {
    const std::string& file;  // for errors
    std::string_view data;    // the whole file
    bool swapBytes;           // the file's byte order is not the host's
};

// The vertex element, which must have no list property and fit in the bytes
// from `offset` on (count x record size): positions, and normals and uvs when
// the layout has them, in parallel chunks. Throws "file: byte offset N: vertex
// i has a non-finite y" for the first such value in file order.
void decodeVertices(const BinaryBody& body, size_t offset, const Layout& layout,
                    TriangleMesh& mesh);

// The face element from `offset`: fan-triangulated into mesh.indices. Returns
// the offset after it, or nullopt (mesh untouched) when the element has a list
// besides the index list or attributes, is cut short, or holds a face shorter than 3 corners
// or a negative list length: the generic reader then reports the first problem.
// Throws "file: byte offset N: face i refers to vertex j but there are only n
// vertices" for the first bad index in file order.
std::optional<size_t> decodeFaces(const BinaryBody& body, size_t offset, const Layout& layout,
                                  TriangleMesh& mesh);

}  // namespace strahl::meshio::ply
