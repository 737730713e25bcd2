// glTF 2.0 loader: .gltf (external or data-URI buffers) and binary .glb. tinygltf
// 2.7 (Debian's header-only libtinygltf-dev, its implementation compiled here)
// parses the JSON and loads the buffers; everything it does not check (indices
// into arrays, accessor ranges, node cycles) is checked here before any data is
// read, and the default scene is flattened into one world-space TriangleMesh.
// Supported features, the uv convention and the errors: docs/mesh-files.md.

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "strahl/core/hash.h"
#include "strahl/meshio/gltf_camera.h"
#include "strahl/meshio/mesh_file.h"
#include "text_scan.h"

// Textures are read later by OpenImageIO from their paths, so tinygltf neither
// decodes images (no stb_image) nor reads external image files. Included last:
// it declares nlohmann::json with hidden visibility, which must not be the
// first declaration of anything else (getpid would become hidden).
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

namespace fs = std::filesystem;

namespace strahl {

namespace {

static_assert(std::endian::native == std::endian::little,
              "glTF buffers are little-endian and are read in place");

// Extensions whose data the loader reads; any other one listed in
// extensionsRequired is an error, in extensionsUsed a warning.
constexpr std::string_view kSupportedExtensions[] = {
    "KHR_materials_emissive_strength", "KHR_materials_ior", "KHR_materials_transmission"};

constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kGlbBinChunk = 0x004E4942;   // "BIN\0"
constexpr size_t kGlbHeaderBytes = 12;          // magic, version, length
constexpr size_t kGlbChunkHeaderBytes = 8;      // length, type

std::string componentTypeName(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return "byte";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return "unsigned byte";
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return "short";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return "unsigned short";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return "unsigned int";
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return "float";
        default:
            return concat("component type ", type);
    }
}

std::string typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
        default:
            return concat("type ", type);
    }
}

size_t componentBytes(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;
    }
}

// Only the accessor types the loader reads (SCALAR, VEC2, VEC3).
size_t componentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return 1;
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        default:
            return 0;
    }
}

// One component as a number: floats as they are, normalized integers mapped
// onto [0, 1] (unsigned) or [-1, 1] (signed) as the glTF specification says,
// other integers as their value.
double readComponent(const unsigned char* p, int componentType, bool normalized) {
    const auto load = [p]<typename T>(T) {
        T value;
        std::memcpy(&value, p, sizeof value);
        return value;
    };
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return double(load(float{}));
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return double(load(uint32_t{}));
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const double v = load(uint8_t{});
            return normalized ? v / 255.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const double v = load(uint16_t{});
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const double v = load(int8_t{});
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const double v = load(int16_t{});
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        default:
            return 0.0;  // excluded by checkAccessor
    }
}

uint32_t readLe32(std::string_view bytes, size_t offset) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + offset, sizeof value);
    return value;
}

// RFC 3986 percent-decoding of a URI path ("my%20file.png"); a '%' not
// followed by two hex digits is kept as it is.
std::string percentDecode(std::string_view uri) {
    const auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    std::string out;
    out.reserve(uri.size());
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size()) {
            const int hi = hex(uri[i + 1]), lo = hex(uri[i + 2]);
            if (hi >= 0 && lo >= 0) {
                out += static_cast<char>(hi * 16 + lo);
                i += 2;
                continue;
            }
        }
        out += uri[i];
    }
    return out;
}

std::string hex64(uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

// File extension for encoded image bytes: the content decides, the declared MIME
// type only when the content is not recognised. Empty: not a format strahl reads.
std::string imageExtension(const unsigned char* bytes, size_t size, const std::string& mime) {
    static constexpr unsigned char kPng[] = {0x89, 'P', 'N', 'G'};
    static constexpr unsigned char kJpeg[] = {0xFF, 0xD8, 0xFF};
    if (size >= sizeof kPng && std::memcmp(bytes, kPng, sizeof kPng) == 0) return ".png";
    if (size >= sizeof kJpeg && std::memcmp(bytes, kJpeg, sizeof kJpeg) == 0) return ".jpg";
    if (mime == "image/png") return ".png";
    if (mime == "image/jpeg") return ".jpg";
    return {};
}

// tinygltf's image callback. Data-URI images arrive decoded from base64 and are
// kept as they are (still PNG/JPEG bytes). Images in buffer views are left
// alone: tinygltf hands them over without checking the view against its
// buffer, so the reader extracts them itself after checking.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
    if (image->bufferView < 0 && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

// tinygltf looks for external buffers in the glTF's folder (given as an absolute
// path) and then in the working directory; refusing relative paths drops the
// second guess.
bool fileExistsInGltfFolder(const std::string& path, void* userData) {
    return fs::path(path).is_absolute() && tinygltf::FileExists(path, userData);
}

// tinygltf's messages end in '\n' and may be several: join them into one line.
// Each is cut at 200 characters, as some quote a whole base64 data URI.
std::string oneLine(const std::string& text) {
    constexpr size_t kMaxLine = 200;
    std::string out;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string_view line = meshio::trimBlanks({text.data() + start, end - start});
        if (!line.empty()) {
            if (!out.empty()) out += "; ";
            out += line.substr(0, kMaxLine);
            if (line.size() > kMaxLine) out += "...";
        }
        start = end + 1;
    }
    return out;
}

// One accessor checked against its buffer view and buffer: element i starts at
// data + i * stride (data is nullptr without a buffer view: all zeros), and the
// sparse substitution, if any, is in range.
struct CheckedAccessor {
    int index = -1;       // -1: the attribute is absent
    std::string subject;  // "meshes[0].primitives[1]: NORMAL accessor 4", for errors
    const tinygltf::Accessor* accessor = nullptr;
    size_t count = 0;
    size_t components = 0;
    size_t elementBytes = 0;
    const unsigned char* data = nullptr;
    size_t stride = 0;
    // Sparse substitution: `sparseCount` indices (u8/u16/u32) and values, packed.
    size_t sparseCount = 0;
    const unsigned char* sparseIndices = nullptr;
    int sparseIndexType = 0;
    const unsigned char* sparseValues = nullptr;

    bool present() const { return index >= 0; }
};

// The component types an attribute may have: {componentType, normalized}.
struct ComponentRule {
    int componentType;
    bool normalized;
};

// One primitive of one node, checked and ready to be appended.
struct PrimitiveJob {
    std::string place;  // "meshes[m].primitives[p]"
    glm::dmat4 world;
    CheckedAccessor positions, normals, uvs, indices;
    uint32_t material = 0;
    size_t indexCount = 0;
};

class GltfReader {
public:
    explicit GltfReader(const fs::path& file) : path_(file), name_(file.string()) {}

    LoadedMesh read(std::string_view bytes) {
        parse(bytes);
        checkExtensions();
        LoadedMesh result;
        convertMaterials(result.materials);
        std::vector<PrimitiveJob> jobs;
        checkNodeGraph();
        for (const auto& [node, world] : sceneNodes())
            if (model_.nodes[node].mesh >= 0) addJobs(node, world, jobs);
        if (usesDefaultMaterial_) {
            MeshMaterial fallback = gltfDefaults();
            fallback.name = "default";
            result.materials.push_back(fallback);
        }
        build(jobs, result.mesh);
        result.mesh.validate(name_);
        return result;
    }

    std::vector<GltfCamera> readCameras(std::string_view bytes) {
        parse(bytes);
        checkExtensions();
        checkNodeGraph();
        std::vector<GltfCamera> cameras;
        for (const auto& [node, world] : sceneNodes()) {
            const tinygltf::Node& n = model_.nodes[node];
            if (n.camera < 0) continue;
            const std::string place = concat("nodes[", node, "]");
            if (size_t(n.camera) >= model_.cameras.size())
                error(place, ": camera ", n.camera, " does not exist (", model_.cameras.size(),
                      " cameras)");
            cameras.push_back(convertCamera(size_t(n.camera), n, world, cameras.size()));
        }
        return cameras;
    }

private:
    GltfCamera convertCamera(size_t index, const tinygltf::Node& node, const glm::dmat4& world,
                             size_t placed) const {
        const tinygltf::Camera& c = model_.cameras[index];
        const std::string place = concat("cameras[", index, "]: ");
        GltfCamera out;
        out.name = !c.name.empty()      ? c.name
                   : !node.name.empty() ? node.name
                                        : concat("camera ", placed);
        const glm::dvec3 back = glm::dvec3(world * glm::dvec4(0, 0, 1, 0));
        const glm::dvec3 up = glm::dvec3(world * glm::dvec4(0, 1, 0, 0));
        const glm::dvec3 eye = glm::dvec3(world * glm::dvec4(0, 0, 0, 1));
        // A scale of (nearly) zero or a shear that folds +y onto +z leaves no frame.
        const double backLength = glm::length(back), upLength = glm::length(up);
        if (!(backLength > 1e-12 && upLength > 1e-12) ||
            glm::length(glm::cross(back / backLength, up / upLength)) < 1e-6 ||
            !std::isfinite(eye.x + eye.y + eye.z))
            error(place, "the transform of the node placing it leaves no camera frame");
        out.eye = Vec3(eye);
        out.back = Vec3(back / backLength);
        out.up = Vec3(up / upLength);
        if (c.type == "perspective") {
            const double yfov = c.perspective.yfov;
            if (!(yfov > 0.0 && yfov < glm::pi<double>()))
                error(place, "perspective.yfov ", yfov, " is not in (0, pi)");
            out.yfovDegrees = float(glm::degrees(yfov));
        } else if (c.type == "orthographic") {
            out.orthographic = true;
            out.xmag = float(std::abs(c.orthographic.xmag));
            out.ymag = float(std::abs(c.orthographic.ymag));
            if (!(out.xmag > 0.0f && out.ymag > 0.0f && std::isfinite(out.xmag) &&
                  std::isfinite(out.ymag)))
                error(place, "orthographic.xmag and ymag must not be zero");
        } else {
            error(place, "type '", c.type, "' is neither perspective nor orthographic");
        }
        return out;
    }

    // Runs a tinygltf call. tinygltf 2.7 throws for some inputs instead of
    // failing (std::out_of_range for a .glb whose BIN chunk is longer than a
    // zero-length buffer, say): that becomes a strahl::Error naming the file.
    template <typename Call>
    bool guarded(Call&& call) const {
        try {
            return call();
        } catch (const Error&) {
            throw;
        } catch (const std::exception& e) {
            error("tinygltf could not read the file: ", e.what());
        }
    }

    // "file: <args>"; the arguments start with the place ("meshes[0].primitives[1]: ").
    template <typename... Args>
    [[noreturn]] void error(const Args&... args) const {
        fail(name_, ": ", args...);
    }

    void warnOnce(const std::string& key, const std::string& message) {
        if (warned_.insert(key).second) meshio::warn(name_ + ": " + message);
    }

    // ---------------------------------------------------------------- parsing

    void parse(std::string_view bytes) {
        std::error_code ec;
        const fs::path absolute = fs::weakly_canonical(fs::absolute(path_, ec), ec);
        const std::string absoluteName = ec ? name_ : absolute.string();
        fileHash_ = fnv1a(absoluteName.data(), absoluteName.size());
        const fs::path folder = ec ? path_.parent_path() : absolute.parent_path();
        folder_ = path_.parent_path();

        tinygltf::TinyGLTF loader;
        loader.SetImageLoader(&keepEncodedImage, nullptr);
        loader.SetFsCallbacks({&fileExistsInGltfFolder, &tinygltf::ExpandFilePath,
                               &tinygltf::ReadWholeFile, &tinygltf::WriteWholeFile, nullptr});
        std::string err, warn;
        bool ok = false;
        const bool binary = bytes.size() >= 4 && readLe32(bytes, 0) == kGlbMagic;
        if (binary) {
            const uint32_t length = checkGlbLayout(bytes);
            checkImageViewsStartInTheirBuffers(
                bytes.substr(kGlbHeaderBytes + kGlbChunkHeaderBytes, readLe32(bytes, 12)));
            ok = guarded([&] {
                return loader.LoadBinaryFromMemory(
                    &model_, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                    length, folder.string());
            });
        } else {
            if (bytes.size() > std::numeric_limits<unsigned int>::max())
                fail(name_, ": ", bytes.size(),
                     " bytes of JSON is more than tinygltf reads (4 GiB)");
            checkImageViewsStartInTheirBuffers(bytes);
            ok = guarded([&] {
                return loader.LoadASCIIFromString(&model_, &err, &warn, bytes.data(),
                                                  static_cast<unsigned int>(bytes.size()),
                                                  folder.string());
            });
        }
        if (!ok) fail(name_, ": ", err.empty() ? "cannot parse the glTF" : oneLine(err));
        // Messages tinygltf reports without failing are warnings.
        for (const std::string* text : {&warn, &err}) {
            if (!text->empty()) meshio::warn(name_ + ": " + oneLine(*text));
        }
    }

    // tinygltf 2.7 hands an image stored in a buffer view to the image loader as
    // &buffer.data[view.byteOffset] before anything checks the view against its
    // buffer: for a view starting at or past the buffer's end, an out-of-range
    // vector index — undefined behaviour (found by the sanitizer build's
    // _GLIBCXX_ASSERTIONS on a mutated .glb), though nothing reads there
    // (keepEncodedImage ignores the bytes; checkedView rejects the view later).
    // So such a file is refused before tinygltf sees it, with checkedView's
    // message. The JSON is read as tinygltf reads it (indices: integers cut to
    // int; byteOffset: only if unsigned, else 0; a loaded buffer's data is
    // exactly its byteLength); anything else wrong is left to tinygltf.
    void checkImageViewsStartInTheirBuffers(std::string_view text) const {
        using nlohmann::json;
        const json doc = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
        const auto member = [](const json& object, const char* key) -> const json* {
            if (!object.is_object()) return nullptr;
            const auto it = object.find(key);
            return it == object.end() ? nullptr : &*it;
        };
        const auto unsignedOr = [](const json* value, uint64_t otherwise) {
            return value && value->is_number_unsigned() ? value->get<uint64_t>() : otherwise;
        };
        const auto element = [&](const char* array, const json* index, int& i) -> const json* {
            const json* items = member(doc, array);
            if (!items || !items->is_array() || !index || !index->is_number_integer())
                return nullptr;
            i = static_cast<int>(index->get<int64_t>());
            return i >= 0 && size_t(i) < items->size() ? &(*items)[size_t(i)] : nullptr;
        };
        const json* images = member(doc, "images");
        if (!images || !images->is_array()) return;
        for (size_t i = 0; i < images->size(); ++i) {
            int view = -1, buffer = -1;
            const json* v = element("bufferViews", member((*images)[i], "bufferView"), view);
            const json* b = v ? element("buffers", member(*v, "buffer"), buffer) : nullptr;
            const json* bufferLength = b ? member(*b, "byteLength") : nullptr;
            if (!bufferLength || !bufferLength->is_number_unsigned()) continue;
            const uint64_t offset = unsignedOr(member(*v, "byteOffset"), 0);
            if (offset >= bufferLength->get<uint64_t>())
                error("images[", i, "]: buffer view ", view, " (",
                      unsignedOr(member(*v, "byteLength"), 0), " bytes from offset ", offset,
                      ") reads past the end of buffer ", buffer, " (",
                      bufferLength->get<uint64_t>(), " bytes)");
        }
    }

    // Checks the GLB header and chunk headers (tinygltf's own messages do not say
    // what is missing) and returns the length the header announces.
    uint32_t checkGlbLayout(std::string_view bytes) const {
        const auto place = [&](size_t offset) {
            return concat(name_, ": byte offset ", offset, ": ");
        };
        if (bytes.size() < kGlbHeaderBytes)
            fail(name_, ": truncated .glb: ", bytes.size(), " bytes, the header alone needs 12");
        const uint32_t version = readLe32(bytes, 4);
        if (version != 2) fail(place(4), "GLB version ", version, " (only version 2 is supported)");
        const uint32_t length = readLe32(bytes, 8);
        if (length > bytes.size())
            fail(name_, ": truncated .glb: the header announces ", length, " bytes, the file has ",
                 bytes.size());
        if (length < kGlbHeaderBytes + kGlbChunkHeaderBytes)
            fail(place(kGlbHeaderBytes), "the .glb has no JSON chunk");
        const uint32_t jsonLength = readLe32(bytes, 12);
        if (readLe32(bytes, 16) != kGlbJsonChunk)
            fail(place(16), "the first chunk of a .glb must be JSON");
        const uint64_t jsonEnd = uint64_t(kGlbHeaderBytes + kGlbChunkHeaderBytes) + jsonLength;
        if (jsonEnd > length)
            fail(place(12), "truncated .glb: the JSON chunk announces ", jsonLength,
                 " bytes, only ", length - kGlbHeaderBytes - kGlbChunkHeaderBytes, " follow");
        if (jsonEnd < length) {
            const size_t bin = static_cast<size_t>(jsonEnd);
            if (bin + kGlbChunkHeaderBytes > length)
                fail(place(bin), "truncated .glb: incomplete chunk header");
            const uint32_t binLength = readLe32(bytes, bin);
            if (readLe32(bytes, bin + 4) != kGlbBinChunk)
                fail(place(bin + 4), "the second chunk of a .glb must be BIN");
            if (uint64_t(bin) + kGlbChunkHeaderBytes + binLength > length)
                fail(place(bin), "truncated .glb: the BIN chunk announces ", binLength,
                     " bytes, only ", length - bin - kGlbChunkHeaderBytes, " follow");
        }
        return length;
    }

    void checkExtensions() {
        const auto supported = [](const std::string& name) {
            return std::find(std::begin(kSupportedExtensions), std::end(kSupportedExtensions),
                             name) != std::end(kSupportedExtensions);
        };
        for (const std::string& name : model_.extensionsRequired) {
            if (!supported(name))
                fail(name_, ": requires the glTF extension '", name,
                     "', which strahl does not support");
        }
        std::string ignored;
        for (const std::string& name : model_.extensionsUsed) {
            if (!supported(name)) ignored += (ignored.empty() ? "" : ", ") + name;
        }
        if (!ignored.empty()) meshio::warn(name_ + ": ignoring the glTF extensions " + ignored);
    }

    // ---------------------------------------------------------------- buffers

    size_t totalBufferBytes() const {
        size_t total = 0;
        for (const tinygltf::Buffer& b : model_.buffers) total += b.data.size();
        return total;
    }

    // Buffer view `view` checked against its buffer; returns its first byte.
    const unsigned char* checkedView(int view, const std::string& place) const {
        if (view < 0 || size_t(view) >= model_.bufferViews.size())
            error(place, ": buffer view ", view, " does not exist (", model_.bufferViews.size(),
                  " buffer views)");
        const tinygltf::BufferView& v = model_.bufferViews[size_t(view)];
        if (v.buffer < 0 || size_t(v.buffer) >= model_.buffers.size())
            error(place, ": buffer view ", view, " refers to buffer ", v.buffer,
                  ", which does not exist (", model_.buffers.size(), " buffers)");
        const std::vector<unsigned char>& data = model_.buffers[size_t(v.buffer)].data;
        if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
            error(place, ": buffer view ", view, " (", v.byteLength, " bytes from offset ",
                  v.byteOffset, ") reads past the end of buffer ", v.buffer, " (", data.size(),
                  " bytes)");
        return data.data() + v.byteOffset;
    }

    // `bytes` bytes from `offset` of buffer view `view`, or an error naming `what`.
    const unsigned char* viewRange(int view, size_t offset, size_t bytes, const std::string& place,
                                   const std::string& what) const {
        const unsigned char* start = checkedView(view, place);
        const size_t length = model_.bufferViews[size_t(view)].byteLength;
        if (offset > length || bytes > length - offset)
            error(place, ": ", what, " reads past the end of buffer view ", view, " (", bytes,
                  " bytes from offset ", offset, ", the view has ", length, ")");
        return start + offset;
    }

    // Accessor `index` as the `role` ("POSITION", "indices") of the primitive at
    // `place`, checked for its type, component type, buffer view and range.
    CheckedAccessor checkAccessor(int index, const std::string& place, const std::string& role,
                                  std::initializer_list<int> types,
                                  std::initializer_list<ComponentRule> rules) const {
        if (index < 0 || size_t(index) >= model_.accessors.size())
            error(place, ": ", role, " accessor ", index, " does not exist (",
                  model_.accessors.size(), " accessors)");
        const tinygltf::Accessor& a = model_.accessors[size_t(index)];
        CheckedAccessor c;
        c.index = index;
        c.subject = concat(place, ": ", role, " accessor ", index);
        if (std::find(types.begin(), types.end(), a.type) == types.end()) {
            std::string expected;
            for (int t : types) expected += (expected.empty() ? "" : " or ") + typeName(t);
            error(c.subject, " is ", typeName(a.type), ", expected ", expected);
        }
        bool allowed = false;
        for (const ComponentRule& r : rules)
            allowed =
                allowed || (a.componentType == r.componentType && a.normalized == r.normalized);
        if (!allowed) {
            std::string expected;
            for (const ComponentRule& r : rules)
                expected +=
                    concat(expected.empty() ? "" : " or ", r.normalized ? "normalized " : "",
                           componentTypeName(r.componentType));
            error(c.subject, " holds ", a.normalized ? "normalized " : "",
                  componentTypeName(a.componentType), " values, expected ", expected);
        }

        c.accessor = &a;
        c.count = a.count;
        c.components = componentCount(a.type);
        c.elementBytes = c.components * componentBytes(a.componentType);
        if (a.bufferView >= 0) {
            const unsigned char* start = checkedView(a.bufferView, c.subject);
            const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
            c.stride = view.byteStride != 0 ? view.byteStride : c.elementBytes;
            if (c.stride < c.elementBytes)
                error(c.subject, ": buffer view ", a.bufferView, " has byteStride ",
                      view.byteStride, ", less than its ", c.elementBytes, "-byte elements");
            // The last element must end inside the view. Computed without overflow,
            // so an absurd count fails here, before anything is allocated.
            const size_t length = view.byteLength;
            const bool fits = c.count == 0 ||
                              (a.byteOffset <= length && length - a.byteOffset >= c.elementBytes &&
                               c.count - 1 <= (length - a.byteOffset - c.elementBytes) / c.stride);
            if (!fits)
                error(c.subject, " reads past the end of buffer view ", a.bufferView, " (", c.count,
                      " elements of ", c.elementBytes, " bytes, stride ", c.stride,
                      ", from offset ", a.byteOffset, "; the view has ", length, " bytes)");
            c.data = start + a.byteOffset;
        } else if (c.count > totalBufferBytes() / c.elementBytes) {
            // Without a buffer view the elements are zeros (plus sparse values), so
            // no data bounds the count: one larger than all the file's bytes is a lie.
            error(c.subject, " has no buffer view and claims ", c.count,
                  " elements, more than all buffers of the file hold (", totalBufferBytes(),
                  " bytes)");
        }
        if (a.sparse.isSparse) checkSparse(c);
        return c;
    }

    void checkSparse(CheckedAccessor& c) const {
        const auto& s = c.accessor->sparse;
        if (s.count < 1 || size_t(s.count) > c.count)
            error(c.subject, ": sparse count ", s.count, " is not in 1..", c.count);
        const size_t n = size_t(s.count);
        const int indexType = s.indices.componentType;
        if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            error(c.subject, ": sparse indices hold ", componentTypeName(indexType),
                  " values, expected unsigned byte, short or int");
        if (s.indices.byteOffset < 0 || s.values.byteOffset < 0)
            error(c.subject, ": negative sparse byteOffset");
        c.sparseCount = n;
        c.sparseIndexType = indexType;
        c.sparseIndices = viewRange(s.indices.bufferView, size_t(s.indices.byteOffset),
                                    n * componentBytes(indexType), c.subject, "sparse indices");
        c.sparseValues = viewRange(s.values.bufferView, size_t(s.values.byteOffset),
                                   n * c.elementBytes, c.subject, "sparse values");
    }

    // All elements of `c` as T, components interleaved, with the sparse values
    // substituted.
    template <typename T>
    std::vector<T> readAccessor(const CheckedAccessor& c) const {
        const tinygltf::Accessor& a = *c.accessor;
        const size_t componentSize = componentBytes(a.componentType);
        std::vector<T> out(c.count * c.components, T(0));
        const auto readElement = [&](const unsigned char* p, size_t element) {
            for (size_t k = 0; k < c.components; ++k)
                out[element * c.components + k] = static_cast<T>(
                    readComponent(p + k * componentSize, a.componentType, a.normalized));
        };
        if (c.data != nullptr) {
            for (size_t i = 0; i < c.count; ++i) readElement(c.data + i * c.stride, i);
        }
        const size_t indexSize = componentBytes(c.sparseIndexType);
        size_t previous = 0;
        for (size_t j = 0; j < c.sparseCount; ++j) {
            const auto target = static_cast<size_t>(
                readComponent(c.sparseIndices + j * indexSize, c.sparseIndexType, false));
            if (target >= c.count || (j > 0 && target <= previous))
                error(c.subject, ": sparse index ", target, " (entry ", j,
                      ") is out of range or not increasing (", c.count, " elements)");
            readElement(c.sparseValues + j * c.elementBytes, target);
            previous = target;
        }
        return out;
    }

    std::vector<float> readFinite(const CheckedAccessor& c) const {
        std::vector<float> values = readAccessor<float>(c);
        for (size_t i = 0; i < values.size(); ++i) {
            if (!std::isfinite(values[i]))
                error(c.subject, ": element ", i / c.components, " is not finite");
        }
        return values;
    }

    // ---------------------------------------------------------------- materials

    static MeshMaterial gltfDefaults() {
        MeshMaterial m;
        m.source = MeshMaterial::Source::Gltf;
        m.diffuse = Color(1.0f);  // baseColorFactor defaults to white
        return m;
    }

    // A number from a material extension object, or `fallback` when absent.
    double extensionNumber(const tinygltf::ExtensionMap& extensions, const char* extension,
                           const char* key, double fallback, const std::string& place) const {
        const auto it = extensions.find(extension);
        if (it == extensions.end() || !it->second.IsObject() || !it->second.Has(key))
            return fallback;
        const tinygltf::Value& v = it->second.Get(key);
        if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble()))
            error(place, extension, ".", key, " is not a finite number");
        return v.GetNumberAsDouble();
    }

    float factor(double value, const std::string& place, const char* what) {
        if (!std::isfinite(value)) error(place, what, " is not a finite number");
        if (value < 0.0 || value > 1.0)
            meshio::warn(
                concat(name_, ": ", place, what, " ", value, " is outside [0, 1]; clamped"));
        return static_cast<float>(std::clamp(value, 0.0, 1.0));
    }

    Color color(const std::vector<double>& values, size_t expected, const std::string& place,
                const char* what) const {
        if (values.size() != expected)
            error(place, what, " has ", values.size(), " numbers, expected ", expected);
        for (double v : values) {
            if (!std::isfinite(v)) error(place, what, " is not finite");
        }
        return Color(float(values[0]), float(values[1]), float(values[2]));
    }

    void convertMaterials(std::vector<MeshMaterial>& out) {
        out.reserve(model_.materials.size() + 1);  // +1: the default material, if used
        for (size_t i = 0; i < model_.materials.size(); ++i) {
            const tinygltf::Material& g = model_.materials[i];
            const std::string place = concat("materials[", i, "].");
            const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
            MeshMaterial m = gltfDefaults();
            m.name = g.name;
            m.diffuse =
                color(pbr.baseColorFactor, 4, place, "pbrMetallicRoughness.baseColorFactor");
            const double alpha = pbr.baseColorFactor[3];
            // The factor's alpha as the dissolve; texture alpha has no field.
            if (g.alphaMode == "BLEND")
                m.dissolve = factor(alpha, place, "baseColorFactor alpha");
            else if (g.alphaMode == "MASK")
                m.dissolve = alpha >= g.alphaCutoff ? 1.0f : 0.0f;
            if (g.alphaMode != "OPAQUE" && pbr.baseColorTexture.index >= 0)
                warnOnce("alpha", "the alpha of base colour textures is ignored (alphaMode " +
                                      g.alphaMode + ")");
            m.metallic = factor(pbr.metallicFactor, place, "pbrMetallicRoughness.metallicFactor");
            m.roughness =
                factor(pbr.roughnessFactor, place, "pbrMetallicRoughness.roughnessFactor");
            const double strength = extensionNumber(g.extensions, "KHR_materials_emissive_strength",
                                                    "emissiveStrength", 1.0, place + "extensions.");
            if (strength < 0.0)
                error(place, "extensions.KHR_materials_emissive_strength.emissiveStrength ",
                      strength, " is negative");
            m.emission = color(g.emissiveFactor, 3, place, "emissiveFactor") * float(strength);
            const double ior = extensionNumber(g.extensions, "KHR_materials_ior", "ior", 1.5,
                                               place + "extensions.");
            if (ior >= 1.0)
                m.ior = float(ior);
            else
                meshio::warn(concat(name_, ": ", place, "extensions.KHR_materials_ior.ior ", ior,
                                    " is less than 1; using 1.5"));
            m.transmission =
                Color(factor(extensionNumber(g.extensions, "KHR_materials_transmission",
                                             "transmissionFactor", 0.0, place + "extensions."),
                             place, "extensions.KHR_materials_transmission.transmissionFactor"));

            m.diffuseTexture = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                       place + "pbrMetallicRoughness.baseColorTexture");
            m.metallicRoughnessTexture =
                texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                        place + "pbrMetallicRoughness.metallicRoughnessTexture");
            m.normalTexture =
                texture(g.normalTexture.index, g.normalTexture.texCoord, place + "normalTexture");
            if (!m.normalTexture.empty() && g.normalTexture.scale != 1.0)
                warnOnce("normal scale", "normalTexture.scale is ignored (taken as 1)");
            m.emissionTexture = texture(g.emissiveTexture.index, g.emissiveTexture.texCoord,
                                        place + "emissiveTexture");
            const auto transmission = g.extensions.find("KHR_materials_transmission");
            if (transmission != g.extensions.end() &&
                transmission->second.Has("transmissionTexture"))
                warnOnce("transmission texture", "transmissionTexture is ignored");
            out.push_back(std::move(m));
        }
    }

    // The image file of texture `index` (-1: none), or empty with a warning.
    fs::path texture(int index, int texCoord, const std::string& place) {
        if (index < 0) return {};
        if (size_t(index) >= model_.textures.size())
            error(place, ": texture ", index, " does not exist (", model_.textures.size(),
                  " textures)");
        if (texCoord != 0)
            warnOnce("texcoord",
                     concat(place, ": uses TEXCOORD_", texCoord, "; strahl reads TEXCOORD_0 only"));
        const int source = model_.textures[size_t(index)].source;
        if (source < 0) {
            // Only an extension (KTX2, WebP, ...) gives its image.
            meshio::warn(concat(name_, ": ", place, ": texture ", index,
                                " has no PNG/JPEG source; the texture is ignored"));
            return {};
        }
        if (size_t(source) >= model_.images.size())
            error(place, ": texture ", index, " refers to image ", source,
                  ", which does not exist (", model_.images.size(), " images)");
        return image(size_t(source));
    }

    fs::path image(size_t index) {
        if (images_.size() < model_.images.size()) images_.resize(model_.images.size());
        if (!images_[index]) images_[index] = resolveImage(index);
        return *images_[index];
    }

    fs::path resolveImage(size_t index) {
        const tinygltf::Image& img = model_.images[index];
        const std::string place = concat("images[", index, "]");
        if (img.bufferView >= 0) {
            const unsigned char* bytes = checkedView(img.bufferView, place);
            return extracted(index, bytes, model_.bufferViews[size_t(img.bufferView)].byteLength,
                             img.mimeType);
        }
        if (!img.image.empty())
            return extracted(index, img.image.data(), img.image.size(), img.mimeType);
        if (img.uri.rfind("data:", 0) == 0) {
            meshio::warn(concat(name_, ": ", place, ": unsupported data URI type '",
                                img.uri.substr(0, std::min<size_t>(img.uri.find(','), 40)),
                                "'; the texture is ignored"));
            return {};
        }
        if (img.uri.find("://") != std::string::npos) {
            meshio::warn(concat(name_, ": ", place, ": '", img.uri,
                                "' is not a relative path; the texture is ignored"));
            return {};
        }
        const std::string decoded = percentDecode(img.uri);
        fs::path found = findFileCaseInsensitive(folder_, decoded);
        if (found.empty())
            meshio::warn(concat(name_, ": ", place, ": texture '", decoded,
                                "' not found; materials using it get no texture"));
        return found;
    }

    // Writes an embedded image once into temp/strahl-gltf-<hash of the glTF's
    // path>/image<i>-<hash of the bytes>.<ext> and returns that path: a file of
    // that name and size is the same image and is reused.
    fs::path extracted(size_t index, const unsigned char* bytes, size_t size,
                       const std::string& mime) {
        const std::string place = concat(name_, ": images[", index, "]: ");
        const std::string ext = imageExtension(bytes, size, mime);
        if (ext.empty()) {
            meshio::warn(concat(place, "embedded image of type '", mime,
                                "' is neither PNG nor JPEG; the texture is ignored"));
            return {};
        }
        std::error_code ec;
        const fs::path temp = fs::temp_directory_path(ec);
        if (ec) {
            meshio::warn(concat(place, "no temporary folder for the embedded image (", ec.message(),
                                "); the texture is ignored"));
            return {};
        }
        const fs::path dir = temp / ("strahl-gltf-" + hex64(fileHash_));
        const fs::path file = dir / concat("image", index, '-', hex64(fnv1a(bytes, size)), ext);
        if (fs::file_size(file, ec) == size && !ec) return file;
        // Written under a unique name, then renamed: a loader running in parallel
        // never sees half an image.
        static std::atomic<unsigned> counter{0};
        const fs::path part = concat(file.string(), ".part-", getpid(), '-', counter++);
        bool written = false;
        fs::create_directories(dir, ec);
        if (!ec) {
            std::FILE* f = std::fopen(part.c_str(), "wb");
            if (f != nullptr) {
                written = std::fwrite(bytes, 1, size, f) == size;
                written = std::fclose(f) == 0 && written;
            }
            if (written) fs::rename(part, file, ec);
            written = written && !ec;
            std::error_code ignored;  // nothing to remove after a successful rename
            if (!written) fs::remove(part, ignored);
        }
        if (!written) {
            meshio::warn(concat(place, "cannot write the embedded image to ", file.string(),
                                "; the texture is ignored"));
            return {};
        }
        return file;
    }

    // ---------------------------------------------------------------- scene

    // All nodes, in the scene or not: children exist, no node has two parents,
    // and no node is its own ancestor.
    void checkNodeGraph() const {
        const size_t count = model_.nodes.size();
        constexpr size_t kNoParent = std::numeric_limits<size_t>::max();
        std::vector<size_t> parent(count, kNoParent);
        for (size_t i = 0; i < count; ++i) {
            const std::vector<int>& children = model_.nodes[i].children;
            for (size_t k = 0; k < children.size(); ++k) {
                const int c = children[k];
                const std::string place = concat("nodes[", i, "].children[", k, "]: ");
                if (c < 0 || size_t(c) >= count)
                    error(place, "node ", c, " does not exist (", count, " nodes)");
                if (size_t(c) == i)
                    error(place, "node ", c, " is its own ancestor (cyclic node hierarchy)");
                if (parent[size_t(c)] != kNoParent)
                    error(place, "node ", c, " already is a child of node ", parent[size_t(c)],
                          " (a node has at most one parent)");
                parent[size_t(c)] = i;
            }
        }
        // With one parent each, a cycle is a parent chain that comes back to a
        // node of the same walk; every node is walked over once.
        enum class State : uint8_t { Unknown, OnWalk, Rooted };
        std::vector<State> state(count, State::Unknown);
        std::vector<size_t> walk;
        for (size_t i = 0; i < count; ++i) {
            walk.clear();
            size_t x = i;
            while (x != kNoParent && state[x] == State::Unknown) {
                state[x] = State::OnWalk;
                walk.push_back(x);
                x = parent[x];
            }
            if (x != kNoParent && state[x] == State::OnWalk)
                error("nodes[", x, "]: node ", x, " is its own ancestor (cyclic node hierarchy)");
            for (size_t w : walk) state[w] = State::Rooted;
        }
    }

    // Local transform of node `index`: its matrix, or T * R * S.
    glm::dmat4 localTransform(size_t index) const {
        const tinygltf::Node& n = model_.nodes[index];
        const std::string place = concat("nodes[", index, "]");
        const auto check = [&](const std::vector<double>& v, std::initializer_list<size_t> sizes,
                               const char* what) {
            if (std::find(sizes.begin(), sizes.end(), v.size()) == sizes.end())
                error(place, what, " has ", v.size(), " numbers");
            for (double x : v) {
                if (!std::isfinite(x)) error(place, what, " is not finite");
            }
        };
        check(n.matrix, {0, 16}, ".matrix");
        check(n.translation, {0, 3}, ".translation");
        check(n.rotation, {0, 4}, ".rotation");
        check(n.scale, {0, 3}, ".scale");
        if (!n.matrix.empty()) return glm::make_mat4(n.matrix.data());  // column-major, as glm
        glm::dmat4 m(1.0);
        if (!n.translation.empty()) m = glm::translate(m, glm::make_vec3(n.translation.data()));
        if (!n.rotation.empty()) {
            // glTF stores (x, y, z, w); glm's constructor takes w first.
            glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
            const double length = glm::length(q);
            if (!(length > 0.0)) error(place, ".rotation is the zero quaternion");
            m *= glm::mat4_cast(q / length);
        }
        if (!n.scale.empty()) m = glm::scale(m, glm::make_vec3(n.scale.data()));
        return m;
    }

    // Every node of the scene with its world transform, parents before
    // children. Cycles and nodes with two parents are errors: a hierarchy must
    // be a forest, and a cycle would never end.
    std::vector<std::pair<size_t, glm::dmat4>> sceneNodes() const {
        std::vector<int> roots;
        std::string rootsPlace = "root nodes";
        if (!model_.scenes.empty()) {
            const int scene = model_.defaultScene >= 0 ? model_.defaultScene : 0;
            if (size_t(scene) >= model_.scenes.size())
                fail(name_, ": scene ", scene, " does not exist (", model_.scenes.size(),
                     " scenes)");
            roots = model_.scenes[size_t(scene)].nodes;
            rootsPlace = concat("scenes[", scene, "].nodes");
        } else {
            // No scene at all: every node that is no node's child.
            std::vector<bool> child(model_.nodes.size(), false);
            for (const tinygltf::Node& n : model_.nodes) {
                for (int c : n.children) {
                    if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
                }
            }
            for (size_t i = 0; i < child.size(); ++i) {
                if (!child[i]) roots.push_back(int(i));
            }
        }

        enum class State : uint8_t { Unvisited, Open, Done };
        std::vector<State> state(model_.nodes.size(), State::Unvisited);
        std::vector<std::pair<size_t, glm::dmat4>> instances;
        struct Frame {
            size_t node;
            glm::dmat4 world;
            size_t nextChild;
        };
        std::vector<Frame> stack;  // explicit: a deep hierarchy must not overflow the call stack
        const auto enter = [&](int node, const glm::dmat4& parent, const std::string& place) {
            if (node < 0 || size_t(node) >= model_.nodes.size())
                error(place, "node ", node, " does not exist (", model_.nodes.size(), " nodes)");
            const size_t n = size_t(node);
            if (state[n] == State::Open)
                error(place, "node ", node, " is its own ancestor (cyclic node hierarchy)");
            if (state[n] == State::Done)
                error(place, "node ", node,
                      " appears twice in the hierarchy (a node has at most"
                      " one parent)");
            state[n] = State::Open;
            const glm::dmat4 world = parent * localTransform(n);
            const int mesh = model_.nodes[n].mesh;
            if (mesh >= 0) {
                if (size_t(mesh) >= model_.meshes.size())
                    error(concat("nodes[", n, "]"), ": mesh ", mesh, " does not exist (",
                          model_.meshes.size(), " meshes)");
            }
            instances.emplace_back(n, world);
            stack.push_back({n, world, 0});
        };
        for (size_t r = 0; r < roots.size(); ++r) {
            enter(roots[r], glm::dmat4(1.0), concat(rootsPlace, '[', r, "]: "));
            while (!stack.empty()) {
                Frame& top = stack.back();
                const std::vector<int>& children = model_.nodes[top.node].children;
                if (top.nextChild == children.size()) {
                    state[top.node] = State::Done;
                    stack.pop_back();
                    continue;
                }
                const size_t k = top.nextChild++;
                const glm::dmat4 world = top.world;  // `top` dangles once enter() pushes
                enter(children[k], world, concat("nodes[", top.node, "].children[", k, "]: "));
            }
        }
        return instances;
    }

    void addJobs(size_t node, const glm::dmat4& world, std::vector<PrimitiveJob>& jobs) {
        const tinygltf::Node& n = model_.nodes[node];
        if (n.skin >= 0) warnOnce("skin", "skins are ignored (meshes keep their node transforms)");
        const size_t meshIndex = size_t(n.mesh);
        const tinygltf::Mesh& mesh = model_.meshes[meshIndex];
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = mesh.primitives[p];
            const std::string place = concat("meshes[", meshIndex, "].primitives[", p, "]");
            if (prim.mode != TINYGLTF_MODE_TRIANGLES) {
                warnOnce(place, concat(place, ": mode ", prim.mode,
                                       " is not TRIANGLES (4); primitive skipped"));
                continue;
            }
            if (!prim.targets.empty()) warnOnce("morph", "morph targets are ignored");
            PrimitiveJob job;
            job.place = place;
            job.world = world;
            const auto attribute = [&](const char* name) {
                const auto it = prim.attributes.find(name);
                return it == prim.attributes.end() ? -1 : it->second;
            };
            const int position = attribute("POSITION");
            if (position < 0) error(place, ": no POSITION attribute");
            const int floatType = TINYGLTF_COMPONENT_TYPE_FLOAT;
            job.positions = checkAccessor(position, place, "POSITION", {TINYGLTF_TYPE_VEC3},
                                          {{floatType, false}});
            const size_t vertices = job.positions.count;
            if (vertices > std::numeric_limits<uint32_t>::max())
                error(place, ": more than 2^32-1 vertices");
            const auto sameCount = [&](const CheckedAccessor& a) {
                if (a.count != vertices)
                    error(a.subject, " has ", a.count, " elements, POSITION has ", vertices);
            };
            if (const int normal = attribute("NORMAL"); normal >= 0) {
                job.normals = checkAccessor(normal, place, "NORMAL", {TINYGLTF_TYPE_VEC3},
                                            {{floatType, false}});
                sameCount(job.normals);
            }
            if (const int uv = attribute("TEXCOORD_0"); uv >= 0) {
                job.uvs = checkAccessor(uv, place, "TEXCOORD_0", {TINYGLTF_TYPE_VEC2},
                                        {{floatType, false},
                                         {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, true},
                                         {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, true}});
                sameCount(job.uvs);
            }
            if (prim.indices >= 0) {
                job.indices = checkAccessor(prim.indices, place, "indices", {TINYGLTF_TYPE_SCALAR},
                                            {{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, false},
                                             {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, false},
                                             {TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, false}});
                job.indexCount = job.indices.count;
            } else {
                job.indexCount = vertices;
            }
            if (job.indexCount % 3 != 0)
                error(place, ": ", job.indexCount, " indices are not a whole number of triangles");
            if (prim.material >= 0) {
                if (size_t(prim.material) >= model_.materials.size())
                    error(place, ": material ", prim.material, " does not exist (",
                          model_.materials.size(), " materials)");
                job.material = uint32_t(prim.material);
            } else {
                job.material = uint32_t(model_.materials.size());  // the default, appended last
                usesDefaultMaterial_ = true;
            }
            jobs.push_back(std::move(job));
        }
    }

    // ---------------------------------------------------------------- assembly

    void build(const std::vector<PrimitiveJob>& jobs, TriangleMesh& mesh) const {
        // glTF asks for flat normals where a primitive has none; when others have
        // normals, such a primitive gets one vertex per corner with its face normal.
        bool anyNormals = false, anyUvs = false;
        for (const PrimitiveJob& j : jobs) {
            anyNormals = anyNormals || j.normals.present();
            anyUvs = anyUvs || j.uvs.present();
        }
        uint64_t vertices = 0, indices = 0;
        for (const PrimitiveJob& j : jobs) {
            const bool flat = anyNormals && !j.normals.present();
            vertices += flat ? j.indexCount : j.positions.count;
            indices += j.indexCount;
        }
        // Indices are 32-bit: all instances together must fit.
        if (vertices >= std::numeric_limits<uint32_t>::max())
            fail(name_, ": ", vertices,
                 " vertices in the scene (instances included), more than"
                 " 32-bit indices address");
        mesh.positions.reserve(size_t(vertices) + 1);  // the spare element Embree's loads need
        if (anyNormals) mesh.normals.reserve(size_t(vertices));
        if (anyUvs) mesh.uvs.reserve(size_t(vertices));
        mesh.indices.reserve(size_t(indices));
        mesh.faceMaterials.reserve(size_t(indices / 3));
        for (const PrimitiveJob& j : jobs) append(j, anyNormals, anyUvs, mesh);
    }

    void append(const PrimitiveJob& j, bool anyNormals, bool anyUvs, TriangleMesh& mesh) const {
        const size_t n = j.positions.count;
        const std::vector<float> p = readFinite(j.positions);
        const std::vector<float> nrm =
            j.normals.present() ? readFinite(j.normals) : std::vector<float>();
        const std::vector<float> uv = j.uvs.present() ? readFinite(j.uvs) : std::vector<float>();
        std::vector<uint32_t> idx;
        if (j.indices.present()) {
            idx = readAccessor<uint32_t>(j.indices);
            for (size_t i = 0; i < idx.size(); ++i) {
                if (idx[i] >= n)
                    error(j.indices.subject, ": index ", idx[i], " (element ", i,
                          ") is out of range: the primitive has ", n, " vertices");
            }
        } else {
            idx.resize(n);
            for (size_t i = 0; i < n; ++i) idx[i] = uint32_t(i);
        }

        // Normals go through the cofactor matrix, det * inverse transpose: the
        // inverse transpose up to its sign and scale, defined for singular matrices
        // too. The sign is put back so normals of mirrored nodes stay outward.
        const glm::dmat3 linear(j.world);
        const double det = glm::determinant(linear);
        const glm::dmat3 cofactor(glm::cross(linear[1], linear[2]),
                                  glm::cross(linear[2], linear[0]),
                                  glm::cross(linear[0], linear[1]));
        const glm::dmat3 normalMatrix = cofactor * (det < 0.0 ? -1.0 : 1.0);
        const bool mirror = det < 0.0;  // flips the winding: swap two corners per triangle

        const auto position = [&](size_t v) {
            return Vec3(j.world * glm::dvec4(p[3 * v], p[3 * v + 1], p[3 * v + 2], 1.0));
        };
        const auto normal = [&](const glm::dvec3& v) {
            const glm::dvec3 t = normalMatrix * v;
            const double length = glm::length(t);
            return Vec3(length > 0.0 ? t / length : t);
        };
        // glTF's v runs down from the top of the image; strahl's uvs follow OBJ,
        // v up from the bottom: store (u, 1 - v).
        const auto texcoord = [&](size_t v) {
            return uv.empty() ? Vec2(0.0f) : Vec2(uv[2 * v], 1.0f - uv[2 * v + 1]);
        };

        const auto base = static_cast<uint32_t>(mesh.positions.size());
        const bool flat = anyNormals && nrm.empty();
        if (!flat) {
            for (size_t v = 0; v < n; ++v) {
                mesh.positions.push_back(position(v));
                if (anyNormals)
                    mesh.normals.push_back(
                        normal(glm::dvec3(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2])));
                if (anyUvs) mesh.uvs.push_back(texcoord(v));
            }
        }
        for (size_t t = 0; t + 2 < idx.size(); t += 3) {
            uint32_t c[3] = {idx[t], idx[t + 1], idx[t + 2]};
            if (mirror) std::swap(c[1], c[2]);
            if (flat) {
                const uint32_t first = static_cast<uint32_t>(mesh.positions.size());
                const Vec3 q[3] = {position(c[0]), position(c[1]), position(c[2])};
                const Vec3 face = glm::cross(q[1] - q[0], q[2] - q[0]);
                const float length = glm::length(face);
                for (int k = 0; k < 3; ++k) {
                    mesh.positions.push_back(q[k]);
                    mesh.normals.push_back(length > 0.0f ? face / length : Vec3(0.0f));
                    if (anyUvs) mesh.uvs.push_back(texcoord(c[k]));
                    mesh.indices.push_back(first + uint32_t(k));
                }
            } else {
                for (uint32_t corner : c) mesh.indices.push_back(base + corner);
            }
            mesh.faceMaterials.push_back(j.material);
        }
    }

    fs::path path_;
    std::string name_;
    fs::path folder_;        // the glTF's folder, for image URIs
    uint64_t fileHash_ = 0;  // of the path, names the embedded-image cache folder
    tinygltf::Model model_;
    std::vector<std::optional<fs::path>> images_;  // resolved image paths, by image index
    std::set<std::string> warned_;
    bool usesDefaultMaterial_ = false;
};

}  // namespace

LoadedMesh loadGltf(const fs::path& file) {
    return loadGltfFromMemory(meshio::readWholeFile(file), file);
}

LoadedMesh loadGltfFromMemory(std::string_view data, const fs::path& file) {
    return GltfReader(file).read(data);
}

std::vector<GltfCamera> loadGltfCameras(const fs::path& file) {
    return GltfReader(file).readCameras(meshio::readWholeFile(file));
}

}  // namespace strahl
