// Parallel decoding of binary PLY vertex and face elements.
//
// Vertices: an element without lists has records of one fixed size, so record
// i starts at offset + i * stride and chunks of records decode independently,
// each straight into its slice of the (pre-sized) positions, normals and uvs.
//
// Faces: almost every file has one index list per face and the same corner
// count in all of them (triangles). The record size is then fixed too; it is
// derived from the first face's count and checked on every face as it is
// decoded. If some face differs (quads among triangles), one sequential pass
// walks the records, validating every count and noting where each block of
// kFacesPerBlock faces starts and how many triangles come before it; the blocks
// are then decoded in parallel. A face element with a second list property, or
// anything odd the pass meets (a face shorter than 3 corners, a negative list
// length, the end of the data), and faces with attributes (rare) go back to
// the generic reader, which names
// the first problem in file order.
//
// Errors found by parallel chunks (a non-finite coordinate, an index out of
// range) are collected, not thrown, and the one first in file order is thrown
// after the loop, so the message is the generic reader's whatever the thread
// count.

#include "ply_parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <mutex>
#include <tuple>
#include <vector>

#include "ply_binary.h"
#include "strahl/core/error.h"

namespace strahl::meshio::ply {

namespace {

// Records per parallel task. 2^14 vertices are 200-800 KB of input and 2^14
// triangles 210 KB: large enough that the scheduler's cost per task (about a
// microsecond) is lost in the decoding (tens of microseconds), small enough
// that a 10^5-triangle mesh still splits into several tasks per thread.
constexpr size_t kVertexGrain = size_t(1) << 14;
constexpr size_t kFaceGrain = size_t(1) << 14;
// Faces per block on the variable-size path: the walk stores 16 bytes per
// block, and 2^12 faces (50-100 KB) are plenty of work for one task.
constexpr uint64_t kFacesPerBlock = uint64_t(1) << 12;

// The error first in file order among those the chunks report. Each chunk
// reports at most one (it stops at its first), so the lock is rarely taken.
class FirstError {
public:
    void offer(uint64_t item, uint64_t part, size_t offset, std::string what) {
        std::lock_guard lock(mutex_);
        if (any_ && std::tie(item_, part_) <= std::tie(item, part)) return;
        any_ = true;
        item_ = item;
        part_ = part;
        offset_ = offset;
        what_ = std::move(what);
    }

    void throwIfAny(const std::string& file) const {
        if (any_) fail(file, ": byte offset ", offset_, ": ", what_);
    }

private:
    std::mutex mutex_;
    bool any_ = false;
    uint64_t item_ = 0;  // vertex or face index
    uint64_t part_ = 0;  // property or corner within it
    size_t offset_ = 0;
    std::string what_;
};

// Resizes `v` to n elements with room for `spare` more. (Transparent huge
// pages for these arrays, madvise(MADV_HUGEPAGE), made repeated loads 25 %
// faster but the first load of a process up to 3x slower, while the kernel
// compacted memory for them: rejected.)
template <typename T>
void resizeForDecoding(std::vector<T>& v, size_t n, size_t spare = 0) {
    v.reserve(n + spare);
    v.resize(n);
}

// ---------------------------------------------------------------------------
// Vertices

struct VertexField {
    int role;
    size_t offset;  // within the record
    Scalar type;
    size_t property;  // index in the element, for the error order
    const std::string* name;
};

// kAllFloat: every field used is a float32, loaded without the double detour
// (float -> double -> float is the identity for every finite value).
template <bool kSwap, bool kAllFloat>
void decodeVerticesAs(const BinaryBody& body, size_t offset, const Layout& layout,
                      TriangleMesh& mesh) {
    const Element& e = *layout.vertex;
    const size_t stride = e.fixedBinarySize();
    std::vector<VertexField> fields;
    size_t at = 0;
    for (size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (layout.vertexRoles[k] != kSkip)
            fields.push_back({layout.vertexRoles[k], at, p.type, k, &p.name});
        at += sizeOf(p.type);
    }

    const auto count = static_cast<size_t>(e.count);  // at most 2^32-1 (makeLayout)
    resizeForDecoding(mesh.positions, count, 1);  // the spare element Embree's 16-byte loads need
    if (layout.hasNormals) resizeForDecoding(mesh.normals, count);
    if (layout.hasUvs) resizeForDecoding(mesh.uvs, count);
    for (size_t a = 0; a < layout.vertexAttributes.size(); ++a)
        resizeForDecoding(mesh.attributes[a].values, count * size_t(mesh.attributes[a].channels));

    const char* const records = body.data.data() + offset;
    FirstError firstError;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, kVertexGrain), [&](const auto& range) {
        std::vector<float> values(kRoleCount + layout.vertexChannels(), 0.0f);
        for (size_t i = range.begin(); i != range.end(); ++i) {
            const char* record = records + i * stride;
            for (const VertexField& f : fields) {
                // Through double, as the generic reader converts: same bits.
                // (attributeValue leaves a float as it is.)
                float v;
                if constexpr (kAllFloat)
                    v = loadAs<kSwap, float, uint32_t>(record + f.offset);
                else if (f.role < kRoleCount)
                    v = static_cast<float>(loadReal<kSwap>(record + f.offset, f.type));
                else
                    v = attributeValue(loadReal<kSwap>(record + f.offset, f.type), f.type);
                if (!std::isfinite(v)) {
                    firstError.offer(i, f.property, offset + i * stride + f.offset,
                                     concat("vertex ", i, " has a non-finite ", *f.name));
                    return;
                }
                values[f.role] = v;
            }
            mesh.positions[i] = Vec3(values[kX], values[kY], values[kZ]);
            if (layout.hasNormals) mesh.normals[i] = Vec3(values[kNX], values[kNY], values[kNZ]);
            if (layout.hasUvs) mesh.uvs[i] = Vec2(values[kU], values[kV]);
            size_t channel = kRoleCount;
            for (size_t a = 0; a < layout.vertexAttributes.size(); ++a) {
                const auto n = size_t(mesh.attributes[a].channels);
                for (size_t c = 0; c < n; ++c) mesh.attributes[a].values[i * n + c] = values[channel++];
            }
        }
    });
    firstError.throwIfAny(body.file);
}

// ---------------------------------------------------------------------------
// Faces

// The face record around its index list: scalars before and after it, and
// whether any other list makes records variable beyond the index list's count.
struct FaceRecord {
    size_t before = 0;  // bytes of the properties in front of the index list
    size_t after = 0;   // bytes of those behind it (if all are scalars)
    bool otherLists = false;
};

FaceRecord faceRecord(const Layout& layout) {
    FaceRecord r;
    bool behind = false;
    for (const Property& p : layout.face->properties) {
        if (&p == layout.faceIndices) {
            behind = true;
        } else if (p.isList) {
            r.otherLists = true;
        } else {
            (behind ? r.after : r.before) += sizeOf(p.type);
        }
    }
    return r;
}

// Decodes the index list of face `face` whose first index is at `p` into
// `out` (3 * (n - 2) entries); false after reporting a bad index.
template <bool kSwap, Scalar kIndex>
bool decodePolygon(const BinaryBody& body, const Layout& layout, uint64_t face, const char* p,
                   uint64_t n, uint32_t* out, FirstError& firstError) {
    constexpr size_t size = sizeOf(kIndex);
    const uint64_t vertexCount = layout.vertex->count;
    uint32_t first = 0, previous = 0;
    for (uint64_t k = 0; k < n; ++k, p += size) {
        const int64_t index = loadInteger<kSwap>(p, kIndex);  // a switch on a constant
        if (index < 0 || uint64_t(index) >= vertexCount) {
            firstError.offer(face, k, size_t(p - body.data.data()),
                             concat("face ", face, " refers to vertex ", index,
                                    " but there are only ", vertexCount, " vertices"));
            return false;
        }
        const auto v = static_cast<uint32_t>(index);
        // Fan triangulation keeps the polygon's winding (convex polygons only).
        if (k == 0) {
            first = v;
        } else if (k >= 2) {
            *out++ = first;
            *out++ = previous;
            *out++ = v;
        }
        previous = v;
    }
    return true;
}

// Every face has n corners, so records are `stride` bytes. Returns false (and
// leaves mesh.indices as it found them) when a face turns out to differ.
template <bool kSwap, Scalar kIndex>
bool decodeFixedFaces(const BinaryBody& body, size_t offset, const Layout& layout,
                      const FaceRecord& shape, uint64_t n, size_t stride, TriangleMesh& mesh) {
    const Element& e = *layout.face;
    const Property& list = *layout.faceIndices;
    const size_t countSize = sizeOf(list.countType);
    const size_t first = mesh.indices.size();
    const size_t perFace = 3 * size_t(n - 2);
    // count * stride fits in the file (checked by the caller), so this is bounded.
    resizeForDecoding(mesh.indices, first + size_t(e.count) * perFace);

    const char* const records = body.data.data() + offset;
    std::atomic<bool> differs = false;
    FirstError firstError;
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, size_t(e.count), kFaceGrain), [&](const auto& range) {
            for (size_t i = range.begin(); i != range.end(); ++i) {
                const char* count = records + i * stride + shape.before;
                if (loadInteger<kSwap>(count, list.countType) != int64_t(n)) {
                    differs.store(true, std::memory_order_relaxed);
                    return;
                }
                if (!decodePolygon<kSwap, kIndex>(body, layout, i, count + countSize, n,
                                          mesh.indices.data() + first + i * perFace, firstError))
                    return;
            }
        });
    if (differs) {
        mesh.indices.resize(first);
        return false;
    }
    firstError.throwIfAny(body.file);
    return true;
}

struct FaceBlock {
    size_t offset;           // of the block's first face record
    uint64_t firstTriangle;  // triangles of all faces before it
};

// Faces of different sizes: one walk over the records validates the counts
// and finds the blocks; then the blocks decode in parallel.
template <bool kSwap, Scalar kIndex>
std::optional<size_t> decodeVariableFaces(const BinaryBody& body, size_t offset,
                                          const Layout& layout, const FaceRecord& shape,
                                          TriangleMesh& mesh) {
    const Element& e = *layout.face;
    const Property& list = *layout.faceIndices;
    const size_t countSize = sizeOf(list.countType), indexSize = sizeOf(list.type);
    const char* const data = body.data.data();
    const size_t size = body.data.size();

    std::vector<FaceBlock> blocks;
    size_t p = offset;
    uint64_t triangles = 0;
    for (uint64_t i = 0; i < e.count; ++i) {
        if (i % kFacesPerBlock == 0) blocks.push_back({p, triangles});
        if (size - p < shape.before + countSize) return std::nullopt;
        const int64_t n = loadInteger<kSwap>(data + p + shape.before, list.countType);
        if (n < 3) return std::nullopt;
        p += shape.before + countSize;
        if (uint64_t(n) > (size - p) / indexSize) return std::nullopt;
        p += size_t(n) * indexSize;
        if (size - p < shape.after) return std::nullopt;
        p += shape.after;
        triangles += uint64_t(n) - 2;
    }

    const size_t first = mesh.indices.size();
    resizeForDecoding(mesh.indices, first + 3 * size_t(triangles));  // n - 2 < n bytes of the file
    FirstError firstError;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks.size(), 1), [&](const auto& range) {
        for (size_t b = range.begin(); b != range.end(); ++b) {
            const char* record = data + blocks[b].offset;
            uint32_t* out = mesh.indices.data() + first + 3 * blocks[b].firstTriangle;
            const uint64_t begin = b * kFacesPerBlock;
            const uint64_t end = std::min<uint64_t>(e.count, begin + kFacesPerBlock);
            for (uint64_t i = begin; i < end; ++i) {
                const char* count = record + shape.before;
                const auto n = static_cast<uint64_t>(loadInteger<kSwap>(count, list.countType));
                if (!decodePolygon<kSwap, kIndex>(body, layout, i, count + countSize, n, out, firstError))
                    return;
                out += 3 * (n - 2);
                record = count + countSize + n * indexSize + shape.after;
            }
        }
    });
    firstError.throwIfAny(body.file);
    return p;
}

template <bool kSwap, Scalar kIndex>
std::optional<size_t> decodeFacesAs(const BinaryBody& body, size_t offset, const Layout& layout,
                                    TriangleMesh& mesh) {
    const Element& e = *layout.face;
    const FaceRecord shape = faceRecord(layout);
    if (shape.otherLists || !layout.faceAttributes.empty()) return std::nullopt;
    if (e.count == 0) return offset;

    // Try the record size of the first face for all of them.
    const Property& list = *layout.faceIndices;
    const size_t countSize = sizeOf(list.countType), indexSize = sizeOf(list.type);
    const size_t remaining = body.data.size() - offset;
    if (remaining < shape.before + countSize) return std::nullopt;
    const int64_t n = loadInteger<kSwap>(body.data.data() + offset + shape.before, list.countType);
    if (n >= 3 && uint64_t(n) <= remaining / indexSize) {
        const size_t stride = shape.before + countSize + size_t(n) * indexSize + shape.after;
        if (e.count <= remaining / stride &&
            decodeFixedFaces<kSwap, kIndex>(body, offset, layout, shape, uint64_t(n), stride, mesh))
            return offset + size_t(e.count) * stride;
    }
    return decodeVariableFaces<kSwap, kIndex>(body, offset, layout, shape, mesh);
}

}  // namespace

void decodeVertices(const BinaryBody& body, size_t offset, const Layout& layout,
                    TriangleMesh& mesh) {
    bool allFloat = true;
    for (size_t k = 0; k < layout.vertex->properties.size(); ++k) {
        if (layout.vertexRoles[k] != kSkip)
            allFloat = allFloat && layout.vertex->properties[k].type == Scalar::Float32;
    }
    if (body.swapBytes)
        allFloat ? decodeVerticesAs<true, true>(body, offset, layout, mesh)
                 : decodeVerticesAs<true, false>(body, offset, layout, mesh);
    else
        allFloat ? decodeVerticesAs<false, true>(body, offset, layout, mesh)
                 : decodeVerticesAs<false, false>(body, offset, layout, mesh);
}

template <Scalar kIndex>
std::optional<size_t> decodeFacesWith(const BinaryBody& body, size_t offset,
                                      const Layout& layout, TriangleMesh& mesh) {
    return body.swapBytes ? decodeFacesAs<true, kIndex>(body, offset, layout, mesh)
                          : decodeFacesAs<false, kIndex>(body, offset, layout, mesh);
}

std::optional<size_t> decodeFaces(const BinaryBody& body, size_t offset, const Layout& layout,
                                  TriangleMesh& mesh) {
    // The index type as a template argument: the per-index load is then one
    // fixed-size move instead of a switch.
    switch (layout.faceIndices->type) {
        case Scalar::Int8:
            return decodeFacesWith<Scalar::Int8>(body, offset, layout, mesh);
        case Scalar::UInt8:
            return decodeFacesWith<Scalar::UInt8>(body, offset, layout, mesh);
        case Scalar::Int16:
            return decodeFacesWith<Scalar::Int16>(body, offset, layout, mesh);
        case Scalar::UInt16:
            return decodeFacesWith<Scalar::UInt16>(body, offset, layout, mesh);
        case Scalar::Int32:
            return decodeFacesWith<Scalar::Int32>(body, offset, layout, mesh);
        case Scalar::UInt32:
            return decodeFacesWith<Scalar::UInt32>(body, offset, layout, mesh);
        default:
            return std::nullopt;  // not an integer list: ruled out by makeLayout
    }
}

}  // namespace strahl::meshio::ply
