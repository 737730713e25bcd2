#pragma once
// The cameras a glTF 2.0 file places: each node of the default scene with a
// camera, in the node hierarchy's order (parents before children, children in
// order), with its world transform applied. glTF cameras look down their
// local -z with +y up; strahl's camera frame has the back axis w = +z. A scene
// file takes one with "camera": {"gltf": FILE, "gltf_camera": N or NAME}
// (docs/scene-format.md, "camera").

#include <filesystem>
#include <string>
#include <vector>

#include "strahl/core/math.h"
#include "strahl/meshio/mesh_file.h"

namespace strahl {

struct GltfCamera {
    std::string name;  // the camera's name, else its node's, else "camera K"
    bool orthographic = false;
    Vec3 eye{0.0f};    // the node's origin in world space
    Vec3 back{0.0f};   // unit: the node's +z in world space (it looks down -back)
    Vec3 up{0.0f};     // unit: the node's +y in world space
    float yfovDegrees = 0.0f;        // perspective: the vertical field of view
    float xmag = 0.0f, ymag = 0.0f;  // orthographic: half the view's width and height
};

// Throws strahl::Error "file: <place>: ..." for a malformed file or camera (a
// missing camera index, a non-positive yfov, a zero xmag/ymag, a node whose
// transform collapses the view direction).
std::vector<GltfCamera> loadGltfCameras(const std::filesystem::path& file);

// What loadGltf and loadGltfCameras give for the same file, from one read and
// one parse (a scene using a glTF file as its camera source and its mesh).
struct GltfContents {
    LoadedMesh mesh;
    std::vector<GltfCamera> cameras;
};

// Throws what calling loadGltfCameras, then loadGltf would throw first: an
// error of the file, its node hierarchy or a camera before an error of the
// mesh or materials. (loadGltf alone checks materials before the hierarchy, so
// for a file with both kinds of error it names the material one instead.)
// Warns what loadGltf warns (up to the error, if any); the two separate calls
// would repeat the file's parse and extension warnings.
GltfContents loadGltfContents(const std::filesystem::path& file);

}  // namespace strahl
