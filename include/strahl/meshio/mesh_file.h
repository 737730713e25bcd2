#pragma once
// Mesh file loaders. Each returns one TriangleMesh (polygons fan-triangulated)
// plus the materials its faces refer to, and throws strahl::Error with
// "file:line: what" (text), "file: byte offset N: what" (binary) or
// "file: meshes[0].primitives[1]: what" (glTF) on any malformed, truncated or
// out-of-range input.

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/core/math.h"
#include "strahl/geometry/triangle_mesh.h"

namespace strahl {

// A surface description found in a mesh file: an OBJ .mtl entry or a glTF 2.0
// material. The scene builder maps it onto strahl's materials
// (docs/materials.md, "Materials from mesh files"); textures are resolved paths
// on disk, empty when absent.
struct MeshMaterial {
    enum class Source { Obj, Gltf };
    std::string name;
    Source source = Source::Obj;
    Color diffuse{0.8f};     // OBJ Kd; glTF baseColorFactor (rgb)
    Color specular{0.0f};    // OBJ Ks
    float shininess = 0.0f;  // OBJ Ns (Phong exponent)
    float ior = 1.5f;        // OBJ Ni; glTF KHR_materials_ior
    float dissolve = 1.0f;   // OBJ d (or 1 - Tr): 1 opaque; glTF baseColorFactor alpha
                             // (alphaMode MASK or BLEND, else 1)
    int illum = 2;           // OBJ illumination model (5, 7: mirror; 4, 6, 7, 9: glass)
    Color transmission{0.0f};  // OBJ Tf; glTF KHR_materials_transmission factor (grey)
    float metallic = 1.0f;   // glTF metallicFactor
    float roughness = 1.0f;  // glTF roughnessFactor (perceptual)
    Color emission{0.0f};    // OBJ Ke; glTF emissiveFactor x KHR_materials_emissive_strength
    std::filesystem::path diffuseTexture;    // OBJ map_Kd; glTF baseColorTexture
    std::filesystem::path normalTexture;     // OBJ norm (not map_Bump/bump); glTF normalTexture
    std::filesystem::path metallicRoughnessTexture;  // glTF (B: metallic, G: roughness)
    std::filesystem::path emissionTexture;   // OBJ map_Ke; glTF emissiveTexture
    // glTF alphaMode MASK or BLEND: the base colour texture, whose alpha
    // times `dissolve` is the opacity; MASK's alphaCutoff (else negative).
    std::filesystem::path opacityTexture;
    float opacityCutoff = -1.0f;
};

struct LoadedMesh {
    TriangleMesh mesh;  // faceMaterials index into `materials` (empty if none)
    std::vector<MeshMaterial> materials;
};

LoadedMesh loadObj(const std::filesystem::path& file);
LoadedMesh loadPly(const std::filesystem::path& file);
// glTF 2.0, .gltf or .glb (docs/mesh-files.md): the default scene flattened into
// world space, materials with source Gltf, uvs stored as (u, 1 - v).
LoadedMesh loadGltf(const std::filesystem::path& file);
// Mitsuba's .serialized (docs/mesh-files.md): mesh `shapeIndex` of the file
// (0 is the first); positions, normals and uvs (v turned up), no materials.
LoadedMesh loadSerialized(const std::filesystem::path& file, uint32_t shapeIndex = 0);

// The same loaders on bytes already in memory (the path loaders above read the
// file and call these; the fuzz targets in fuzz/ call them directly). `file`
// names the data in errors and anchors what it refers to: an OBJ's mtllib and
// texture names, a glTF's external buffers and images. It need not exist.
LoadedMesh loadObjFromMemory(std::string_view data, const std::filesystem::path& file);
LoadedMesh loadPlyFromMemory(std::string_view data, const std::filesystem::path& file);
LoadedMesh loadGltfFromMemory(std::string_view data, const std::filesystem::path& file);
LoadedMesh loadSerializedFromMemory(std::string_view data, const std::filesystem::path& file,
                                    uint32_t shapeIndex = 0);

// Recoverable problems (a missing .mtl, an unknown material, an attribute only
// some corners have) are warnings, not errors. They go to the handler set here,
// from any loader thread but one at a time; with no handler (the default) each
// is printed as "strahl: warning: <message>" on stderr. The CLI's --quiet
// installs a handler that drops them.
using MeshWarningHandler = std::function<void(const std::string& message)>;
void setMeshWarningHandler(MeshWarningHandler handler);
namespace meshio {
// Reports one such warning (also used by the scene importers for a note the
// user should see: an integrator substituted, say).
void reportWarning(const std::string& message);
}  // namespace meshio

// Whether a PLY file (or a .ply.gz) declares vertex normals (an "nx"
// property of its vertex element), from its header alone; false for a file
// that cannot be read or is no PLY (loading it reports that).
bool plyFileHasVertexNormals(const std::filesystem::path& file);
// The face count a PLY file (or a .ply.gz) declares ("element face N"), from
// its header alone; 0 for a file that cannot be read, is no PLY or has none.
// Compared with a loaded mesh's triangle count, it says whether every face
// was a triangle.
size_t plyFileFaceCount(const std::filesystem::path& file);

// Dispatches on the extension (.obj, .ply, .gltf, .glb; case-insensitive).
LoadedMesh loadMeshFile(const std::filesystem::path& file);

// Finds `name` (which may contain sub-folders) below `dir`, matching each path
// component case-insensitively when the exact spelling does not exist (Sponza's
// .mtl names textures in the wrong case). Returns an empty path if not found.
std::filesystem::path findFileCaseInsensitive(const std::filesystem::path& dir,
                                              const std::string& name);

}  // namespace strahl
