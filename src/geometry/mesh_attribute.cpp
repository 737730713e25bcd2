#include "strahl/geometry/mesh_attribute.h"

#include "strahl/geometry/triangle_mesh.h"

namespace strahl {

const MeshAttribute* MeshAttributePoint::find(std::string_view name) const {
    if (!mesh) return nullptr;
    for (const MeshAttribute& a : mesh->attributes)
        if (a.name == name) return &a;
    return nullptr;
}

Vec4 MeshAttributePoint::value(std::string_view name) const {
    const MeshAttribute* a = find(name);
    if (!a) return Vec4(0.0f);
    const auto n = size_t(a->channels);
    float v[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    if (a->scope == MeshAttribute::Scope::Face) {
        for (size_t c = 0; c < n; ++c) v[c] = a->values[triangle * n + c];
    } else {
        const uint32_t* corner = &mesh->indices[3 * size_t(triangle)];
        const float b0 = 1.0f - barycentric.x - barycentric.y;
        for (size_t c = 0; c < n; ++c)
            v[c] = b0 * a->values[corner[0] * n + c] + barycentric.x * a->values[corner[1] * n + c] +
                   barycentric.y * a->values[corner[2] * n + c];
    }
    if (n == 1) v[1] = v[2] = v[0];
    return Vec4(v[0], v[1], v[2], v[3]);
}

}  // namespace strahl
