// Mitsuba's .serialized meshes (docs/mesh-files.md, "Mitsuba serialized"): a
// sequence of meshes, each a 4-byte header (format 0x041C, version 3 or 4)
// followed by a zlib stream holding flags, the name (version 4), the vertex
// and triangle counts, positions, optional normals, texture coordinates and
// colours (floats or doubles, by the flags) and uint32 triangle indices; the
// file ends with the byte offset of every mesh (uint64, uint32 in version 3)
// and their count (uint32). Little endian throughout.

#include <zlib.h>

#include <bit>

#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "inflate.h"
#include "strahl/meshio/mapped_file.h"
#include "strahl/core/error.h"
#include "strahl/meshio/mesh_format.h"

namespace strahl {

namespace {

namespace fs = std::filesystem;

constexpr uint16_t kFormat = 0x041C;
constexpr uint32_t kHasNormals = 0x0001, kHasTexcoords = 0x0002, kHasColors = 0x0008,
                   kDouble = 0x2000;

template <typename T>
T readLittle(std::string_view bytes, size_t offset) {
    static_assert(std::endian::native == std::endian::little, "strahl runs on little-endian hosts");
    T value;
    std::memcpy(&value, bytes.data() + offset, sizeof(T));
    return value;
}

// Reads a mesh's uncompressed stream front to back, failing on truncation.
class Reader {
public:
    Reader(std::string_view data, std::string name) : data_(data), name_(std::move(name)) {}

    template <typename T>
    T value(const char* what) {
        need(sizeof(T), what);
        const T v = readLittle<T>(data_, at_);
        at_ += sizeof(T);
        return v;
    }
    std::string cString() {
        const size_t end = data_.find('\0', at_);
        if (end == std::string_view::npos) fail(name_, ": truncated (in the shape's name)");
        std::string s(data_.substr(at_, end - at_));
        at_ = end + 1;
        return s;
    }
    // `count` floats or doubles, as floats.
    std::vector<float> reals(uint64_t count, bool doubles, const char* what) {
        const size_t size = doubles ? 8 : 4;
        if (count > (data_.size() - at_) / size) fail(name_, ": truncated (in the ", what, ")");
        std::vector<float> out(count);
        for (uint64_t i = 0; i < count; ++i)
            out[i] = doubles ? static_cast<float>(readLittle<double>(data_, at_ + i * 8))
                             : readLittle<float>(data_, at_ + i * 4);
        at_ += count * size;
        return out;
    }
    void need(size_t bytes, const char* what) const {
        if (bytes > data_.size() - at_) fail(name_, ": truncated (in the ", what, ")");
    }
    size_t position() const { return at_; }

private:
    std::string_view data_;
    std::string name_;
    size_t at_ = 0;
};

// The byte offset of mesh `index`, from the dictionary at the end of the file.
size_t meshOffset(std::string_view bytes, uint16_t version, uint32_t index, const std::string& name) {
    if (index == 0) return 0;
    if (bytes.size() < 4) fail(name, ": truncated (no mesh dictionary)");
    const uint32_t count = readLittle<uint32_t>(bytes, bytes.size() - 4);
    if (index >= count)
        fail(name, ": shape_index ", index, " is out of range (the file holds ", count, " meshes)");
    const size_t entry = version == 4 ? 8 : 4;
    if (uint64_t(count) * entry + 4 > bytes.size()) fail(name, ": the mesh dictionary is corrupt");
    const size_t at = bytes.size() - 4 - size_t(count - index) * entry;
    const uint64_t offset =
        version == 4 ? readLittle<uint64_t>(bytes, at) : readLittle<uint32_t>(bytes, at);
    // (not offset + 4 > size: a corrupt offset near 2^64 would wrap around)
    if (offset > bytes.size() - 4) fail(name, ": the offset of mesh ", index, " is outside the file");
    return size_t(offset);
}

}  // namespace

LoadedMesh loadSerializedFromMemory(std::string_view bytes, const fs::path& file, uint32_t shapeIndex) {
    const std::string name = file.string();
    if (bytes.size() < 4 || readLittle<uint16_t>(bytes, 0) != kFormat)
        fail(name, ": not a Mitsuba serialized mesh (no 0x041C header)");
    const uint16_t version = readLittle<uint16_t>(bytes, 2);
    if (version != 3 && version != 4)
        fail(name, ": serialized format version ", version, " is not supported (3 and 4 are)");
    const size_t offset = meshOffset(bytes, version, shapeIndex, name);
    if (readLittle<uint16_t>(bytes, offset) != kFormat || readLittle<uint16_t>(bytes, offset + 2) != version)
        fail(name, ": mesh ", shapeIndex, " has no valid header at byte ", offset);
    const std::string data = meshio::inflateAll(bytes.substr(offset + 4), name, meshio::Compression::Zlib);

    Reader in(data, name);
    const uint32_t flags = in.value<uint32_t>("flags");
    if (version == 4) in.cString();  // the shape's name
    const uint64_t vertices = in.value<uint64_t>("vertex count");
    const uint64_t triangles = in.value<uint64_t>("triangle count");
    if (vertices > std::numeric_limits<uint32_t>::max() || triangles > std::numeric_limits<uint32_t>::max())
        fail(name, ": ", vertices, " vertices and ", triangles, " triangles: more than strahl's 32-bit indices hold");
    const bool doubles = (flags & kDouble) != 0;

    LoadedMesh result;
    TriangleMesh& mesh = result.mesh;
    const auto vec3s = [&](const char* what) {
        const std::vector<float> v = in.reals(3 * vertices, doubles, what);
        std::vector<Vec3> out(vertices);
        for (uint64_t i = 0; i < vertices; ++i) out[i] = Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        return out;
    };
    mesh.positions = vec3s("positions");
    mesh.reservePadding();
    if (flags & kHasNormals) mesh.normals = vec3s("normals");
    if (flags & kHasTexcoords) {
        const std::vector<float> uv = in.reals(2 * vertices, doubles, "texture coordinates");
        mesh.uvs.resize(vertices);
        // Mitsuba's v runs down the image; strahl's up (docs/mitsuba.md).
        for (uint64_t i = 0; i < vertices; ++i) mesh.uvs[i] = Vec2(uv[2 * i], 1.0f - uv[2 * i + 1]);
    }
    if (flags & kHasColors) in.reals(3 * vertices, doubles, "vertex colours");  // not used
    in.need(12 * triangles, "triangle indices");
    mesh.indices.resize(3 * triangles);
    if (triangles > 0)  // (an empty vector's data() may be null, which memcpy must not see)
        std::memcpy(mesh.indices.data(), data.data() + in.position(), 12 * triangles);
    mesh.validate(name);
    return result;
}

LoadedMesh loadSerialized(const fs::path& file, uint32_t shapeIndex) {
    const meshio::MappedFile mapping(file);
    return loadSerializedFromMemory(mapping.bytes(), file, shapeIndex);
}

namespace {
constexpr std::string_view kSerializedExtensions[] = {".serialized"};
LoadedMesh loadFirst(const fs::path& file) { return loadSerialized(file, 0); }
LoadedMesh loadFirstFromMemory(std::string_view data, const fs::path& file) {
    return loadSerializedFromMemory(data, file, 0);
}
}  // namespace

extern const MeshFormat kSerializedFormat{"Mitsuba serialized", kSerializedExtensions, &loadFirst,
                                          &loadFirstFromMemory};

}  // namespace strahl
