// EmbreeSphereAccel: spheres as Embree's built-in sphere points, the baseline
// for the implicit sphere (see embree_spheres.h). Everything but the geometry —
// device, scene, queries, packet layout — is EmbreeSceneAccel's.

#include "strahl/accel/embree_spheres.h"

#include <cmath>
#include <cstring>

#include "embree_scene.h"
#include "strahl/core/error.h"

namespace strahl {

namespace {

static_assert(sizeof(Vec4) == 4 * sizeof(float), "spheres are copied as RTC_FORMAT_FLOAT4");

class EmbreeSphereAccel final : public EmbreeSceneAccel {
public:
    EmbreeSphereAccel(std::span<const Vec4> spheres, const AccelBuildOptions& options)
        : EmbreeSceneAccel(options) {
        Bounds3 bounds;
        for (size_t i = 0; i < spheres.size(); ++i) {
            const Vec4& s = spheres[i];
            if (!isFinite(Vec3(s)) || !std::isfinite(s.w))
                fail("sphere ", i, ": centre or radius is not finite");
            if (!(s.w > 0.0f)) fail("sphere ", i, ": radius must be > 0 (got ", s.w, ")");
            bounds.expand(Vec3(s) - s.w);
            bounds.expand(Vec3(s) + s.w);
        }
        if (!spheres.empty()) {
            if (!rtcGetDeviceProperty(device(), RTC_DEVICE_PROPERTY_POINT_GEOMETRY_SUPPORTED))
                fail("Embree: this Embree was built without point geometry (spheres)");
            RTCGeometry geom = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
            void* dst = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                sizeof(Vec4), spheres.size());
            if (dst) std::memcpy(dst, spheres.data(), spheres.size_bytes());
            attach(geom, 0, bounds, "adding the spheres");
        }
        commit();
    }
};

}  // namespace

std::unique_ptr<Accel> buildEmbreeSphereAccel(std::span<const Vec4> spheres,
                                              const AccelBuildOptions& options) {
    return std::make_unique<EmbreeSphereAccel>(spheres, options);
}

}  // namespace strahl
