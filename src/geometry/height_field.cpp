// Height fields: bicubic Catmull–Rom over a grid of samples; the math is in
// include/strahl/geometry/height_field.h.
//
// Why 9/32 bounds the overshoot. On a cell (t, s ∈ [0,1]) h = Σ w_a(t) w_b(s) p_ab
// with Σ_a w_a = 1. w_1, w_2 ≥ 0 and w_0 = −t(1−t)²/2, w_3 = −t²(1−t)/2 ≤ 0,
// so the negative weights of one direction sum to N(t) = t(1−t)/2 ≤ 1/8 and the
// positive ones to 1 + N. With m ≤ p_ab ≤ M:
//     h − M = Σ w_a w_b (p_ab − M) ≤ Σ_{w_a w_b < 0} |w_a w_b| (M − m)
//           = (N(t)(1 + N(s)) + (1 + N(t))N(s)) (M − m) ≤ (2·1/8 + 2/64)(M − m) = 9/32 (M − m),
// and h − m ≥ −9/32 (M − m) alike. The grid coordinate is clamped to the grid
// before evaluation, so t and s never leave [0,1].

#include "strahl/geometry/height_field.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <utility>

#include "dual_value.h"
#include "strahl/core/error.h"
#include "strahl/geometry/bezier_patches.h"

namespace strahl {

namespace {

using geometry_detail::valueOf;

// A sub-rectangle touching at most this many cells is bounded cell by cell
// (tight); larger ones by the sample range plus overshoot (constant time).
constexpr size_t kMaxExactCells = 16;

// The Catmull–Rom weights w_0..w_3 at t (header comment), written so that
// t = 0 gives exactly (0, 1, 0, 0) and t = 1 exactly (0, 0, 1, 0).
template <class T>
std::array<T, 4> weights(const T& t) {
    return {T(0.5) * t * ((T(2.0) - t) * t - T(1.0)),
            T(0.5) * (T(2.0) + t * t * (T(3.0) * t - T(5.0))),
            T(0.5) * t * (T(1.0) + t * (T(4.0) - T(3.0) * t)), T(0.5) * t * t * (t - T(1.0))};
}

std::array<double, 4> weightDerivatives(double t) {
    return {0.5 * (-1.0 + t * (4.0 - 3.0 * t)), 0.5 * t * (9.0 * t - 10.0),
            0.5 * (1.0 + t * (8.0 - 9.0 * t)), 0.5 * t * (3.0 * t - 2.0)};
}

// Catmull–Rom through p1, p2 (neighbours p0, p3) in Bézier form over [0,1].
std::array<double, 4> catmullRomToBezier(double p0, double p1, double p2, double p3) {
    return {p1, p1 + (p2 - p0) / 6.0, p2 - (p3 - p1) / 6.0, p2};
}

class HeightField final : public ParametricSurfaceOf<HeightField> {
public:
    HeightField(std::vector<float> heights, size_t columns, size_t rows, double sizeX, double sizeY,
                double heightScale)
        : heights_(std::move(heights)),
          columns_(columns),
          rows_(rows),
          sizeX_(sizeX),
          sizeY_(sizeY),
          scale_(heightScale) {
        domain_ = {-0.5 * sizeX, 0.5 * sizeX, -0.5 * sizeY, 0.5 * sizeY, false, false};
        scaleX_ = static_cast<double>(columns - 1) / sizeX;
        scaleY_ = static_cast<double>(rows - 1) / sizeY;
        buildPyramid();
    }

    const ParamDomain& domain() const override { return domain_; }

    // double and Dual2.
    template <class T>
    Point3<T> eval(uint32_t, const T& u, const T& v) const {
        const T gx = clampGrid((u - T(domain_.u0)) * T(scaleX_), columns_);
        const T gy = clampGrid((T(domain_.v1) - v) * T(scaleY_), rows_);
        const size_t cx = cellOf(valueOf(gx), columns_), cy = cellOf(valueOf(gy), rows_);
        const std::array<T, 4> wx = weights(gx - T(static_cast<double>(cx)));
        const std::array<T, 4> wy = weights(gy - T(static_cast<double>(cy)));
        T h(0.0);
        for (size_t b = 0; b < 4; ++b) {
            T row(0.0);
            for (size_t a = 0; a < 4; ++a) row += wx[a] * T(sample(cx + a, cy + b));
            h += wy[b] * row;
        }
        return {u, v, T(scale_) * h};
    }

    Point3<num::Interval> eval(uint32_t, const num::Interval& u, const num::Interval& v) const {
        return {u, v, num::Interval(scale_) * heightRange(u, v)};
    }

    SurfacePoint partials(uint32_t, double u, double v) const override {
        double gx = (u - domain_.u0) * scaleX_, gy = (domain_.v1 - v) * scaleY_;
        double dgx = scaleX_, dgy = -scaleY_;  // d(grid)/du, d(grid)/dv
        const double topX = static_cast<double>(columns_ - 1),
                     topY = static_cast<double>(rows_ - 1);
        if (gx < 0.0 || gx > topX) gx = std::clamp(gx, 0.0, topX), dgx = 0.0;
        if (gy < 0.0 || gy > topY) gy = std::clamp(gy, 0.0, topY), dgy = 0.0;
        const size_t cx = cellOf(gx, columns_), cy = cellOf(gy, rows_);
        const double tx = gx - static_cast<double>(cx), ty = gy - static_cast<double>(cy);
        const std::array<double, 4> wx = weights(tx), wy = weights(ty);
        const std::array<double, 4> dx = weightDerivatives(tx), dy = weightDerivatives(ty);
        double h = 0.0, hx = 0.0, hy = 0.0;
        for (size_t b = 0; b < 4; ++b) {
            double row = 0.0, rowX = 0.0;
            for (size_t a = 0; a < 4; ++a) {
                const double p = sample(cx + a, cy + b);
                row += wx[a] * p;
                rowX += dx[a] * p;
            }
            h += wy[b] * row;
            hx += wy[b] * rowX;
            hy += dy[b] * row;
        }
        return {DVec3(u, v, scale_ * h), DVec3(1.0, 0.0, scale_ * hx * dgx),
                DVec3(0.0, 1.0, scale_ * hy * dgy)};
    }

    std::string describe() const override {
        return concat("height field ", columns_, " x ", rows_, " size ", sizeX_, " x ", sizeY_,
                      " scale ", scale_);
    }

private:
    struct Level {
        size_t width = 0, height = 0;
        std::vector<float> lo, hi;  // min and max of each 2^L x 2^L block
    };

    // The sample at column xPlus1 − 1, row yPlus1 − 1, clamped to the grid:
    // sample(cx + a, cy + b) is the one weight a, b of cell (cx, cy) applies
    // to (columns cx − 1 .. cx + 2, rows cy − 1 .. cy + 2).
    double sample(size_t xPlus1, size_t yPlus1) const {
        const size_t x = std::min(xPlus1 == 0 ? 0 : xPlus1 - 1, columns_ - 1);
        const size_t y = std::min(yPlus1 == 0 ? 0 : yPlus1 - 1, rows_ - 1);
        return heights_[y * columns_ + x];
    }

    template <class T>
    static T clampGrid(const T& g, size_t n) {
        const double top = static_cast<double>(n - 1);
        if (valueOf(g) < 0.0) return T(0.0);
        if (valueOf(g) > top) return T(top);
        return g;
    }

    // The cell whose cubic evaluates grid coordinate g ∈ [0, n − 1]: floor(g),
    // with the last sample in the last cell (NaN goes to cell 0).
    static size_t cellOf(double g, size_t n) {
        if (!(g > 0.0)) return 0;
        return std::min(static_cast<size_t>(g), n - 2);
    }

    // [lo, hi] of a grid coordinate computed as (x − origin)·scale, rounded
    // outwards (two roundings, ≤ 2^-52 relative) and clamped to [0, n − 1]
    // like the evaluation does.
    static std::pair<double, double> gridRange(double lo, double hi, size_t n) {
        const double top = static_cast<double>(n - 1);
        const double l = lo - (std::abs(lo) * 0x1p-50 + 1e-300);
        const double h = hi + (std::abs(hi) * 0x1p-50 + 1e-300);
        return {std::clamp(l, 0.0, top), std::clamp(h, 0.0, top)};
    }

    num::Interval heightRange(const num::Interval& u, const num::Interval& v) const {
        if (std::isnan(u.lo) || std::isnan(u.hi) || std::isnan(v.lo) || std::isnan(v.hi))
            return num::Interval::entire();
        // Outside the domain the surface is flat, so clamping the parameters
        // first loses nothing (and keeps infinite bounds out of the grid).
        const double uLo = std::clamp(u.lo, domain_.u0, domain_.u1);
        const double uHi = std::clamp(u.hi, domain_.u0, domain_.u1);
        const double vLo = std::clamp(v.lo, domain_.v0, domain_.v1);
        const double vHi = std::clamp(v.hi, domain_.v0, domain_.v1);
        // The grid coordinates grow with u and shrink with v.
        const auto [x0, x1] =
            gridRange((uLo - domain_.u0) * scaleX_, (uHi - domain_.u0) * scaleX_, columns_);
        const auto [y0, y1] =
            gridRange((domain_.v1 - vHi) * scaleY_, (domain_.v1 - vLo) * scaleY_, rows_);
        const size_t cx0 = cellOf(x0, columns_), cy0 = cellOf(y0, rows_);
        size_t cx1 = cellOf(x1, columns_), cy1 = cellOf(y1, rows_);
        // Ending on a sample: the cell before already reaches it.
        if (cx1 > cx0 && x1 == static_cast<double>(cx1)) --cx1;
        if (cy1 > cy0 && y1 == static_cast<double>(cy1)) --cy1;

        if ((cx1 - cx0 + 1) * (cy1 - cy0 + 1) <= kMaxExactCells) {
            num::Interval h;
            bool first = true;
            for (size_t cy = cy0; cy <= cy1; ++cy)
                for (size_t cx = cx0; cx <= cx1; ++cx) {
                    // Cell-local ranges; x − c is exact here (Sterbenz).
                    const auto cxd = static_cast<double>(cx), cyd = static_cast<double>(cy);
                    const num::Interval tx(std::max(x0 - cxd, 0.0), std::min(x1 - cxd, 1.0));
                    const num::Interval ty(std::max(y0 - cyd, 0.0), std::min(y1 - cyd, 1.0));
                    const num::Interval hc = cellRange(cx, cy, tx, ty);
                    h = first ? hc : num::hull(h, hc);
                    first = false;
                }
            return h;
        }
        // Every sample some covered cell reads: columns cx0 − 1 .. cx1 + 2.
        const auto [m, M] = sampleRange(cx0 == 0 ? 0 : cx0 - 1, std::min(cx1 + 2, columns_ - 1),
                                        cy0 == 0 ? 0 : cy0 - 1, std::min(cy1 + 2, rows_ - 1));
        const double overshoot = 9.0 / 32.0 * (M - m);
        const double slack = 0x1p-45 * std::max(std::abs(m), std::abs(M)) + 1e-300;
        return {m - overshoot - slack, M + overshoot + slack};
    }

    // h over the local rectangle tx × ty of cell (cx, cy): its bicubic in
    // Bézier form restricted to the rectangle.
    num::Interval cellRange(size_t cx, size_t cy, const num::Interval& tx,
                            const num::Interval& ty) const {
        std::array<std::array<double, 4>, 4> q;  // q[b][i]: row b converted along x
        double magnitude = 0.0;
        for (size_t b = 0; b < 4; ++b) {
            std::array<double, 4> p;
            for (size_t a = 0; a < 4; ++a) {
                p[a] = sample(cx + a, cy + b);
                magnitude = std::max(magnitude, std::abs(p[a]));
            }
            q[b] = catmullRomToBezier(p[0], p[1], p[2], p[3]);
        }
        std::array<double, 16> net;  // net[4i + j]: i along x, j along y
        for (size_t i = 0; i < 4; ++i) {
            const std::array<double, 4> c = catmullRomToBezier(q[0][i], q[1][i], q[2][i], q[3][i]);
            for (size_t j = 0; j < 4; ++j) net[4 * i + j] = c[j];
        }
        // The conversion's rounding is relative to the samples, which may be
        // larger than the net (differences of large neighbours): pass them.
        return bezier::bicubicRange(net, tx, ty, 2.0 * magnitude);
    }

    // Min and max of the samples in columns [x0, x1] × rows [y0, y1] (or of a
    // few more around them): at most 4 x 4 blocks of the coarsest pyramid level
    // whose blocks split the range into no more than 4 per axis.
    std::pair<double, double> sampleRange(size_t x0, size_t x1, size_t y0, size_t y1) const {
        size_t level = 0;
        while ((x1 >> level) - (x0 >> level) > 3 || (y1 >> level) - (y0 >> level) > 3) ++level;
        float lo = heights_[y0 * columns_ + x0], hi = lo;
        for (size_t by = y0 >> level; by <= y1 >> level; ++by)
            for (size_t bx = x0 >> level; bx <= x1 >> level; ++bx) {
                if (level == 0) {
                    const float h = heights_[by * columns_ + bx];
                    lo = std::min(lo, h);
                    hi = std::max(hi, h);
                } else {
                    const Level& l = levels_[level - 1];
                    lo = std::min(lo, l.lo[by * l.width + bx]);
                    hi = std::max(hi, l.hi[by * l.width + bx]);
                }
            }
        return {lo, hi};
    }

    // levels_[L − 1] holds the min/max of the 2^L x 2^L blocks, down to 1 x 1.
    void buildPyramid() {
        size_t width = columns_, height = rows_;
        while (width > 1 || height > 1) {
            Level next;
            next.width = (width + 1) / 2;
            next.height = (height + 1) / 2;
            next.lo.resize(next.width * next.height);
            next.hi.resize(next.width * next.height);
            const Level* prev = levels_.empty() ? nullptr : &levels_.back();
            auto lo = [&](size_t x, size_t y) {
                return prev ? prev->lo[y * width + x] : heights_[y * width + x];
            };
            auto hi = [&](size_t x, size_t y) {
                return prev ? prev->hi[y * width + x] : heights_[y * width + x];
            };
            for (size_t y = 0; y < next.height; ++y)
                for (size_t x = 0; x < next.width; ++x) {
                    const size_t xa = 2 * x, xb = std::min(2 * x + 1, width - 1);
                    const size_t ya = 2 * y, yb = std::min(2 * y + 1, height - 1);
                    next.lo[y * next.width + x] =
                        std::min({lo(xa, ya), lo(xb, ya), lo(xa, yb), lo(xb, yb)});
                    next.hi[y * next.width + x] =
                        std::max({hi(xa, ya), hi(xb, ya), hi(xa, yb), hi(xb, yb)});
                }
            width = next.width;
            height = next.height;
            levels_.push_back(std::move(next));
        }
    }

    std::vector<float> heights_;
    size_t columns_, rows_;
    double sizeX_, sizeY_, scale_;
    double scaleX_ = 0.0, scaleY_ = 0.0;  // grid units per unit of u, v
    ParamDomain domain_;
    std::vector<Level> levels_;
};

}  // namespace

ParametricSurfacePtr makeHeightField(std::vector<float> heights, int columns, int rows,
                                     double sizeX, double sizeY, double heightScale) {
    const char* what = "height field";
    if (columns < 2 || rows < 2)
        fail(what, ": needs at least 2 x 2 samples, got ", columns, " x ", rows);
    const size_t c = static_cast<size_t>(columns), r = static_cast<size_t>(rows);
    if (heights.size() != c * r)
        fail(what, ": ", heights.size(), " heights for ", columns, " x ", rows, " = ", c * r,
             " samples");
    if (!(std::isfinite(sizeX) && sizeX > 0.0 && std::isfinite(sizeY) && sizeY > 0.0))
        fail(what, ": the size must be positive and finite, got ", sizeX, " x ", sizeY);
    if (!std::isfinite(heightScale))
        fail(what, ": the height scale must be finite, got ", heightScale);
    for (size_t k = 0; k < heights.size(); ++k)
        if (!std::isfinite(heights[k]))
            fail(what, ": the height at column ", k % c, ", row ", k / c, " is not finite (",
                 heights[k], ")");
    return std::make_shared<HeightField>(std::move(heights), c, r, sizeX, sizeY, heightScale);
}

}  // namespace strahl
