#include "strahl/core/filter.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <string>

#include "strahl/core/error.h"

namespace strahl {
namespace {

constexpr std::string_view kFilterNames[] = {"box", "gaussian", "blackman-harris",
                                             "tent"};  // enum order

// The 4-term Blackman-Harris window (Harris 1978, -92 dB side lobes); they sum
// to 1, so f1(0) = 1, and f1(+-radius) = a0 - a1 + a2 - a3 = 6e-5 > 0.
constexpr double kA0 = 0.35875, kA1 = 0.48829, kA2 = 0.14128, kA3 = 0.01168;

void checkPositive(const char* what, float value) {
    if (!(value > 0.0f) || !std::isfinite(value))
        fail("filter: the ", what, " must be positive and finite, got ", value);
}

}  // namespace

PixelFilter::PixelFilter(FilterType type, float radius, float sigma)
    : type_(type), radius_(radius), sigma_(sigma) {
    checkPositive("radius", radius);
    if (type_ == FilterType::Gaussian) {
        checkPositive("Gaussian sigma", sigma);
        const double r = radius, s = sigma;
        gaussianFloor_ = std::exp(-r * r / (2.0 * s * s));
    }
    if (type_ == FilterType::Box) return;  // sampled in closed form, no table

    // CDF at the bin edges from the exact antiderivative, so every bin holds
    // exactly the filter's mass over it (docs/camera.md, "Pixel filters").
    const double total = antiderivative1D(radius_);
    cdf_.resize(kTableBins + 1);
    for (int i = 0; i <= kTableBins; ++i) {
        const double x = -static_cast<double>(radius_) +
                         2.0 * static_cast<double>(radius_) * i / kTableBins;
        cdf_[static_cast<size_t>(i)] = static_cast<float>(antiderivative1D(x) / total);
    }
    cdf_.front() = 0.0f;
    cdf_.back() = 1.0f;
    // Rounding must not make the CDF decrease anywhere.
    for (size_t i = 1; i < cdf_.size(); ++i) cdf_[i] = std::max(cdf_[i], cdf_[i - 1]);
}

PixelFilter PixelFilter::box(float radius) { return {FilterType::Box, radius, 0.0f}; }

PixelFilter PixelFilter::gaussian(float radius, float sigma) {
    return {FilterType::Gaussian, radius, sigma};
}

PixelFilter PixelFilter::blackmanHarris(float radius) {
    return {FilterType::BlackmanHarris, radius, 0.0f};
}

PixelFilter PixelFilter::tent(float radius) { return {FilterType::Tent, radius, 0.0f}; }

std::span<const std::string_view> PixelFilter::names() { return kFilterNames; }

PixelFilter PixelFilter::fromName(std::string_view name, std::optional<float> radius) {
    if (name == "box") return radius ? box(*radius) : box();
    if (name == "gaussian") return radius ? gaussian(*radius) : gaussian();
    if (name == "blackman-harris") return radius ? blackmanHarris(*radius) : blackmanHarris();
    if (name == "tent") return radius ? tent(*radius) : tent();
    std::string valid;
    for (std::string_view n : kFilterNames) valid += concat(valid.empty() ? "" : ", ", n);
    fail("filter: unknown filter '", name, "' (valid: ", valid, ")");
}

const char* PixelFilter::name() const {
    return kFilterNames[static_cast<size_t>(type_)].data();  // literals: NUL-terminated
}

float PixelFilter::evaluate1D(float x) const {
    if (!(std::abs(x) <= radius_)) return 0.0f;  // outside the support (or NaN)
    const double xd = x, r = radius_;
    switch (type_) {
        case FilterType::Box:
            return 1.0f;
        case FilterType::Gaussian: {
            const double twoSigma2 = 2.0 * static_cast<double>(sigma_) * sigma_;
            // For sigma small against the radius g(radius) is tiny (it may
            // underflow to 0, then expm1 below would overflow); otherwise the two
            // exponentials are close and expm1 keeps the digits their difference
            // loses: g(x) - g(r) = g(r) expm1((r^2 - x^2) / 2 sigma^2) and
            // 1 - g(r) = -expm1(-r^2 / 2 sigma^2).
            if (gaussianFloor_ < 0.5)
                return static_cast<float>((std::exp(-xd * xd / twoSigma2) - gaussianFloor_) /
                                          (1.0 - gaussianFloor_));
            return static_cast<float>(gaussianFloor_ * std::expm1((r * r - xd * xd) / twoSigma2) /
                                      -std::expm1(-r * r / twoSigma2));
        }
        case FilterType::BlackmanHarris: {
            const double phi = std::numbers::pi * xd / r;
            const double f = kA0 + kA1 * std::cos(phi) + kA2 * std::cos(2.0 * phi) +
                             kA3 * std::cos(3.0 * phi);
            return static_cast<float>(std::max(f, 0.0));
        }
        case FilterType::Tent:
            return static_cast<float>(1.0 - std::abs(xd) / r);
    }
    fail("invalid FilterType value ", static_cast<int>(type_));
}

double PixelFilter::antiderivative1D(double x) const {
    const double r = radius_;
    x = std::clamp(x, -r, r);
    switch (type_) {
        case FilterType::Box:
            return x + r;
        case FilterType::Gaussian: {
            // integral of exp(-t^2 / 2 sigma^2) = sigma sqrt(pi/2) erf(t / (sigma sqrt 2)).
            const double s = sigma_;
            const double scale = 1.0 / (s * std::numbers::sqrt2);
            const double gauss = s * std::sqrt(0.5 * std::numbers::pi) *
                                 (std::erf(x * scale) + std::erf(r * scale));
            return (gauss - gaussianFloor_ * (x + r)) / (1.0 - gaussianFloor_);
        }
        case FilterType::BlackmanHarris: {
            // The sines vanish at x = -r (phi = -pi), so this is 0 there.
            const double phi = std::numbers::pi * x / r;
            return kA0 * (x + r) + r / std::numbers::pi *
                                       (kA1 * std::sin(phi) + kA2 / 2.0 * std::sin(2.0 * phi) +
                                        kA3 / 3.0 * std::sin(3.0 * phi));
        }
        case FilterType::Tent:
            // (x + r)^2 / 2r on the rising half, r - (r - x)^2 / 2r on the falling one.
            return x <= 0.0 ? (x + r) * (x + r) / (2.0 * r) : r - (r - x) * (r - x) / (2.0 * r);
    }
    fail("invalid FilterType value ", static_cast<int>(type_));
}

float PixelFilter::evaluate(Vec2 offset) const {
    return evaluate1D(offset.x) * evaluate1D(offset.y);
}

float PixelFilter::integral() const {
    const double a = antiderivative1D(radius_);
    return static_cast<float>(a * a);
}

float PixelFilter::sample1D(float u) const {
    // The bin i with cdf[i] <= u < cdf[i + 1]; the last such edge, so empty bins
    // (equal neighbours) are never chosen.
    const auto above = std::upper_bound(cdf_.begin(), cdf_.end(), u);
    const auto i = std::clamp<std::ptrdiff_t>(std::distance(cdf_.begin(), above) - 1, 0,
                                              kTableBins - 1);
    const float lo = cdf_[static_cast<size_t>(i)], hi = cdf_[static_cast<size_t>(i) + 1];
    // Linear inside the bin: the density there is flat (the bin's mean of f1).
    const float t = hi > lo ? (u - lo) / (hi - lo) : 0.5f;
    const float binWidth = 2.0f * radius_ / static_cast<float>(kTableBins);
    const float x = -radius_ + (static_cast<float>(i) + t) * binWidth;
    return std::clamp(x, -radius_, radius_);
}

Vec2 PixelFilter::sample(Vec2 u) const {
    if (type_ == FilterType::Box)  // the inverse CDF of a uniform density is linear
        return radius_ * (2.0f * u - Vec2(1.0f));
    return Vec2(sample1D(u.x), sample1D(u.y));
}

}  // namespace strahl
