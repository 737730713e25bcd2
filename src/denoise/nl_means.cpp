#include "nl_means.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace strahl::denoise_detail {

namespace {
constexpr int kNlMeansTileSize = 32;  // pixels per tile side: the tile's sums stay in cache
}

PlanarImage nlMeans(const PlanarImage& data, const PatchWeights& weights, int windowRadius) {
    const int W = data.width, H = data.height, C = data.channels;
    PlanarImage out(W, H, C);
    const std::vector<Region> tiles = imageTiles(W, H, kNlMeansTileSize);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const auto& range) {
        std::vector<float> scratch, w, sums, total;
        for (size_t t = range.begin(); t != range.end(); ++t) {
            const Region& tile = tiles[t];
            const size_t n = tile.pixels();
            w.resize(n);
            sums.assign(n * size_t(C), 0.0f);
            total.assign(n, 0.0f);
            for (int dy = -windowRadius; dy <= windowRadius; ++dy) {
                for (int dx = -windowRadius; dx <= windowRadius; ++dx) {
                    weights.distances(tile, dx, dy, w.data(), scratch);
                    for (float& v : w) v = patchWeight(v);
                    for (int y = tile.y0; y < tile.y1; ++y) {
                        const int qy = y + dy;
                        if (qy < 0 || qy >= H) continue;
                        // Columns whose q = p + dx lies in the image.
                        const int xa = std::max(tile.x0, -dx), xb = std::min(tile.x1, W - dx);
                        const size_t row = size_t(y - tile.y0) * size_t(tile.width());
                        float* tot = total.data() + row;
                        const float* wr = w.data() + row;
                        for (int x = xa; x < xb; ++x) tot[x - tile.x0] += wr[x - tile.x0];
                        for (int c = 0; c < C; ++c) {
                            const float* src = data.plane(c) + size_t(qy) * size_t(W);
                            float* s = sums.data() + size_t(c) * n + row;
                            for (int x = xa; x < xb; ++x)
                                s[x - tile.x0] += wr[x - tile.x0] * src[x + dx];
                        }
                    }
                }
            }
            for (int c = 0; c < C; ++c)
                for (int y = tile.y0; y < tile.y1; ++y)
                    for (int x = tile.x0; x < tile.x1; ++x) {
                        const size_t i =
                            size_t(y - tile.y0) * size_t(tile.width()) + size_t(x - tile.x0);
                        out.at(c, x, y) = sums[size_t(c) * n + i] / total[i];
                    }
        }
    });
    return out;
}

}  // namespace strahl::denoise_detail
