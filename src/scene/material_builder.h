#pragma once
// Internal to the scene module: turns material descriptions — the scene
// file's and those of mesh files (OBJ .mtl, glTF) — into the World's
// materials, registering their textures with the world's texture system
// (created on the first texture). The mapping of mesh-file materials is
// documented in docs/materials.md, "Materials from mesh files".

#include <string>

#include "strahl/integrator/world.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

// Registers an image with the world's texture system (made on the first
// one); an empty file is no texture. An unreadable file fails as
// "<where>: <file>: <reason>".
TextureHandle addTexture(World& world, const std::filesystem::path& file, TextureEncoding encoding,
                         const std::string& where);

// Errors (an unreadable texture) name the scene file and the material's JSON
// pointer, or for a mesh file's material its name "<shape>/<material>".
Material buildMaterial(const MaterialDesc& desc, const SceneDesc& scene, World& world);
Material buildMeshMaterial(const MeshMaterial& mesh, const std::string& name, World& world);

}  // namespace strahl::scene_detail
