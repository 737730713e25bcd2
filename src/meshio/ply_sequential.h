#pragma once
// The generic, one-value-at-a-time PLY body reader (ply_sequential.cpp).

#include <cstddef>
#include <string>
#include <string_view>

#include "ply_header.h"
#include "strahl/geometry/triangle_mesh.h"

namespace strahl::meshio::ply {

// Reads element `e` of a binary body starting at byte `offset` of `data`,
// appending its vertices or triangles to `mesh` (other elements are skipped);
// returns the offset after the element. `swapBytes`: the file's byte order is
// not the host's. Errors: "file: byte offset N: what"; `truncationNote`, if not
// empty, follows the end-of-file message.
size_t readBinaryElement(const std::string& file, std::string_view data, size_t offset,
                         bool swapBytes, const Layout& layout, const Element& e,
                         TriangleMesh& mesh, std::string_view truncationNote = {});

// Reads a whole ascii body. Errors: "file:line N: what".
void readAsciiBody(const std::string& file, std::string_view data, const Header& h,
                   const Layout& layout, TriangleMesh& mesh);

}  // namespace strahl::meshio::ply
