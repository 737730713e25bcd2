#include "patch_weights.h"

#include <algorithm>
#include <cmath>

namespace strahl::denoise_detail {

namespace {

// Keeps 0/0 finite where guide and variance are both exactly equal (a black
// background): Rousselle et al. use the same tiny constant.
constexpr float kEpsilon = 1e-10f;
// Per-pixel distances are capped here before the running box sums: a pair of
// noise-free pixels that differ gives a distance of order 1/kEpsilon, which
// would swamp the float running sum (adding and later subtracting 1e12
// leaves its rounding error behind). Any capped pixel already makes its
// patch's mean distance >= kMaxDistance / (channels (2f+1)^2) >= 20 for the
// largest patches used (3 channels, 7 x 7), a weight below e^-20.
constexpr float kMaxDistance = 3000.0f;

int clampTo(int v, int n) {
    return std::clamp(v, 0, n - 1);
}

}  // namespace

PatchWeights::PatchWeights(const PlanarImage& guide, const PlanarImage& variance, int patchRadius,
                           float k)
    : guide_(guide), variance_(variance), f_(patchRadius), k2_(k * k) {}

void PatchWeights::distances(const Region& region, int dx, int dy, float* out,
                             std::vector<float>& scratch) const {
    const int W = guide_.width, H = guide_.height, C = guide_.channels;
    // Per-pixel distances over the region grown by the patch radius, then a
    // separable box sum over the patch.
    const int ew = region.width() + 2 * f_, eh = region.height() + 2 * f_;
    const int rw = region.width();
    scratch.assign(size_t(ew) * size_t(eh) + size_t(rw) * size_t(eh) + size_t(rw) + 4 * size_t(ew),
                   0.0f);
    float* dist = scratch.data();
    float* rows = dist + size_t(ew) * size_t(eh);
    float* column = rows + size_t(rw) * size_t(eh);
    float* gathered = column + rw;  // clamped copies of one row of gp, gq, vp, vq

    // Whether the grown region's columns, for p and for q, lie inside the image:
    // then the rows are read in place, else through clamped copies.
    const int x0 = region.x0 - f_;
    const bool inside = x0 >= 0 && x0 + ew <= W && x0 + dx >= 0 && x0 + dx + ew <= W;
    for (int ey = 0; ey < eh; ++ey) {
        const int py = clampTo(region.y0 - f_ + ey, H);
        const int qy = clampTo(region.y0 - f_ + ey + dy, H);
        float* __restrict d = dist + size_t(ey) * size_t(ew);
        for (int c = 0; c < C; ++c) {
            const float* gp = guide_.plane(c) + size_t(py) * size_t(W);
            const float* gq = guide_.plane(c) + size_t(qy) * size_t(W);
            const float* vp = variance_.plane(c) + size_t(py) * size_t(W);
            const float* vq = variance_.plane(c) + size_t(qy) * size_t(W);
            const float *a0, *a1, *b0, *b1;  // gp, gq, vp, vq from column x0 on
            if (inside) {
                a0 = gp + x0;
                a1 = gq + x0 + dx;
                b0 = vp + x0;
                b1 = vq + x0 + dx;
            } else {
                float* g = gathered;
                for (int ex = 0; ex < ew; ++ex) {
                    const int px = clampTo(x0 + ex, W), qx = clampTo(x0 + ex + dx, W);
                    g[ex] = gp[px];
                    g[ew + ex] = gq[qx];
                    g[2 * ew + ex] = vp[px];
                    g[3 * ew + ex] = vq[qx];
                }
                a0 = g;
                a1 = g + ew;
                b0 = g + 2 * ew;
                b1 = g + 3 * ew;
            }
            for (int ex = 0; ex < ew; ++ex) {
                const float diff = a0[ex] - a1[ex];
                const float va = b0[ex], vb = b1[ex];
                d[ex] += std::min(kMaxDistance, (diff * diff - (va + std::min(va, vb))) /
                                                    (kEpsilon + k2_ * (va + vb)));
            }
        }
    }

    // Horizontal running sums over 2f+1 pixels, then vertical ones, row by row.
    // The running sums drift by rounding in an order that is fixed, so the
    // weights stay deterministic.
    const int n = 2 * f_ + 1;
    for (int ey = 0; ey < eh; ++ey) {
        const float* d = dist + size_t(ey) * size_t(ew);
        float* r = rows + size_t(ey) * size_t(rw);
        float sum = 0.0f;
        for (int i = 0; i < n; ++i) sum += d[i];
        r[0] = sum;
        for (int x = 1; x < rw; ++x) {
            sum += d[x + n - 1] - d[x - 1];
            r[x] = sum;
        }
    }
    for (int x = 0; x < rw; ++x) column[x] = 0.0f;
    for (int i = 0; i < n; ++i)
        for (int x = 0; x < rw; ++x) column[x] += rows[size_t(i) * size_t(rw) + size_t(x)];
    const float norm = 1.0f / float(C * n * n);
    for (int y = 0; y < region.height(); ++y) {
        float* __restrict o = out + size_t(y) * size_t(rw);
        if (y > 0) {
            const float* add = rows + size_t(y + n - 1) * size_t(rw);
            const float* sub = rows + size_t(y - 1) * size_t(rw);
            for (int x = 0; x < rw; ++x) column[x] += add[x] - sub[x];
        }
        for (int x = 0; x < rw; ++x) o[x] = std::max(0.0f, column[x] * norm);
        // p or q = p + (dx, dy) outside the image: no weight.
        const int py = region.y0 + y, qy = py + dy;
        if (py < 0 || py >= H || qy < 0 || qy >= H) {
            std::fill(o, o + rw, kNoWeight);
            continue;
        }
        for (int x = 0; x < rw; ++x) {
            const int px = region.x0 + x;
            if (px < 0 || px >= W || px + dx < 0 || px + dx >= W) o[x] = kNoWeight;
        }
    }
}

}  // namespace strahl::denoise_detail
