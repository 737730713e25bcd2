#include "bench_mesh.h"

#include <cstring>
#include <filesystem>
#include <unordered_map>

#include "strahl/meshio/mesh_file.h"

namespace strahl::bench {

TriangleMesh subdivideMidpoints(const TriangleMesh& mesh) {
    TriangleMesh out;
    out.positions = mesh.positions;
    std::unordered_map<uint64_t, uint32_t> midpoint;  // edge (min,max) -> new vertex
    auto mid = [&](uint32_t a, uint32_t b) {
        const uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
        auto [it, inserted] = midpoint.try_emplace(key, uint32_t(out.positions.size()));
        if (inserted) out.positions.push_back(0.5f * (mesh.positions[a] + mesh.positions[b]));
        return it->second;
    };
    out.indices.reserve(mesh.indices.size() * 4);
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
        const uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
        for (uint32_t i : {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca}) out.indices.push_back(i);
    }
    return out;
}

namespace {
TriangleMesh uvSphere(int rings, int segments) {
    TriangleMesh m;
    for (int r = 0; r <= rings; ++r) {
        const float theta = kPi * float(r) / float(rings);
        for (int s = 0; s < segments; ++s) {
            const float phi = 2.0f * kPi * float(s) / float(segments);
            m.positions.emplace_back(std::sin(theta) * std::cos(phi), std::cos(theta),
                                     std::sin(theta) * std::sin(phi));
        }
    }
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            const uint32_t i0 = uint32_t(r * segments + s), i1 = uint32_t(r * segments + (s + 1) % segments);
            const uint32_t i2 = i0 + uint32_t(segments), i3 = i1 + uint32_t(segments);
            for (uint32_t i : {i0, i2, i1, i1, i2, i3}) m.indices.push_back(i);
        }
    }
    return m;
}
}  // namespace

TriangleMesh benchmarkMesh(const std::string& path, size_t minTriangles, std::string& description) {
    TriangleMesh mesh;
    std::filesystem::path file = path;
    if (file.empty()) file = std::filesystem::path(STRAHL_SHARED_DATA) / "stanford-armadillo/Armadillo.ply";
    if (std::filesystem::exists(file)) {
        mesh = loadMeshFile(file).mesh;
        description = file.filename().string();
    } else {
        mesh = uvSphere(512, 1024);
        description = "procedural sphere (../shared/data not found)";
    }
    int levels = 0;
    while (mesh.triangleCount() < minTriangles) {
        mesh = subdivideMidpoints(mesh);
        ++levels;
    }
    if (levels) description += " subdivided " + std::to_string(levels) + "x";
    mesh.reservePadding();
    return mesh;
}

Camera frontCamera(const Bounds3& bounds, int size) {
    const float radius = 0.5f * glm::length(bounds.diagonal());
    const Vec3 eye = bounds.center() + Vec3(0.0f, 0.0f, 1.5f * radius);
    return Camera(CameraFrame::lookAt(eye, bounds.center(), Vec3(0, 1, 0)), Projection::Perspective,
                  Camera::windowFromFov(glm::radians(40.0f), 1.0f, size, size), 1.0f, size, size);
}

std::string takeOption(int& argc, char** argv, const char* name) {
    for (int i = 1; i + 1 < argc; ++i) {
        if (std::strcmp(argv[i], name) == 0) {
            std::string path = argv[i + 1];
            for (int j = i; j + 2 <= argc; ++j) argv[j] = argv[j + 2];
            argc -= 2;
            return path;
        }
    }
    return {};
}

}  // namespace strahl::bench
