#pragma once
// The Mrays/s figure the accelerator benchmarks share: one pass of single
// camera rays through the pixel centres of a size x size image, parallel over
// rows.

#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstddef>

#include "strahl/accel/accel.h"
#include "strahl/camera/camera.h"

namespace strahl::bench {

// Mrays/s of the pass; `hits` receives how many rays hit something.
inline double traceCameraRays(const Accel& accel, const Camera& camera, int size, size_t& hits) {
    std::atomic<size_t> count{0};
    const auto t0 = std::chrono::steady_clock::now();
    tbb::parallel_for(0, size, [&](int y) {
        size_t local = 0;
        for (int x = 0; x < size; ++x)
            if (accel.intersect(camera.generateRay(float(x) + 0.5f, float(y) + 0.5f)).valid()) ++local;
        count += local;
    });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    hits = count;
    return double(size) * size / seconds * 1e-6;
}

}  // namespace strahl::bench
