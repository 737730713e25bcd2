#pragma once
// Internal to the scene module: the files a SceneDesc names that building the
// world reads — mesh files, the glTF file a camera comes from, Bézier patch
// files and height images — each read once (a file that several shapes name,
// or the camera and a shape, is read once), all in parallel. Textures and
// environment images are not here: OpenImageIO's texture cache and the light
// builder read those.

#include <vector>

#include "height_image.h"
#include "strahl/geometry/bezier_patches.h"
#include "strahl/meshio/gltf_camera.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

// What one shape takes from its file (only the member of its kind is set).
struct ShapeFile {
    LoadedMesh mesh;                   // a mesh shape's file
    std::vector<BezierPatch> patches;  // a parametric shape's .bpt file
    HeightImage heights;               // a parametric shape's height image
};

struct SceneFiles {
    std::vector<GltfCamera> cameras;  // the cameras of desc.camera.gltf's file
    std::vector<ShapeFile> shapes;    // one per entry of `shapes`, in its order
};

// Reads every file that desc.camera and `shapes` name, with `threads` threads
// (0: all). Throws the error of the first file that fails, the camera's
// first, then in the order of `shapes`: a mesh loader's own message, or for
// the camera, patch files and height images "<scene>: <pointer>: <message>".
SceneFiles readSceneFiles(const SceneDesc& desc, const std::vector<const ShapeDesc*>& shapes,
                          int threads);

// desc.camera with the glTF camera it chooses filled in (the choice checked
// against the file's cameras); desc.camera itself if it names no glTF file.
CameraDesc resolveCamera(const SceneDesc& desc, const std::vector<GltfCamera>& cameras);

// The surface of a parametric shape whose data is a file, from what was read.
ParametricSurfacePtr surfaceFromFile(const SceneDesc& desc, const ParametricFile& file,
                                     ShapeFile&& data);

}  // namespace strahl::scene_detail
