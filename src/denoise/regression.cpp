#include "regression.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace strahl::denoise_detail {

namespace {

constexpr int kTileSize = 32;  // pixels per tile side
constexpr int kTilePixels = kTileSize * kTileSize;
// The stride between the planes of a tile's sums: a multiple of 4 KiB would
// put all of them in the same L1 cache set (and alias in the store buffer),
// which made the accumulation ~30x slower; one cache line more avoids that.
constexpr int kSumStride = kTilePixels + 16;
constexpr int kDim = kFeatureCount + 1;              // the fit's unknowns per colour channel
constexpr int kNormalTerms = kDim * (kDim + 1) / 2;  // the symmetric X^T W X
constexpr int kRhsTerms = kDim * 3;                  // X^T W c
constexpr int kTerms = kNormalTerms + kRhsTerms;
// Ridge added to the feature diagonal, relative to the window's total weight:
// a feature that varies by less than about sqrt(kRidge) = 0.03 over the
// window hardly enters the fit (a fit to noise there would only add
// variance); features of real edges (albedo, normal, depth steps of 0.1 and
// more) are fitted almost unregularised.
constexpr double kRidge = 1e-3;

// One offset's values for the pixels [xa, xb) of a tile row (at most
// kTileSize): v[0] = 1, v[1..7] the feature differences f(q) - f(p),
// v[8..10] the colour at q.
struct RowValues {
    alignas(64) float v[kDim + 3][kTileSize];
    int n = 0;
};

void gatherRow(RowValues& row, const std::array<const float*, kFeatureCount>& fp,
               const std::array<const float*, kFeatureCount>& fq,
               const std::array<const float*, 3>& cq, int xa, int xb) {
    const int n = row.n = xb - xa;
    for (int x = 0; x < n; ++x) row.v[0][x] = 1.0f;
    for (int k = 0; k < kFeatureCount; ++k) {
        const float* __restrict q = fq[k] + xa;
        const float* __restrict p = fp[k] + xa;
        for (int x = 0; x < n; ++x) row.v[k + 1][x] = q[x] - p[x];
    }
    for (int c = 0; c < 3; ++c) {
        const float* __restrict q = cq[c] + xa;
        for (int x = 0; x < n; ++x) row.v[kDim + c][x] = q[x];
    }
}

// Adds w v v^T and w v c^T for one row into one candidate's sums (planar,
// kSumStride apart); every term is one simple loop over x that vectorises.
void accumulateRow(float* __restrict sums, const float* __restrict w, const RowValues& row) {
    const int n = row.n;
    alignas(64) float wv[kDim][kTileSize];  // w times v[a]
    for (int a = 0; a < kDim; ++a)
        for (int x = 0; x < n; ++x) wv[a][x] = w[x] * row.v[a][x];
    int term = 0;
    for (int a = 0; a < kDim; ++a)
        for (int b = a; b < kDim; ++b, ++term) {
            float* __restrict s = sums + term * kSumStride;
            for (int x = 0; x < n; ++x) s[x] += wv[a][x] * row.v[b][x];
        }
    for (int a = 0; a < kDim; ++a)
        for (int c = 0; c < 3; ++c, ++term) {
            float* __restrict s = sums + term * kSumStride;
            for (int x = 0; x < n; ++x) s[x] += wv[a][x] * row.v[kDim + c][x];
        }
}

// Solves (A + ridge) beta = B for one pixel by Cholesky in double; falls back
// to the zero-order fit (the weighted mean) if the system is not positive
// definite. beta is kDim x 3, row-major.
void solvePixel(const float* sums, int i, float beta[kDim * 3]) {
    double A[kDim][kDim], B[kDim][3];
    int term = 0;
    for (int a = 0; a < kDim; ++a)
        for (int b = a; b < kDim; ++b) A[a][b] = A[b][a] = sums[(term++) * kSumStride + i];
    for (int a = 0; a < kDim; ++a)
        for (int c = 0; c < 3; ++c) B[a][c] = sums[(term++) * kSumStride + i];
    const double total = A[0][0];
    for (int a = 1; a < kDim; ++a) A[a][a] += kRidge * total;

    double L[kDim][kDim] = {};
    bool ok = total > 0.0;
    for (int j = 0; j < kDim && ok; ++j) {
        double d = A[j][j];
        for (int k = 0; k < j; ++k) d -= L[j][k] * L[j][k];
        if (!(d > 1e-12 * total)) {
            ok = false;
            break;
        }
        L[j][j] = std::sqrt(d);
        for (int r = j + 1; r < kDim; ++r) {
            double s = A[r][j];
            for (int k = 0; k < j; ++k) s -= L[r][k] * L[j][k];
            L[r][j] = s / L[j][j];
        }
    }
    if (!ok) {
        for (int a = 0; a < kDim * 3; ++a) beta[a] = 0.0f;
        for (int c = 0; c < 3; ++c)
            beta[c] = total > 0.0 ? static_cast<float>(B[0][c] / total) : 0.0f;
        return;
    }
    for (int c = 0; c < 3; ++c) {
        double y[kDim];
        for (int r = 0; r < kDim; ++r) {
            double s = B[r][c];
            for (int k = 0; k < r; ++k) s -= L[r][k] * y[k];
            y[r] = s / L[r][r];
        }
        for (int r = kDim - 1; r >= 0; --r) {
            double s = y[r];
            for (int k = r + 1; k < kDim; ++k) s -= L[k][r] * beta[k * 3 + c];
            beta[r * 3 + c] = static_cast<float>(s / L[r][r]);
        }
    }
}

}  // namespace

std::vector<PlanarImage> collaborativeRegression(const PlanarImage& color,
                                                 const PlanarImage& features,
                                                 const PatchWeights& weights, int windowRadius,
                                                 const std::vector<float>& bandwidths) {
    const int W = color.width, H = color.height;
    const int K = static_cast<int>(bandwidths.size());
    std::vector<float> inverseK2;  // D_k = D_1 / k^2 (patch_weights.h)
    for (float k : bandwidths) inverseK2.push_back(1.0f / (k * k));
    const std::vector<Region> tiles = imageTiles(W, H, kTileSize);
    const size_t candidateSums = size_t(kTerms) * kSumStride;

    // Pass 1: every pixel's fit, for every candidate.
    std::vector<PlanarImage> betas(size_t(K), PlanarImage(W, H, kDim * 3));
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const auto& range) {
        std::vector<float> scratch, distance(kTilePixels), w(kTileSize);
        std::vector<float> sums(candidateSums * size_t(K));
        RowValues row;
        for (size_t t = range.begin(); t != range.end(); ++t) {
            const Region& tile = tiles[t];
            std::fill(sums.begin(), sums.end(), 0.0f);
            for (int dy = -windowRadius; dy <= windowRadius; ++dy) {
                for (int dx = -windowRadius; dx <= windowRadius; ++dx) {
                    weights.distances(tile, dx, dy, distance.data(), scratch);
                    const int xa = std::max(tile.x0, -dx), xb = std::min(tile.x1, W - dx);
                    for (int y = tile.y0; y < tile.y1; ++y) {
                        const int qy = y + dy;
                        if (qy < 0 || qy >= H || xa >= xb) continue;
                        std::array<const float*, kFeatureCount> fp, fq;
                        for (int k = 0; k < kFeatureCount; ++k) {
                            fp[k] = features.plane(k) + size_t(y) * size_t(W);
                            fq[k] = features.plane(k) + size_t(qy) * size_t(W) + dx;
                        }
                        std::array<const float*, 3> cq;
                        for (int c = 0; c < 3; ++c)
                            cq[c] = color.plane(c) + size_t(qy) * size_t(W) + dx;
                        gatherRow(row, fp, fq, cq, xa, xb);
                        // The tile's rows hold tile.width() pixels.
                        const int first = (y - tile.y0) * tile.width() + (xa - tile.x0);
                        for (int k = 0; k < K; ++k) {
                            for (int x = 0; x < row.n; ++x)
                                w[size_t(x)] =
                                    patchWeight(distance[size_t(first + x)] * inverseK2[size_t(k)]);
                            accumulateRow(sums.data() + size_t(k) * candidateSums + size_t(first),
                                          w.data(), row);
                        }
                    }
                }
            }
            for (int k = 0; k < K; ++k)
                for (int y = tile.y0; y < tile.y1; ++y)
                    for (int x = tile.x0; x < tile.x1; ++x) {
                        float beta[kDim * 3];
                        solvePixel(sums.data() + size_t(k) * candidateSums,
                                   (y - tile.y0) * tile.width() + (x - tile.x0), beta);
                        for (int j = 0; j < kDim * 3; ++j) betas[size_t(k)].at(j, x, y) = beta[j];
                    }
        }
    });

    // Pass 2: every pixel averages the fits of the windows that contain it.
    std::vector<PlanarImage> out(size_t(K), PlanarImage(W, H, 3));
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const auto& range) {
        std::vector<float> scratch, distance(kTilePixels);
        std::vector<float> total(size_t(K) * kTilePixels), sums(size_t(K) * 3 * kSumStride);
        alignas(64) float diff[kFeatureCount][kTileSize];
        for (size_t t = range.begin(); t != range.end(); ++t) {
            const Region& tile = tiles[t];
            std::fill(total.begin(), total.end(), 0.0f);
            std::fill(sums.begin(), sums.end(), 0.0f);
            for (int dy = -windowRadius; dy <= windowRadius; ++dy) {
                for (int dx = -windowRadius; dx <= windowRadius; ++dx) {
                    // q in the tile, p = q - (dx, dy): D(p, q) at q's place.
                    const Region shifted{tile.x0 - dx, tile.y0 - dy, tile.x1 - dx, tile.y1 - dy};
                    weights.distances(shifted, dx, dy, distance.data(), scratch);
                    const int xa = std::max(tile.x0, dx), xb = std::min(tile.x1, W + dx);
                    const int n = xb - xa;
                    for (int y = tile.y0; y < tile.y1; ++y) {
                        const int py = y - dy;
                        if (py < 0 || py >= H || n <= 0) continue;
                        const size_t qRow = size_t(y) * size_t(W) + size_t(xa);
                        const size_t pRow = size_t(py) * size_t(W) + size_t(xa - dx);
                        for (int f = 0; f < kFeatureCount; ++f) {
                            const float* __restrict fq = features.plane(f) + qRow;
                            const float* __restrict fp = features.plane(f) + pRow;
                            for (int x = 0; x < n; ++x) diff[f][x] = fq[x] - fp[x];
                        }
                        const int first = (y - tile.y0) * tile.width() + (xa - tile.x0);
                        for (int k = 0; k < K; ++k) {
                            const PlanarImage& beta = betas[size_t(k)];
                            float* __restrict tot = total.data() + size_t(k) * kTilePixels + first;
                            const float* __restrict d = distance.data() + first;
                            alignas(64) float w[kTileSize];
                            for (int x = 0; x < n; ++x) {
                                w[x] = patchWeight(d[x] * inverseK2[size_t(k)]);
                                tot[x] += w[x];
                            }
                            for (int c = 0; c < 3; ++c) {
                                alignas(64) float fit[kTileSize];
                                const float* __restrict b0 = beta.plane(c) + pRow;
                                for (int x = 0; x < n; ++x) fit[x] = b0[x];
                                for (int f = 0; f < kFeatureCount; ++f) {
                                    const float* __restrict bf = beta.plane((f + 1) * 3 + c) + pRow;
                                    for (int x = 0; x < n; ++x) fit[x] += bf[x] * diff[f][x];
                                }
                                float* __restrict s =
                                    sums.data() + (size_t(k) * 3 + size_t(c)) * kSumStride + first;
                                for (int x = 0; x < n; ++x) s[x] += w[x] * fit[x];
                            }
                        }
                    }
                }
            }
            for (int k = 0; k < K; ++k)
                for (int c = 0; c < 3; ++c)
                    for (int y = tile.y0; y < tile.y1; ++y)
                        for (int x = tile.x0; x < tile.x1; ++x) {
                            const size_t i = size_t((y - tile.y0) * tile.width() + (x - tile.x0));
                            out[size_t(k)].at(c, x, y) =
                                sums[(size_t(k) * 3 + size_t(c)) * kSumStride + i] /
                                total[size_t(k) * kTilePixels + i];
                        }
        }
    });
    return out;
}

}  // namespace strahl::denoise_detail
