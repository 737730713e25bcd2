#pragma once
// Piecewise-constant distributions for importance sampling (pbrt-v3 13.3.1,
// 13.6.7): 1D over [0, 1) from non-negative weights, and 2D as a marginal over
// rows times a conditional per row. Sampling inverts the CDF exactly, so pdf()
// of a sample equals the density sample() reports, bit for bit: a sample always
// lies in the bin pdf() looks up for it, and bins of weight 0 are never sampled.

#include <cstddef>
#include <vector>

#include "strahl/core/math.h"

namespace strahl {

class Distribution1D {
public:
    Distribution1D() = default;
    // All-zero weights give a uniform distribution (so sampling never fails).
    // Throws strahl::Error on no weights or a negative or non-finite weight.
    explicit Distribution1D(std::vector<float> weights);
    size_t size() const { return func_.size(); }
    // x in [0, 1) with density pdf; offset = the bin of x. u in [0, 1).
    float sampleContinuous(float u, float& pdf, size_t& offset) const;
    size_t sampleDiscrete(float u, float& pmf) const;
    float pdf(float x) const;                     // density at x in [0, 1)
    float pmf(size_t i) const;                    // probability of bin i
    float integral() const { return integral_; }  // mean of the weights

private:
    // Clamps u into [0, 1) in place (NaN to 0) and returns the bin it falls in.
    size_t binOfSample(float& u) const;

    std::vector<float> func_;
    std::vector<float> cdf_;  // size() + 1 entries, cdf_[0] = 0, cdf_[size()] = 1
    float integral_ = 0.0f;
};

class Distribution2D {
public:
    Distribution2D() = default;
    // weights: nu x nv, row-major (v rows of u columns). Rows of weight 0 are
    // never sampled; all-zero weights give the uniform distribution.
    Distribution2D(const std::vector<float>& weights, int nu, int nv);
    Vec2 sample(const Vec2& u, float& pdf) const;  // (u, v) in [0, 1)^2
    float pdf(const Vec2& uv) const;

private:
    std::vector<Distribution1D> conditional_;
    Distribution1D marginal_;
};

}  // namespace strahl
