// The mesh file formats (strahl/meshio/mesh_format.h): one line per format.

#include <algorithm>
#include <vector>

#include "strahl/meshio/mesh_format.h"
#include "text_scan.h"

namespace strahl {

extern const MeshFormat kObjFormat;   // obj_loader.cpp
extern const MeshFormat kPlyFormat;   // ply_loader.cpp
extern const MeshFormat kGzipPlyFormat;  // ply_loader.cpp
extern const MeshFormat kGltfFormat;  // gltf_loader.cpp
extern const MeshFormat kSerializedFormat;  // serialized_loader.cpp

namespace {

const MeshFormat* const kFormats[] = {
    &kObjFormat,
    &kPlyFormat,
    &kGzipPlyFormat,
    &kGltfFormat,
    &kSerializedFormat,
};

}  // namespace

std::span<const MeshFormat* const> meshFormats() { return kFormats; }

// By how the file name ends, so that double extensions (".ply.gz") work.
const MeshFormat* findMeshFormat(const std::filesystem::path& file) {
    const std::string name = meshio::toLower(file.filename().string());
    for (const MeshFormat* format : kFormats)
        for (std::string_view extension : format->extensions)
            if (name.size() > extension.size() && name.ends_with(extension)) return format;
    return nullptr;
}

std::string meshExtensionList(std::string_view separator, std::string_view lastSeparator) {
    std::vector<std::string_view> all;
    for (const MeshFormat* format : kFormats)
        all.insert(all.end(), format->extensions.begin(), format->extensions.end());
    std::string list;
    for (size_t i = 0; i < all.size(); ++i) {
        if (i > 0) list += i + 1 == all.size() ? lastSeparator : separator;
        list += all[i];
    }
    return list;
}

}  // namespace strahl
