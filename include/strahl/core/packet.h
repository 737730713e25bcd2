#pragma once
// SoA ray/hit packets of N = 8 or 16 lanes. The field order mirrors Embree 3's
// RTCRayHitNt so the accel module can hand a packet to rtcIntersect8/16 without
// copying; accel/ static_asserts every offset, so a change here that breaks the
// layout fails to compile instead of silently corrupting rays.

#include <cstdint>

#include "strahl/core/ray.h"

namespace strahl {

template <int N>
struct alignas(64) RayHitPacket {
    static_assert(N == 8 || N == 16, "packets have 8 or 16 lanes");
    static constexpr int kWidth = N;
    // ray
    float org_x[N], org_y[N], org_z[N];
    float tnear[N];
    float dir_x[N], dir_y[N], dir_z[N];
    float time[N];
    float tfar[N];
    uint32_t mask[N];
    uint32_t id[N];
    uint32_t flags[N];
    // hit
    float Ng_x[N], Ng_y[N], Ng_z[N];
    float u[N], v[N];
    uint32_t primID[N];
    uint32_t geomID[N];
    uint32_t instID[N];

    void setRay(int lane, const Ray& r) {
        org_x[lane] = r.origin.x;
        org_y[lane] = r.origin.y;
        org_z[lane] = r.origin.z;
        dir_x[lane] = r.dir.x;
        dir_y[lane] = r.dir.y;
        dir_z[lane] = r.dir.z;
        tnear[lane] = r.tnear;
        tfar[lane] = r.tfar;
        time[lane] = r.time;
        mask[lane] = 0xFFFFFFFFu;
        id[lane] = static_cast<uint32_t>(lane);
        flags[lane] = 0;
        geomID[lane] = kInvalidId;
        primID[lane] = kInvalidId;
        instID[lane] = kInvalidId;
    }
    Ray ray(int lane) const {
        Ray r;
        r.origin = Vec3(org_x[lane], org_y[lane], org_z[lane]);
        r.dir = Vec3(dir_x[lane], dir_y[lane], dir_z[lane]);
        r.tnear = tnear[lane];
        r.tfar = tfar[lane];
        r.time = time[lane];
        return r;
    }
    // Writes a lane's hit as Embree would: a miss sets only geomID (tfar and
    // the rest of the lane stay as they were).
    void setHit(int lane, const Hit& h) {
        geomID[lane] = h.geomID;
        if (!h.valid()) return;
        tfar[lane] = h.t;
        u[lane] = h.u;
        v[lane] = h.v;
        Ng_x[lane] = h.Ng.x;
        Ng_y[lane] = h.Ng.y;
        Ng_z[lane] = h.Ng.z;
        primID[lane] = h.primID;
        instID[lane] = h.instID;
    }
    Hit hit(int lane) const {
        Hit h;
        if (geomID[lane] == kInvalidId) return h;
        h.t = tfar[lane];
        h.u = u[lane];
        h.v = v[lane];
        h.Ng = Vec3(Ng_x[lane], Ng_y[lane], Ng_z[lane]);
        h.geomID = geomID[lane];
        h.primID = primID[lane];
        h.instID = instID[lane];
        return h;
    }
};

using RayHitPacket8 = RayHitPacket<8>;
using RayHitPacket16 = RayHitPacket<16>;

}  // namespace strahl
