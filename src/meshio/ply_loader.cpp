// Stanford PLY loader: ascii, binary_little_endian and binary_big_endian 1.0.
// loadPly maps the file (mapped_file.h) and decodes from the mapping; the header
// is parsed into a list of elements (ply_header.h); the body is then read
// element by element in file order:
//   - before anything is allocated, the element's item count times the fewest
//     bytes an item can take is checked against what is left of the file, so a
//     lying count fails at once with a message naming the element;
//   - binary vertex and face elements are decoded in parallel (ply_parallel.h),
//     elements of fixed-size items that are neither are jumped over;
//   - ascii bodies, and every binary element the parallel decoder declines or
//     that does not fit, go through the generic one-value-at-a-time reader
//     (ply_sequential.h), which names the first bad value's place.
// Both paths give the same mesh, bit for bit, and the same errors.

#include <charconv>
#include <zlib.h>

#include <bit>
#include <cstring>

#include "loader_tuning.h"
#include "inflate.h"
#include "strahl/meshio/mapped_file.h"
#include "ply_header.h"
#include "ply_parallel.h"
#include "ply_sequential.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/meshio/mesh_format.h"
#include "text_scan.h"

namespace fs = std::filesystem;

namespace strahl {

namespace meshio::ply {

namespace {

const char* itemNoun(const Element& e, const Layout& layout) {
    if (&e == layout.vertex) return "vertices";
    if (&e == layout.face) return "faces";
    return "items";
}

// Empty when `e`'s items can fit in the bytes from `offset` on; otherwise the
// reason, to follow the end-of-file message of the reader that runs into it:
// ": element vertex: 1000000 vertices of 12 bytes need 12000000 bytes but only
// 1234 remain after the header".
std::string shortfall(const Header& h, const Layout& layout, const Element& e, size_t offset,
                      size_t size) {
    const size_t fixed = e.fixedBinarySize();
    const size_t least = fixed ? fixed : e.minBinarySize(&e == layout.face ? layout.faceIndices : nullptr);
    const size_t remaining = size - offset;
    if (least == 0 || e.count <= remaining / least) return {};
    uint64_t needed = 0;
    const bool overflows = __builtin_mul_overflow(e.count, uint64_t(least), &needed);
    const std::string where =
        offset == h.bodyOffset ? std::string("after the header") : concat("from byte offset ", offset);
    return concat(": element ", e.name, ": ", e.count, ' ', itemNoun(e, layout), " of ",
                  fixed ? "" : "at least ", least, " bytes need ",
                  overflows ? std::string("more than 2^64") : concat(needed), " bytes but only ",
                  remaining, " remain ", where);
}

void readBinaryBody(const std::string& name, std::string_view data, const Header& h,
                    const Layout& layout, bool parallel, TriangleMesh& mesh) {
    constexpr bool kLittleHost = std::endian::native == std::endian::little;
    const bool swap = (h.encoding == Encoding::BinaryBigEndian) == kLittleHost;
    const BinaryBody body{name, data, swap};
    size_t offset = h.bodyOffset;
    for (const Element& e : h.elements) {
        if (e.properties.empty()) continue;  // items without properties occupy no bytes
        const std::string note = shortfall(h, layout, e, offset, data.size());
        if (parallel && note.empty()) {
            const size_t fixed = e.fixedBinarySize();
            if (&e == layout.vertex && fixed != 0) {
                decodeVertices(body, offset, layout, mesh);
                offset += size_t(e.count) * fixed;
                continue;
            }
            if (&e == layout.face) {
                if (const std::optional<size_t> end = decodeFaces(body, offset, layout, mesh)) {
                    offset = *end;
                    continue;
                }
            } else if (&e != layout.vertex && fixed != 0) {
                offset += size_t(e.count) * fixed;  // fits: checked by shortfall()
                continue;
            }
        }
        offset = readBinaryElement(name, data, offset, swap, layout, e, mesh, note);
    }
}

}  // namespace

}  // namespace meshio::ply

namespace meshio {

LoadedMesh decodePly(std::string_view data, const fs::path& file, bool parallel) {
    const std::string name = file.string();
    const ply::Header header = ply::parseHeader(name, data);
    const ply::Layout layout = ply::makeLayout(name, header);

    LoadedMesh result;
    result.mesh.attributes = ply::makeAttributes(layout);
    if (header.encoding == ply::Encoding::Ascii)
        ply::readAsciiBody(name, data, header, layout, result.mesh);
    else
        ply::readBinaryBody(name, data, header, layout, parallel, result.mesh);
    // Both body readers already check everything validate() does as they store
    // it (finite coordinates, indices below the vertex count; the array sizes
    // hold by construction), the parallel decoder in parallel: validating again
    // would be a sequential pass over the whole mesh (6 % of a 10M-triangle
    // load). The sequential path keeps it, as the loader always did.
    if (!parallel || header.encoding == ply::Encoding::Ascii) result.mesh.validate(name);
    return result;
}

LoadedMesh loadPlySequential(const fs::path& file) {
    return decodePly(readWholeFile(file), file, false);
}

}  // namespace meshio

LoadedMesh loadPly(const fs::path& file) {
    const meshio::MappedFile mapping(file);
    return meshio::decodePly(mapping.bytes(), file, true);
}

LoadedMesh loadPlyFromMemory(std::string_view data, const fs::path& file) {
    return meshio::decodePly(data, file, true);
}

namespace {
constexpr std::string_view kPlyExtensions[] = {".ply"};

// gzip-compressed PLY (.ply.gz, as pbrt-v4's scenes ship some meshes):
// inflated into memory, then read as any PLY.
LoadedMesh loadGzipPlyFromMemory(std::string_view data, const fs::path& file) {
    const std::string ply = meshio::inflateAll(data, file.string(), meshio::Compression::Gzip);
    return meshio::decodePly(ply, file, true);
}
LoadedMesh loadGzipPly(const fs::path& file) {
    const meshio::MappedFile mapping(file);
    return loadGzipPlyFromMemory(mapping.bytes(), file);
}
constexpr std::string_view kGzipPlyExtensions[] = {".ply.gz"};
}  // namespace

// What the two header queries below need, from one pass over the header
// lines (of a plain or gzipped file): whether the vertex element has "nx",
// and the face element's count. All false and 0 for a file that cannot be read.
struct PlyHeaderFacts {
    bool vertexNormals = false;
    size_t faces = 0;
};

PlyHeaderFacts scanPlyHeader(const fs::path& file) {
    PlyHeaderFacts facts;
    // gzread reads plain files as they are and .gz files inflated.
    gzFile in = gzopen(file.string().c_str(), "rb");
    if (!in) return facts;
    char line[1024];
    bool inVertex = false;
    // A header of more than 1000 lines is no PLY header strahl reads.
    for (int lines = 0; lines < 1000 && gzgets(in, line, sizeof line); ++lines) {
        std::string_view text(line);
        while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.remove_suffix(1);
        if (text.starts_with("end_header")) break;
        if (text.starts_with("element ")) inVertex = text.starts_with("element vertex ");
        if (inVertex && text.starts_with("property ") && text.ends_with(" nx")) facts.vertexNormals = true;
        if (text.starts_with("element face ")) {
            const std::string_view count = text.substr(13);
            std::from_chars(count.data(), count.data() + count.size(), facts.faces);
        }
    }
    gzclose(in);
    return facts;
}

bool plyFileHasVertexNormals(const fs::path& file) { return scanPlyHeader(file).vertexNormals; }

size_t plyFileFaceCount(const fs::path& file) { return scanPlyHeader(file).faces; }

extern const MeshFormat kPlyFormat{"PLY", kPlyExtensions, &loadPly, &loadPlyFromMemory};
extern const MeshFormat kGzipPlyFormat{"gzip-compressed PLY", kGzipPlyExtensions, &loadGzipPly,
                                       &loadGzipPlyFromMemory};

}  // namespace strahl
