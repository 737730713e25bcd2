// Wavefront OBJ loader with its .mtl material libraries (mtl_reader.h). The
// text is cut into chunks at line ends and the chunks are parsed in parallel
// (obj_chunks.h); then, in file order, this file joins them: .mtl libraries are
// read and warnings given where their statements are, each face's material
// slot follows the usemtl statements before it, and every corner gets its
// output vertex from one table of distinct (v, vt, vn) triples, so vertices are
// numbered as a line-by-line reader would number them. The result and the
// first error are the same for any chunk size and thread count. What is and is
// not supported: docs/mesh-formats.md; the .mtl keys: docs/mesh-files.md.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>
#include <set>
#include <unordered_map>
#include <utility>

#include "loader_tuning.h"
#include "strahl/meshio/mapped_file.h"
#include "mtl_reader.h"
#include "obj_chunks.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/meshio/mesh_format.h"
#include "text_scan.h"

namespace fs = std::filesystem;

namespace strahl {

namespace {

using meshio::LineScanner;
using meshio::obj::Chunk;
using meshio::obj::Corner;
using meshio::obj::kNone;

// Chunks of 1 MiB: a 30 MB OBJ makes 30 tasks, enough to keep 2-16 threads
// busy to the end, while each chunk's arrays and its task cost next to nothing
// against the ~5 ms it takes to parse.
constexpr size_t kChunkBytes = size_t(1) << 20;

// The distinct corners, each of which becomes one output vertex. Corners are
// chained per position index: few corners share a position, so a lookup walks
// a short list and needs no hashing.
struct CornerTable {
    std::vector<Corner> corners;
    std::vector<uint32_t> next;  // next corner with the same position
    std::vector<uint32_t> head;  // first corner of each position

    uint32_t insert(const Corner& c) {
        if (c.v >= head.size()) head.resize(size_t(c.v) + 1, kNone);
        for (uint32_t e = head[c.v]; e != kNone; e = next[e]) {
            if (corners[e].vt == c.vt && corners[e].vn == c.vn) return e;
        }
        const auto e = static_cast<uint32_t>(corners.size());
        corners.push_back(c);
        next.push_back(head[c.v]);
        head[c.v] = e;
        return e;
    }
};

class ObjReader {
public:
    explicit ObjReader(const fs::path& file) : path_(file), name_(file.string()) {}

    LoadedMesh read(std::string_view text, size_t chunkBytes) {
        std::vector<Chunk> chunks = meshio::obj::splitIntoChunks(text, chunkBytes);
        // Pass 1 counts v/vt/vn per chunk; their running sums are what relative
        // indices in each chunk are resolved against in pass 2.
        tbb::parallel_for(size_t(0), chunks.size(),
                          [&](size_t i) { meshio::obj::countStatements(chunks[i]); });
        for (size_t i = 1; i < chunks.size(); ++i) {
            const Chunk& previous = chunks[i - 1];
            chunks[i].firstLine = previous.firstLine + previous.lines;
            chunks[i].before = {previous.before.v + previous.own.v,
                                previous.before.vt + previous.own.vt,
                                previous.before.vn + previous.own.vn};
        }
        if (!chunks.empty()) {
            const Chunk& last = chunks.back();
            attributes_.positions.resize(last.before.v + last.own.v);
            attributes_.texcoords.resize(last.before.vt + last.own.vt);
            attributes_.normals.resize(last.before.vn + last.own.vn);
        }
        tbb::parallel_for(size_t(0), chunks.size(), [&](size_t i) {
            meshio::obj::parseChunk(name_, chunks[i], attributes_);
        });
        reserve(chunks);
        for (const Chunk& chunk : chunks) join(chunk);
        return finish();
    }

private:
    struct Slot {
        std::string name;  // empty: faces before any usemtl
        size_t line = 0;   // first usemtl naming it, for warnings
    };

    void reserve(const std::vector<Chunk>& chunks) {
        size_t corners = 0;
        for (const Chunk& c : chunks) corners += c.corners.size();
        const size_t v = attributes_.positions.size();
        table_.head.assign(v, kNone);
        // Most files have one corner per position (distinct corners may be fewer,
        // or more when positions carry several uvs or normals).
        table_.corners.reserve(std::min(corners, v));
        table_.next.reserve(std::min(corners, v));
    }

    // Adds one parsed chunk, in file order, doing what depends on everything
    // before it; rethrows its error after its earlier statements took effect.
    void join(const Chunk& chunk) {
        for (const meshio::obj::Deferred& d : chunk.deferred) {
            if (d.kind == meshio::obj::Deferred::Kind::MaterialLibrary) {
                LineScanner s{name_, d.line, d.text.data(), d.text.data() + d.text.size()};
                materialLibraries(s);
            } else if (ignoredKeywords_.insert(std::string(d.text)).second) {
                meshio::warn(concat(name_, ':', d.line, ": ignoring unsupported statement '",
                                    d.text, "' (reported once)"));
            }
        }
        if (chunk.error) std::rethrow_exception(chunk.error);

        cornerWithUv_ |= chunk.cornerWithUv;
        cornerWithoutUv_ |= chunk.cornerWithoutUv;
        cornerWithNormal_ |= chunk.cornerWithNormal;
        cornerWithoutNormal_ |= chunk.cornerWithoutNormal;

        uint32_t use = 0;  // usemtl statements of this chunk in effect
        const Corner* corner = chunk.corners.data();
        for (size_t f = 0; f < chunk.faceSizes.size(); ++f) {
            if (chunk.faceUse[f] != use) {
                use = chunk.faceUse[f];
                useMaterial(chunk.usemtl[use - 1]);
            }
            polygon_.clear();
            for (uint32_t k = 0; k < chunk.faceSizes[f]; ++k) {
                if (table_.corners.size() == kNone)
                    fail(name_, ':', meshio::obj::lineOfFace(name_, chunk, f),
                         ": more than 2^32-1 distinct vertices");
                polygon_.push_back(table_.insert(*corner++));
            }
            if (currentSlot_ == kNone) currentSlot_ = slot(currentName_, currentLine_);
            // Fan triangulation keeps the polygon's winding (convex polygons only).
            for (size_t i = 1; i + 1 < polygon_.size(); ++i) {
                indices_.insert(indices_.end(), {polygon_[0], polygon_[i], polygon_[i + 1]});
                faceSlots_.push_back(currentSlot_);
            }
        }
        // A usemtl after the chunk's last face still holds for the next chunk.
        if (!chunk.usemtl.empty() && use != chunk.usemtl.size()) useMaterial(chunk.usemtl.back());
    }

    void useMaterial(const meshio::obj::UseMaterial& u) {
        currentName_ = u.name;
        currentLine_ = u.line;
        currentSlot_ = kNone;
    }

    uint32_t slot(const std::string& material, size_t line) {
        const auto [it, inserted] =
            slotByName_.try_emplace(material, static_cast<uint32_t>(slots_.size()));
        if (inserted) slots_.push_back({material, line});
        return it->second;
    }

    void materialLibraries(LineScanner& s) {
        const fs::path dir = path_.parent_path();
        const std::string_view rest = s.rest();
        // One name with spaces, or several names separated by blanks.
        std::vector<std::string> names;
        if (!findFileCaseInsensitive(dir, std::string(rest)).empty()) {
            names.emplace_back(rest);
        } else {
            LineScanner words{s.file, s.line, rest.data(), rest.data() + rest.size()};
            for (std::string_view w = words.token(); !w.empty(); w = words.token())
                names.emplace_back(w);
        }
        if (names.empty()) s.error("mtllib without a file name");
        for (const std::string& libraryName : names) {
            const fs::path file = findFileCaseInsensitive(dir, libraryName);
            if (file.empty()) {
                meshio::warn(concat(name_, ':', s.line, ": material library '", libraryName,
                                    "' not found; its materials get default values"));
            } else if (loadedLibraries_.insert(file).second) {
                meshio::readMaterialLibrary(file, library_);
            }
        }
    }

    std::vector<MeshMaterial> materials() const {
        std::vector<MeshMaterial> result;
        for (const Slot& s : slots_) {
            const auto it = library_.find(s.name);
            if (it != library_.end()) {
                result.push_back(it->second);
                continue;
            }
            if (!s.name.empty())
                meshio::warn(concat(name_, ':', s.line, ": unknown material '", s.name,
                                    "'; using a default material (diffuse 0.8)"));
            result.emplace_back().name = s.name;
        }
        return result;
    }

    LoadedMesh finish() {
        // An attribute only some corners carry cannot be per-vertex: drop it for
        // the whole mesh and merge the corners that differed only in it.
        const bool keepUvs = cornerWithUv_ && !cornerWithoutUv_;
        const bool keepNormals = cornerWithNormal_ && !cornerWithoutNormal_;
        if (cornerWithUv_ && !keepUvs)
            meshio::warn(name_ +
                         ": only some face corners have texture coordinates; "
                         "ignoring texture coordinates for the whole mesh");
        if (cornerWithNormal_ && !keepNormals)
            meshio::warn(name_ +
                         ": only some face corners have normals; "
                         "ignoring normals for the whole mesh");
        if ((cornerWithUv_ && !keepUvs) || (cornerWithNormal_ && !keepNormals)) {
            CornerTable merged;
            std::vector<uint32_t> remap(table_.corners.size());
            for (size_t i = 0; i < remap.size(); ++i) {
                Corner c = table_.corners[i];
                if (!keepUvs) c.vt = kNone;
                if (!keepNormals) c.vn = kNone;
                remap[i] = merged.insert(c);
            }
            for (uint32_t& i : indices_) i = remap[i];
            table_ = std::move(merged);
        }

        LoadedMesh result;
        TriangleMesh& mesh = result.mesh;
        const size_t n = table_.corners.size();
        mesh.positions.reserve(n + 1);  // the spare element Embree's 16-byte loads need
        if (keepUvs) mesh.uvs.reserve(n);
        if (keepNormals) mesh.normals.reserve(n);
        for (const Corner& c : table_.corners) {
            mesh.positions.push_back(attributes_.positions[c.v]);
            if (keepUvs) mesh.uvs.push_back(attributes_.texcoords[c.vt]);
            if (keepNormals) mesh.normals.push_back(attributes_.normals[c.vn]);
        }
        mesh.indices = std::move(indices_);
        // Only the implicit default slot in use: the file assigns no materials.
        const bool anyMaterial =
            slots_.size() > 1 || (slots_.size() == 1 && !slots_[0].name.empty());
        if (anyMaterial) {
            mesh.faceMaterials = std::move(faceSlots_);
            result.materials = materials();
        }
        mesh.validate(name_);
        return result;
    }

    fs::path path_;
    std::string name_;

    meshio::obj::Attributes attributes_;  // every v, vt, vn of the file
    CornerTable table_;
    std::vector<uint32_t> indices_;
    std::vector<uint32_t> faceSlots_;
    std::vector<uint32_t> polygon_;  // corners of the face being joined
    bool cornerWithUv_ = false;
    bool cornerWithoutUv_ = false;
    bool cornerWithNormal_ = false;
    bool cornerWithoutNormal_ = false;

    // Materials: a usemtl only takes a slot once a face uses it.
    std::string currentName_;
    size_t currentLine_ = 0;
    uint32_t currentSlot_ = kNone;
    std::vector<Slot> slots_;
    std::unordered_map<std::string, uint32_t> slotByName_;
    meshio::MaterialLibrary library_;
    std::set<fs::path> loadedLibraries_;
    std::set<std::string> ignoredKeywords_;
};

}  // namespace

namespace meshio {

LoadedMesh decodeObj(std::string_view data, const fs::path& file, size_t chunkBytes) {
    return ObjReader(file).read(data, chunkBytes);
}

}  // namespace meshio

LoadedMesh loadObj(const fs::path& file) {
    const meshio::MappedFile mapping(file);
    return meshio::decodeObj(mapping.bytes(), file, kChunkBytes);
}

LoadedMesh loadObjFromMemory(std::string_view data, const fs::path& file) {
    return meshio::decodeObj(data, file, kChunkBytes);
}

namespace {
constexpr std::string_view kObjExtensions[] = {".obj"};
}  // namespace

extern const MeshFormat kObjFormat{"OBJ", kObjExtensions, &loadObj, &loadObjFromMemory};

}  // namespace strahl
