#pragma once
// Shared by the core sampling tests: the chi-square critical value they test against.

#include <cmath>

namespace strahl::test {

// Upper 0.1% point of the chi-square distribution with k degrees of freedom
// (Wilson-Hilferty approximation, accurate to ~1% for k >= 3; z is the standard
// normal quantile of 1 - 1e-3): a correct sampler fails a fixed-seed test at
// this level with probability 1/1000.
inline double chiSquareCritical(int k, double z = 3.0902) {
    const double a = 2.0 / (9.0 * k);
    return k * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

}  // namespace strahl::test
