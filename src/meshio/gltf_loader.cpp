// glTF 2.0 loader's entry points (mesh_file.h, gltf_camera.h) and the reader's
// passes behind them, each in the order it checks and reads; the stages live
// in the other gltf_*.cpp files (gltf_reader.h).

#include <filesystem>
#include <string_view>
#include <vector>

#include "gltf_reader.h"
#include "strahl/meshio/gltf_camera.h"
#include "strahl/meshio/mesh_file.h"
#include "text_scan.h"

namespace fs = std::filesystem;

namespace strahl {

namespace meshio::gltf {

LoadedMesh GltfReader::read(std::string_view bytes) {
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

std::vector<GltfCamera> GltfReader::readCameras(std::string_view bytes) {
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

}  // namespace strahl
