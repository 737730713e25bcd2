// Assembly: each triangle primitive of a placed mesh checked into a
// PrimitiveJob, then all of them appended into one world-space TriangleMesh.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "gltf_reader.h"

namespace strahl::meshio::gltf {

void GltfReader::assemble(const SceneNodes& nodes, LoadedMesh& result) {
    std::vector<PrimitiveJob> jobs;
    for (const auto& [node, world] : nodes)
        if (model_.nodes[node].mesh >= 0) addJobs(node, world, jobs);
    if (usesDefaultMaterial_) {
        MeshMaterial fallback = gltfDefaults();
        fallback.name = "default";
        result.materials.push_back(fallback);
    }
    build(jobs, result.mesh);
    result.mesh.validate(name_);
}

void GltfReader::addJobs(size_t node, const glm::dmat4& world, std::vector<PrimitiveJob>& jobs) {
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
        job.positions =
            checkAccessor(position, place, "POSITION", {TINYGLTF_TYPE_VEC3}, {{floatType, false}});
        const size_t vertices = job.positions.count;
        if (vertices > std::numeric_limits<uint32_t>::max())
            error(place, ": more than 2^32-1 vertices");
        const auto sameCount = [&](const CheckedAccessor& a) {
            if (a.count != vertices)
                error(a.subject, " has ", a.count, " elements, POSITION has ", vertices);
        };
        if (const int normal = attribute("NORMAL"); normal >= 0) {
            job.normals =
                checkAccessor(normal, place, "NORMAL", {TINYGLTF_TYPE_VEC3}, {{floatType, false}});
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

void GltfReader::build(const std::vector<PrimitiveJob>& jobs, TriangleMesh& mesh) const {
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

void GltfReader::append(const PrimitiveJob& j, bool anyNormals, bool anyUvs,
                        TriangleMesh& mesh) const {
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
    const glm::dmat3 cofactor(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
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

}  // namespace strahl::meshio::gltf
