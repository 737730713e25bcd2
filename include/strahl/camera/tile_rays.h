#pragma once
// The tiled SIMD ray generator: a tile of the image is walked in blocks of
// neighbouring pixels, one camera-ray packet per block and sample, so the rays
// of a packet are coherent (Embree's renderTileStandardStream idea).
// Lanes cover 4 x 4 pixels for 16-wide packets and 4 x 2 for 8-wide ones.
//
// Sample positions: with one sample per pixel the ray goes through the pixel
// centre (i + 0.5, j + 0.5), exactly the textbook image-order ray; with more,
// each sample is offset from the centre by the pixel filter's importance
// sampling (core/filter.h; the default box of radius 0.5 is a uniform jitter
// inside the pixel) and credited to its own pixel with weight 1. The first
// two dimension pairs of the sample's low-discrepancy sampler (core/sampler.h,
// seeded from seed, pixel and sample index only, so images never depend on the
// thread count or tile order) give the filter offset and the thin-lens point;
// the sampler, positioned after them, is handed to the integrator. In a scene
// with motion a third pair gives the ray's time within the camera's shutter
// (so a scene at rest keeps its sampling pattern).

#include <cstdint>
#include <vector>

#include "strahl/camera/camera.h"
#include "strahl/core/packet.h"
#include "strahl/core/filter.h"
#include "strahl/core/pixel_rect.h"
#include "strahl/core/sampler.h"

namespace strahl {

template <int N>
struct CameraPacket {
    static constexpr int kBlockWidth = 4;
    static constexpr int kBlockHeight = N / 4;

    RayHitPacket<N> rays;
    alignas(64) int valid[N];  // -1 active, 0 inactive (Embree's convention)
    int px[N], py[N];
    Sampler sampler[N];
};

class TileRayGenerator {
public:
    // motion: whether camera rays sample a time in the camera's shutter (the
    // scene has something moving).
    TileRayGenerator(const Camera& camera, uint64_t seed, int spp,
                     PixelFilter filter = PixelFilter::box(), bool motion = false)
        : camera_(camera), seed_(seed), spp_(spp), filter_(std::move(filter)), motion_(motion) {}

    // Sample `s` of pixel (px, py); `sampler` is set to that sample's sampler, positioned after the camera's dimensions.
    Ray sampleRay(int px, int py, int s, Sampler& sampler) const;

    // Fills the packet for the block whose top-left pixel is (bx, by), clipped to
    // `tile` and to the pixels for which wanted(x, y) is true (adaptive
    // sampling skips the pixels it stopped). Returns the number of active lanes.
    template <int N, typename Wanted>
    int fillPacket(const PixelRect& tile, int bx, int by, int s, CameraPacket<N>& packet,
                   const Wanted& wanted) const;
    template <int N>
    int fillPacket(const PixelRect& tile, int bx, int by, int s, CameraPacket<N>& packet) const {
        return fillPacket(tile, bx, by, s, packet, [](int, int) { return true; });
    }

    // Every packet of `tile` for sample `s`, blocks row by row: what fillPacket
    // makes, kept, for callers that trace the same rays more than once.
    template <int N>
    std::vector<CameraPacket<N>> tilePackets(const PixelRect& tile, int s) const;

private:
    // Seeds `sampler` for sample `s` of pixel (px, py) and takes the camera's
    // two dimension pairs from it (the filter offset, then the lens point):
    // returns the sample's raster point and sets `lens` (the lens centre,
    // (0.5, 0.5), for a pinhole). sampleRay and fillPacket's pinhole path
    // share it, so both sample exactly alike.
    Vec2 cameraSample(int px, int py, int s, Sampler& sampler, Vec2& lens) const;

    const Camera& camera_;
    uint64_t seed_;
    int spp_;
    PixelFilter filter_;
    bool motion_;
};

template <int N, typename Wanted>
int TileRayGenerator::fillPacket(const PixelRect& tile, int bx, int by, int s,
                                 CameraPacket<N>& packet, const Wanted& wanted) const {
    // The common case, a pinhole at rest, takes sampleRay's samplers and
    // raster points lane by lane and then makes all the packet's rays at once
    // (bit for bit sampleRay's; tested). A lens or motion goes lane by lane.
    const bool pinholeAtRest = camera_.apertureRadius() == 0.0f && !motion_;
    alignas(16) float rasterX[N], rasterY[N];
    int active = 0;
    for (int lane = 0; lane < N; ++lane) {
        const int x = bx + lane % CameraPacket<N>::kBlockWidth;
        const int y = by + lane / CameraPacket<N>::kBlockWidth;
        packet.px[lane] = x;
        packet.py[lane] = y;
        const bool isActive = x < tile.x1 && y < tile.y1 && wanted(x, y);
        packet.valid[lane] = isActive ? -1 : 0;
        active += isActive;
        rasterX[lane] = rasterY[lane] = 0.0f;
        if (!isActive) {
            packet.rays.setRay(lane, Ray{});  // well-defined contents for inactive lanes
        } else if (pinholeAtRest) {
            Vec2 lens;
            const Vec2 raster = cameraSample(x, y, s, packet.sampler[lane], lens);
            rasterX[lane] = raster.x;
            rasterY[lane] = raster.y;
        } else {
            packet.rays.setRay(lane, sampleRay(x, y, s, packet.sampler[lane]));
        }
    }
    if (pinholeAtRest) {
        auto& rays = packet.rays;
        camera_.generatePinholeRays(rasterX, rasterY, rays);  // origins and directions of every lane
        for (int lane = 0; lane < N; ++lane) {
            const Ray ray{Vec3(rays.org_x[lane], rays.org_y[lane], rays.org_z[lane]),
                          Vec3(rays.dir_x[lane], rays.dir_y[lane], rays.dir_z[lane])};
            rays.setRay(lane, packet.valid[lane] ? ray : Ray{});
        }
    }
    return active;
}

template <int N>
std::vector<CameraPacket<N>> TileRayGenerator::tilePackets(const PixelRect& tile, int s) const {
    std::vector<CameraPacket<N>> packets;
    for (int by = tile.y0; by < tile.y1; by += CameraPacket<N>::kBlockHeight) {
        for (int bx = tile.x0; bx < tile.x1; bx += CameraPacket<N>::kBlockWidth) {
            packets.emplace_back();
            fillPacket(tile, bx, by, s, packets.back());
        }
    }
    return packets;
}

}  // namespace strahl
