// glTF 2.0 loader's entry points (mesh_file.h, gltf_camera.h) and the reader's
// passes behind them, each in the order it checks and reads; the stages live
// in the other gltf_*.cpp files (gltf_reader.h).

#include <filesystem>
#include <string_view>
#include <vector>

#include "gltf_reader.h"
#include "strahl/meshio/gltf_camera.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/meshio/mesh_format.h"
#include "text_scan.h"

namespace fs = std::filesystem;

namespace strahl {

namespace meshio::gltf {

LoadedMesh GltfReader::read(std::string_view bytes) {
    parse(bytes);
    checkExtensions();
    LoadedMesh result;
    convertMaterials(result.materials);
    checkNodeGraph();
    assemble(sceneNodes(), result);
    return result;
}

std::vector<GltfCamera> GltfReader::readCameras(std::string_view bytes) {
    parse(bytes);
    checkExtensions();
    checkNodeGraph();
    return placeCameras(sceneNodes());
}

// readCameras, then read's remaining steps on the same model: the first error
// is the one loadGltfCameras, then loadGltf would throw (read's node checks
// cannot fail once readCameras' have passed), and the warnings are read's.
GltfContents GltfReader::readContents(std::string_view bytes) {
    parse(bytes);
    checkExtensions();
    checkNodeGraph();
    const SceneNodes nodes = sceneNodes();
    GltfContents contents;
    contents.cameras = placeCameras(nodes);
    convertMaterials(contents.mesh.materials);
    assemble(nodes, contents.mesh);
    return contents;
}

}  // namespace meshio::gltf

LoadedMesh loadGltf(const fs::path& file) {
    return loadGltfFromMemory(meshio::readWholeFile(file), file);
}

LoadedMesh loadGltfFromMemory(std::string_view data, const fs::path& file) {
    return meshio::gltf::GltfReader(file).read(data);
}

std::vector<GltfCamera> loadGltfCameras(const fs::path& file) {
    return meshio::gltf::GltfReader(file).readCameras(meshio::readWholeFile(file));
}

GltfContents loadGltfContents(const fs::path& file) {
    return meshio::gltf::GltfReader(file).readContents(meshio::readWholeFile(file));
}

namespace {
constexpr std::string_view kGltfExtensions[] = {".gltf", ".glb"};
}  // namespace

extern const MeshFormat kGltfFormat{"glTF 2.0", kGltfExtensions, &loadGltf, &loadGltfFromMemory};

}  // namespace strahl
