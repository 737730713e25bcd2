#pragma once
// The parallel half of the OBJ loader (obj_chunks.cpp): the text is cut into
// chunks at line ends, and each chunk is parsed on its own into plain arrays.
// What depends on the statements before a chunk is settled by the loader when
// it joins the chunks in order (obj_loader.cpp): relative indices are resolved
// here, from the number of v/vt/vn statements before the chunk (a first,
// cheap pass counts them per chunk); materials, .mtl libraries, warnings and
// the distinct-corner table are left to the join.

#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/core/math.h"

namespace strahl::meshio::obj {

constexpr uint32_t kNone = UINT32_MAX;

// One face corner: 0-based indices into all of the file's v, vt and vn
// (kNone when absent).
struct Corner {
    uint32_t v = kNone;
    uint32_t vt = kNone;
    uint32_t vn = kNone;
};

struct Counts {
    size_t v = 0, vt = 0, vn = 0;
};

// A statement whose effect depends on the whole file so far, kept for the join
// in file order: an mtllib (its names) or the first use in the chunk of a
// keyword strahl does not support.
struct Deferred {
    enum class Kind { MaterialLibrary, Unsupported };
    Kind kind;
    size_t line;
    std::string_view text;  // the rest of the mtllib line, or the keyword
};

struct UseMaterial {
    std::string_view name;
    size_t line;
};

struct Chunk {
    std::string_view text;  // whole lines; the last one may lack its '\n'
    size_t firstLine = 1;   // number of its first line in the file

    // Pass 1.
    size_t lines = 0;  // '\n' characters
    Counts own;        // v, vt, vn statements
    size_t ownFaces = 0;  // f statements (to reserve memory)
    Counts before;     // ... in all chunks before this one

    // Pass 2, up to the chunk's first error. Coordinates go straight into the
    // file's arrays (Attributes), from index `before` on.
    Counts parsed;                     // v, vt, vn statements stored
    std::vector<Corner> corners;       // of all faces, in order
    std::vector<uint32_t> faceSizes;   // corners of each face
    std::vector<uint32_t> faceUse;     // per face: usemtl statements before it in the chunk
    std::vector<UseMaterial> usemtl;   // in order
    std::vector<Deferred> deferred;    // in order
    bool cornerWithUv = false, cornerWithoutUv = false;
    bool cornerWithNormal = false, cornerWithoutNormal = false;
    std::exception_ptr error;  // the first error: "file:line: what"
};

// The v, vt and vn values of the whole file, sized by pass 1; each chunk fills
// its own range.
struct Attributes {
    std::vector<Vec3> positions;
    std::vector<Vec2> texcoords;
    std::vector<Vec3> normals;
};

// Cuts `text` into chunks of about `chunkBytes` (at least one line each), each
// ending just after a '\n' except the last.
std::vector<Chunk> splitIntoChunks(std::string_view text, size_t chunkBytes);

// Pass 1: counts the chunk's lines and v, vt, vn statements.
void countStatements(Chunk& chunk);

// Pass 2: parses the chunk (chunk.before must be set, `attributes` sized for all
// chunks). Stops at the first error, which is kept in chunk.error, not thrown.
void parseChunk(const std::string& file, Chunk& chunk, Attributes& attributes);

// The line of face `face` (0-based, counted within the chunk), for errors
// found after parsing.
size_t lineOfFace(const std::string& file, const Chunk& chunk, size_t face);

}  // namespace strahl::meshio::obj
