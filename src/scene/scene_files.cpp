#include "scene_files.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <exception>
#include <map>
#include <tuple>
#include <utility>

#include "scene_place.h"
#include "strahl/core/error.h"
#include "strahl/geometry/height_field.h"
#include "strahl/meshio/bezier_file.h"

namespace strahl::scene_detail {

namespace {

namespace fs = std::filesystem;

// What is read from one file. A glTF file that gives both the camera and a
// mesh is read once for both.
enum class Content { Mesh, Cameras, MeshAndCameras, BezierPatches, HeightImage };

struct FileRead {
    Content content = Content::Mesh;
    fs::path file;
    uint32_t part = 0;               // which mesh of a multi-mesh file (.serialized)
    const ScenePlace* at = nullptr;  // cameras, patches, images: where errors are placed
    std::vector<size_t> users;       // indices into `shapes`
    LoadedMesh mesh;
    std::vector<GltfCamera> cameras;
    std::vector<BezierPatch> patches;
    HeightImage heights;
    std::exception_ptr error;
};

FileRead fileRead(Content content, const fs::path& file, const ScenePlace* at) {
    FileRead read;
    read.content = content;
    read.file = file;
    read.at = at;
    return read;
}

// The files to read, the camera's first, each once; a file is keyed by what
// is read from it (a mesh and a glTF camera file are both "scene files", a
// .bpt and an image named by the same path are read two ways).
std::vector<FileRead> plan(const SceneDesc& desc, const std::vector<const ShapeDesc*>& shapes) {
    std::vector<FileRead> reads;
    std::map<std::tuple<int, fs::path, uint32_t>, size_t> index;
    if (desc.camera.gltf) {
        index[{0, desc.camera.gltf->file, 0}] = 0;
        reads.push_back(fileRead(Content::Cameras, desc.camera.gltf->file, &desc.camera.gltf->fileAt));
    }
    for (size_t s = 0; s < shapes.size(); ++s) {
        const ShapeDesc& shape = *shapes[s];
        int key = 0;
        FileRead read;
        if (shape.kind == ShapeKind::Mesh && !shape.file.empty()) {
            read = fileRead(Content::Mesh, shape.file, nullptr);
            read.part = shape.shapeIndex;
        } else if (shape.kind == ShapeKind::Parametric && shape.parametric.file) {
            const ParametricFile& f = *shape.parametric.file;
            const bool bezier = f.kind == ParametricFile::Kind::BezierPatches;
            key = bezier ? 1 : 2;
            read = fileRead(bezier ? Content::BezierPatches : Content::HeightImage, f.file, &f.at);
        } else {
            continue;
        }
        const auto [found, added] = index.try_emplace({key, read.file, read.part}, reads.size());
        if (added) {
            reads.push_back(std::move(read));
        } else if (reads[found->second].content == Content::Cameras) {
            reads[found->second].content = Content::MeshAndCameras;
        }
        reads[found->second].users.push_back(s);
    }
    return reads;
}

void readOne(const SceneDesc& desc, FileRead& r) {
    const auto placed = [&](auto&& load) {
        try {
            load();
        } catch (const Error& e) {
            failAt(desc, *r.at, e.what());
        }
    };
    switch (r.content) {
        case Content::Mesh:
            r.mesh = r.part > 0 ? loadSerialized(r.file, r.part) : loadMeshFile(r.file);
            break;
        case Content::Cameras: placed([&] { r.cameras = loadGltfCameras(r.file); }); break;
        case Content::MeshAndCameras:
            try {
                GltfContents contents = loadGltfContents(r.file);
                r.mesh = std::move(contents.mesh);
                r.cameras = std::move(contents.cameras);
            } catch (const Error&) {
                // Name the camera's place if its part is what fails, as
                // reading the cameras alone would; else the mesh loader's
                // message stands.
                placed([&] { loadGltfCameras(r.file); });
                throw;
            }
            break;
        case Content::BezierPatches: placed([&] { r.patches = loadBezierFile(r.file); }); break;
        case Content::HeightImage: placed([&] { r.heights = loadHeightImage(r.file); }); break;
    }
}

// The last user takes the data, the others a copy.
template <typename T>
void handOut(T& data, const std::vector<size_t>& users, std::vector<ShapeFile>& shapes,
             T ShapeFile::*member) {
    for (size_t k = 0; k < users.size(); ++k)
        shapes[users[k]].*member = k + 1 == users.size() ? std::move(data) : data;
}

}  // namespace

SceneFiles readSceneFiles(const SceneDesc& desc, const std::vector<const ShapeDesc*>& shapes,
                          int threads) {
    std::vector<FileRead> reads = plan(desc, shapes);
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(size_t(0), reads.size(), [&](size_t i) {
            try {
                readOne(desc, reads[i]);
            } catch (...) {
                reads[i].error = std::current_exception();
            }
        });
    });
    // The first error in plan order, so the message does not depend on timing.
    for (const FileRead& r : reads)
        if (r.error) std::rethrow_exception(r.error);

    SceneFiles files;
    files.shapes.resize(shapes.size());
    for (FileRead& r : reads) {
        if (r.content == Content::Cameras || r.content == Content::MeshAndCameras)
            files.cameras = std::move(r.cameras);
        handOut(r.mesh, r.users, files.shapes, &ShapeFile::mesh);
        handOut(r.patches, r.users, files.shapes, &ShapeFile::patches);
        handOut(r.heights, r.users, files.shapes, &ShapeFile::heights);
    }
    return files;
}

CameraDesc resolveCamera(const SceneDesc& desc, const std::vector<GltfCamera>& cameras) {
    if (!desc.camera.gltf) return desc.camera;
    const GltfCameraChoice& choice = *desc.camera.gltf;
    if (cameras.empty())
        failAt(desc, choice.fileAt,
               concat(choice.file.filename().string(), " places no camera in its scene"));
    size_t chosen = 0;
    if (choice.byName) {
        const auto found = std::find_if(cameras.begin(), cameras.end(),
                                        [&](const GltfCamera& c) { return c.name == choice.name; });
        if (found == cameras.end()) {
            std::string names;
            for (const GltfCamera& c : cameras) names += (names.empty() ? "" : ", ") + c.name;
            failAt(desc, choice.cameraAt,
                   concat("no camera named '", choice.name, "' (the file has: ", names, ")"));
        }
        chosen = size_t(found - cameras.begin());
    } else {
        if (!choice.index || *choice.index >= cameras.size())
            failAt(desc, choice.cameraAt,
                   concat("must be between 0 and ", cameras.size() - 1, ", got ", choice.indexText));
        chosen = size_t(*choice.index);
    }
    const GltfCamera& g = cameras[chosen];
    CameraDesc c;
    c.apertureRadius = desc.camera.apertureRadius;  // the lens is the scene file's
    c.focusDistance = desc.camera.focusDistance;
    c.shutter = desc.camera.shutter;
    c.eye = g.eye;
    c.back = g.back;
    c.up = g.up;
    if (g.orthographic) {
        c.projection = Projection::Orthographic;
        c.window = ImageWindow{-g.xmag, g.xmag, -g.ymag, g.ymag};
    } else {
        c.fovYDegrees = g.yfovDegrees;
    }
    return c;
}

ParametricSurfacePtr surfaceFromFile(const SceneDesc& desc, const ParametricFile& file,
                                     ShapeFile&& data) {
    try {
        if (file.kind == ParametricFile::Kind::HeightImage) {
            HeightImage& h = data.heights;
            return makeHeightField(std::move(h.heights), h.columns, h.rows, file.size.x,
                                   file.size.y, file.height);
        }
        // Swapping u and v in every patch turns ∂u f × ∂v f around (the
        // classic teapot data's normals point into the pot).
        if (file.reverse)
            for (BezierPatch& patch : data.patches)
                for (int i = 0; i < 4; ++i)
                    for (int j = i + 1; j < 4; ++j)
                        std::swap(patch.points[size_t(4 * i + j)], patch.points[size_t(4 * j + i)]);
        return makeBezierPatchSet(std::move(data.patches), file.file.filename().string());
    } catch (const Error& e) {
        failAt(desc, file.at, e.what());
    }
}

}  // namespace strahl::scene_detail
