#include "strahl/core/distribution.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "strahl/core/error.h"

namespace strahl {

namespace {

// The bin of x in [0, 1) for n bins; out-of-range and NaN x go to the nearest end.
size_t binOf(float x, size_t n) {
    if (!(x > 0.0f)) return 0;
    const float scaled = x * static_cast<float>(n);
    if (!(scaled < static_cast<float>(n))) return n - 1;
    return std::min(static_cast<size_t>(scaled), n - 1);
}

// The largest float below 1: where samples are clamped so they stay in [0, 1).
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

}  // namespace

Distribution1D::Distribution1D(std::vector<float> weights) : func_(std::move(weights)) {
    const size_t n = func_.size();
    if (n == 0) fail("Distribution1D: no weights");
    // Sums in double: a float running sum over ~10^6 texels loses the small ones.
    double total = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const float w = func_[i];
        if (!std::isfinite(w) || w < 0.0f)
            fail("Distribution1D: weight ", i, " is ", w, " (must be finite and >= 0)");
        total += w;
    }
    integral_ = static_cast<float>(total / static_cast<double>(n));
    cdf_.resize(n + 1);
    cdf_[0] = 0.0f;
    double running = 0.0;
    for (size_t i = 0; i < n; ++i) {
        running += total > 0.0 ? func_[i] : 1.0;  // all zero: uniform
        // running / total is exactly 1 once the last non-zero weight is summed, so
        // trailing empty bins have cdf 1 and u < 1 never lands in them.
        cdf_[i + 1] = static_cast<float>(running / (total > 0.0 ? total : static_cast<double>(n)));
    }
    cdf_[n] = 1.0f;
    // A float total that underflowed to 0 (weights ~1e-45) would divide by 0 in
    // pdf(); such weights are as good as zero, so treat them as the uniform case.
    if (!(integral_ > 0.0f) && total > 0.0) {
        integral_ = 0.0f;
        for (size_t i = 0; i <= n; ++i)
            cdf_[i] = static_cast<float>(static_cast<double>(i) / static_cast<double>(n));
    }
}

size_t Distribution1D::binOfSample(float& u) const {
    u = std::isnan(u) ? 0.0f : std::clamp(u, 0.0f, kOneMinusEpsilon);
    // The last bin whose cdf start is <= u. A bin of weight 0 has the same start
    // as its successor, so it is never the last such bin (unless it is the last
    // bin, whose start is 1 > u once all later weights are 0).
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
    return std::clamp<size_t>(static_cast<size_t>(it - cdf_.begin()), 1, func_.size()) - 1;
}

float Distribution1D::sampleContinuous(float u, float& pdf, size_t& offset) const {
    const size_t n = func_.size();
    const size_t i = binOfSample(u);
    const float width = cdf_[i + 1] - cdf_[i];
    float du = u - cdf_[i];
    if (width > 0.0f) du /= width;
    du = std::clamp(du, 0.0f, kOneMinusEpsilon);
    float x = std::min((static_cast<float>(i) + du) / static_cast<float>(n), kOneMinusEpsilon);
    // (i + du) / n can round into a neighbouring bin; step back into bin i so
    // that pdf(x) is the density reported here.
    while (binOf(x, n) < i) x = std::nextafter(x, 1.0f);
    while (binOf(x, n) > i) x = std::nextafter(x, 0.0f);
    offset = i;
    pdf = integral_ > 0.0f ? func_[i] / integral_ : 1.0f;
    return x;
}

size_t Distribution1D::sampleDiscrete(float u, float& pmfOut) const {
    // sampleContinuous's bin, without the point inside it: the light choice
    // of every next-event estimate comes here (issue 20).
    const size_t offset = binOfSample(u);
    pmfOut = pmf(offset);
    return offset;
}

float Distribution1D::pdf(float x) const {
    if (func_.empty()) return 0.0f;
    if (!(integral_ > 0.0f)) return 1.0f;
    return func_[binOf(x, func_.size())] / integral_;
}

float Distribution1D::pmf(size_t i) const {
    const size_t n = func_.size();
    if (i >= n) return 0.0f;
    if (!(integral_ > 0.0f)) return 1.0f / static_cast<float>(n);
    return func_[i] / (integral_ * static_cast<float>(n));
}

Distribution2D::Distribution2D(const std::vector<float>& weights, int nu, int nv) {
    if (nu <= 0 || nv <= 0) fail("Distribution2D: size ", nu, " x ", nv, " is empty");
    const auto cols = static_cast<size_t>(nu), rows = static_cast<size_t>(nv);
    if (weights.size() != cols * rows)
        fail("Distribution2D: ", weights.size(), " weights for ", nu, " x ", nv);
    conditional_.reserve(rows);
    std::vector<float> rowIntegrals(rows);
    for (size_t v = 0; v < rows; ++v) {
        const auto first = weights.begin() + static_cast<std::ptrdiff_t>(v * cols);
        conditional_.emplace_back(
            std::vector<float>(first, first + static_cast<std::ptrdiff_t>(cols)));
        rowIntegrals[v] = conditional_.back().integral();
    }
    marginal_ = Distribution1D(std::move(rowIntegrals));
}

Vec2 Distribution2D::sample(const Vec2& u, float& pdf) const {
    float pdfRow, pdfColumn;
    size_t row, column;
    const float v = marginal_.sampleContinuous(u.y, pdfRow, row);
    const float x = conditional_[row].sampleContinuous(u.x, pdfColumn, column);
    pdf = pdfRow * pdfColumn;
    return Vec2(x, v);
}

float Distribution2D::pdf(const Vec2& uv) const {
    if (conditional_.empty()) return 0.0f;
    const size_t row = binOf(uv.y, conditional_.size());
    return marginal_.pdf(uv.y) * conditional_[row].pdf(uv.x);
}

}  // namespace strahl
