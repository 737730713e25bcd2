#pragma once
// Pixel reconstruction filters, used by filter importance sampling (pbrt-v4's
// FilterSampler idea; derivation in docs/camera.md "Pixel filters"): each camera
// sample is offset from its pixel centre by sample(u), distributed in proportion
// to the filter, and then counts with weight 1 for its own pixel, so the film's
// plain per-pixel mean is the filtered value and stays deterministic.
//
// Every filter is separable, non-negative and symmetric, f(x, y) = f1(x) f1(y),
// with f1(0) = 1 and support [-radius, radius] per axis, in pixels:
//   box              f1 = 1
//   gaussian         f1 = (g(x) - g(radius)) / (1 - g(radius)), g(x) = exp(-x^2 / (2 sigma^2)),
//                    shifted so it reaches 0 at the support's edge (as pbrt-v4)
//   blackman-harris  f1 = a0 + a1 cos(pi x / r) + a2 cos(2 pi x / r) + a3 cos(3 pi x / r),
//                    the 4-term Blackman-Harris window over the width 2 r
//   tent             f1 = 1 - |x| / r, the triangle (Mitsuba's `tent`)

#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "strahl/core/math.h"

namespace strahl {

enum class FilterType { Box, Gaussian, BlackmanHarris, Tent };

class PixelFilter {
public:
    // Bins per axis of the tabulated CDF (docs/camera.md: the sampled density is
    // the filter averaged over bins of width 2 radius / 256).
    static constexpr int kTableBins = 256;

    // Throw strahl::Error unless radius (and sigma) are positive and finite.
    static PixelFilter box(float radius = 0.5f);
    static PixelFilter gaussian(float radius = 1.5f, float sigma = 0.5f);
    static PixelFilter blackmanHarris(float radius = 2.0f);  // width 4 pixels
    static PixelFilter tent(float radius = 1.0f);
    // By name ("box", "gaussian", "blackman-harris", "tent"), with that filter's default
    // radius unless one is given (a Gaussian keeps sigma 0.5). Throws
    // strahl::Error listing the valid names for any other name.
    static PixelFilter fromName(std::string_view name, std::optional<float> radius = std::nullopt);
    static std::span<const std::string_view> names();  // the names fromName accepts

    FilterType type() const { return type_; }
    const char* name() const;  // as fromName spells it
    float radius() const { return radius_; }
    float sigma() const { return sigma_; }  // the Gaussian's; 0 for the other filters

    // f(offset) for an offset from the pixel centre in pixels; 0 outside the support.
    float evaluate(Vec2 offset) const;
    // The integral of evaluate over the support.
    float integral() const;
    // u in [0, 1)^2 to an offset in [-radius, radius]^2 whose density is
    // evaluate / integral (exactly for the box; to the table's resolution
    // otherwise). A pure function of u; sample(0.5, 0.5) is the centre.
    Vec2 sample(Vec2 u) const;

private:
    PixelFilter(FilterType type, float radius, float sigma);
    float evaluate1D(float x) const;
    double antiderivative1D(double x) const;  // integral of f1 over [-radius, x]
    float sample1D(float u) const;

    FilterType type_;
    float radius_;
    float sigma_;
    double gaussianFloor_ = 0.0;  // g(radius), subtracted by the Gaussian
    std::vector<float> cdf_;      // kTableBins + 1 CDF values at the bin edges; empty for the box
};

}  // namespace strahl
