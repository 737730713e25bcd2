#pragma once
// The glTF 2.0 reader behind loadGltf, loadGltfCameras and loadGltfContents,
// shared by the gltf_*.cpp files (one stage each). Not part of the public
// meshio interface; what it reads and its errors: docs/mesh-files.md.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/core/math.h"
#include "strahl/geometry/triangle_mesh.h"
#include "strahl/meshio/gltf_camera.h"
#include "strahl/meshio/mesh_file.h"
#include "text_scan.h"

// Textures are read later by OpenImageIO from their paths, so tinygltf neither
// decodes images (no stb_image) nor reads external image files. Every file
// including tiny_gltf.h must see the same configuration: gltf_parse.cpp
// compiles its implementation.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

namespace strahl::meshio::gltf {

namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little,
              "glTF buffers are little-endian and are read in place");

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

// Reads one glTF 2.0 file: .gltf (external or data-URI buffers) or binary .glb.
// tinygltf 2.7 (Debian's header-only libtinygltf-dev) parses the JSON and loads
// the buffers; everything it does not check (indices into arrays, accessor
// ranges, node cycles) is checked here before any data is read, and the
// default scene is flattened into one world-space TriangleMesh. Errors are
// strahl::Error "file: <place>: what"; warnings go through meshio::warn.
class GltfReader {
public:
    explicit GltfReader(const fs::path& file) : path_(file), name_(file.string()) {}

    // The loads (gltf_loader.cpp), each from the bytes of the whole file: the
    // default scene as one world-space mesh, the cameras its nodes place, or
    // both from one parse.
    LoadedMesh read(std::string_view bytes);
    std::vector<GltfCamera> readCameras(std::string_view bytes);
    GltfContents readContents(std::string_view bytes);

private:
    // "file: <args>"; the arguments start with the place ("meshes[0].primitives[1]: ").
    template <typename... Args>
    [[noreturn]] void error(const Args&... args) const {
        fail(name_, ": ", args...);
    }

    void warnOnce(const std::string& key, const std::string& message) {
        if (warned_.insert(key).second) meshio::warn(name_ + ": " + message);
    }

    // Parsing (gltf_parse.cpp): the GLB layout and image views checked, then
    // tinygltf fills model_ (its exceptions become errors); the extensions the
    // file requires or uses checked against those strahl reads.
    template <typename Call>
    bool guarded(Call&& call) const;
    void parse(std::string_view bytes);
    void checkImageViewsStartInTheirBuffers(std::string_view text) const;
    uint32_t checkGlbLayout(std::string_view bytes) const;
    void checkExtensions();

    // Buffer views and accessors (gltf_accessors.cpp): checked against their
    // buffers, then read with sparse values substituted. readAccessor exists
    // for float and uint32_t.
    size_t totalBufferBytes() const;
    const unsigned char* checkedView(int view, const std::string& place) const;
    const unsigned char* viewRange(int view, size_t offset, size_t bytes, const std::string& place,
                                   const std::string& what) const;
    CheckedAccessor checkAccessor(int index, const std::string& place, const std::string& role,
                                  std::initializer_list<int> types,
                                  std::initializer_list<ComponentRule> rules) const;
    void checkSparse(CheckedAccessor& c) const;
    template <typename T>
    std::vector<T> readAccessor(const CheckedAccessor& c) const;
    std::vector<float> readFinite(const CheckedAccessor& c) const;

    // Materials (gltf_materials.cpp): model_'s materials as MeshMaterials.
    static MeshMaterial gltfDefaults();
    double extensionNumber(const tinygltf::ExtensionMap& extensions, const char* extension,
                           const char* key, double fallback, const std::string& place) const;
    float factor(double value, const std::string& place, const char* what);
    Color color(const std::vector<double>& values, size_t expected, const std::string& place,
                const char* what) const;
    void convertMaterials(std::vector<MeshMaterial>& out);

    // Textures and images (gltf_images.cpp): the image file of a texture,
    // resolved once per image; embedded images are extracted to a temp folder.
    fs::path texture(int index, int texCoord, const std::string& place);
    fs::path image(size_t index);
    fs::path resolveImage(size_t index);
    fs::path extracted(size_t index, const unsigned char* bytes, size_t size,
                       const std::string& mime);

    // The scene (gltf_scene.cpp): the node graph checked, the default scene's
    // nodes with their world transforms, and the cameras those nodes place.
    using SceneNodes = std::vector<std::pair<size_t, glm::dmat4>>;  // node, world transform
    void checkNodeGraph() const;
    glm::dmat4 localTransform(size_t index) const;
    SceneNodes sceneNodes() const;
    std::vector<GltfCamera> placeCameras(const SceneNodes& nodes) const;
    GltfCamera convertCamera(size_t index, const tinygltf::Node& node, const glm::dmat4& world,
                             size_t placed) const;

    // Assembly (gltf_assembly.cpp): the meshes the nodes place, each triangle
    // primitive checked into a job, then all jobs appended into one TriangleMesh
    // (result.materials holds the converted materials already).
    void assemble(const SceneNodes& nodes, LoadedMesh& result);
    void addJobs(size_t node, const glm::dmat4& world, std::vector<PrimitiveJob>& jobs);
    void build(const std::vector<PrimitiveJob>& jobs, TriangleMesh& mesh) const;
    void append(const PrimitiveJob& j, bool anyNormals, bool anyUvs, TriangleMesh& mesh) const;

    fs::path path_;
    std::string name_;
    fs::path folder_;        // the glTF's folder, for image URIs
    uint64_t fileHash_ = 0;  // of the path, names the embedded-image cache folder
    tinygltf::Model model_;
    std::vector<std::optional<fs::path>> images_;  // resolved image paths, by image index
    std::set<std::string> warned_;
    bool usesDefaultMaterial_ = false;
};

}  // namespace strahl::meshio::gltf
