#pragma once
// Shared machinery of the BSDF tests: directions from angles, Monte Carlo
// albedo estimation over sample(), quadrature of pdf() over the sphere and a
// pbrt-style chi-square goodness-of-fit test of sample() against pdf().
// Every estimator draws from a fixed-seed Pcg32, so every test is deterministic.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "strahl/bsdf/bsdf.h"
#include "strahl/core/rng.h"
#include "strahl/core/sampling.h"
#include "test_random.h"

namespace strahl::test {

constexpr double kPiD = 3.14159265358979323846;

// The unit vector at polar angle theta from +z and azimuth phi (degrees).
inline Vec3 direction(float thetaDeg, float phiDeg = 0.0f) {
    const float t = thetaDeg * kPi / 180.0f, p = phiDeg * kPi / 180.0f;
    return Vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
}

// One named BSDF of a table of cases that a test runs over.
struct Case {
    std::string name;
    Bsdf bsdf;
};

// A coated conductor (Bsdf::coatedConductor) whose per-material layers live
// to the end of the test program, as a material's would: eta and k of the
// metal in vacuum, the coat's index, alphas of metal and coat, the layer's
// thickness.
inline Bsdf coatedConductor(const Color& eta, const Color& k, float metalAlpha, float coatEta, float coatAlpha,
                            float thickness = 0.0f) {
    static std::mutex mutex;
    static std::deque<CoatedBase> kept;
    const std::lock_guard lock(mutex);
    kept.emplace_back(CoatedLayers{eta, k, coatEta, thickness, {}});
    return Bsdf::coatedConductor(kept.back(), metalAlpha, coatAlpha);
}

// A uniformly distributed direction of the upper hemisphere.
inline Vec3 sampleHemisphere(Pcg32& rng) {
    const Vec3 w = sampleUniformSphere(next2D(rng));
    return Vec3(w.x, w.y, std::abs(w.z));
}

// ---- White furnace ------------------------------------------------------------

struct AlbedoEstimate {
    Color mean{0.0f};
    Color stdError{0.0f};
    float maxMean() const { return maxComponent(mean); }
    float maxError() const { return maxComponent(stdError); }
};

// Mean of the throughput weight f |cos wi| / pdf over n sample() calls (0 for
// nullopt) = the directional albedo of wo. With undoRadianceScaling, a
// transmitted sample's weight is multiplied by eta^2: radiance transport scales
// transmission by 1 / eta^2 (radiance is compressed into the denser medium's
// smaller solid angle), which conserves radiance / n^2, not energy; undoing it
// gives the energy (importance) throughput, which a lossless interface keeps at 1.
inline AlbedoEstimate estimateAlbedo(const Bsdf& bsdf, const Vec3& wo, int n, uint64_t seed,
                                     bool undoRadianceScaling = true) {
    Pcg32 rng(seed, 7);
    // Double accumulators: a float sum of 10^5..10^6 weights near 1 drifts by
    // tenths of a percent.
    glm::dvec3 sum(0.0), sumSq(0.0);
    for (int i = 0; i < n; ++i) {
        const float uLobe = rng.nextFloat();
        const auto s = bsdf.sample(wo, uLobe, next2D(rng));
        if (!s) continue;
        glm::dvec3 w = glm::dvec3(s->f) * (std::abs(static_cast<double>(s->wi.z)) / s->pdf);
        if (s->transmission && undoRadianceScaling) w *= static_cast<double>(s->eta * s->eta);
        sum += w;
        sumSq += w * w;
    }
    const double nd = n;
    const glm::dvec3 mean = sum / nd;
    const glm::dvec3 variance = glm::max(sumSq / nd - mean * mean, glm::dvec3(0.0));
    AlbedoEstimate e;
    e.mean = Color(mean);
    e.stdError = Color(glm::sqrt(variance / nd));
    return e;
}

// ---- Quadrature of pdf() over the sphere ---------------------------------------

// A (theta, phi) grid over the whole sphere, theta in [0, pi] from +z.
struct SphereGrid {
    int thetaRes = 16, phiRes = 32;
    int cells() const { return thetaRes * phiRes; }
    int cellOf(const Vec3& w) const {
        const double theta = std::acos(std::clamp(static_cast<double>(w.z), -1.0, 1.0));
        double phi = std::atan2(static_cast<double>(w.y), static_cast<double>(w.x));
        if (phi < 0.0) phi += 2.0 * kPiD;
        const int t = std::min(static_cast<int>(theta / kPiD * thetaRes), thetaRes - 1);
        const int p = std::min(static_cast<int>(phi / (2.0 * kPiD) * phiRes), phiRes - 1);
        return t * phiRes + p;
    }
};

// Integral of pdf(wo, .) over every cell: composite two-point Gauss-Legendre
// with sub x sub intervals per cell in (theta, phi) and the sin(theta)
// Jacobian. Its nodes are interior, so the horizon, where opaque pdfs jump to
// 0, is never evaluated (a closed rule such as Simpson's would count the
// limit value there into the cell below the horizon).
inline std::vector<double> integratePdfCells(const Bsdf& bsdf, const Vec3& wo,
                                             const SphereGrid& grid, int sub = 8) {
    std::vector<double> cells(static_cast<size_t>(grid.cells()), 0.0);
    const double dTheta = kPiD / grid.thetaRes, dPhi = 2.0 * kPiD / grid.phiRes;
    const double hT = dTheta / sub, hP = dPhi / sub;
    const double offset = 0.5 / std::sqrt(3.0);  // nodes at centre -+ h / (2 sqrt 3)
    for (int t = 0; t < grid.thetaRes; ++t) {
        for (int p = 0; p < grid.phiRes; ++p) {
            double sum = 0.0;
            for (int i = 0; i < 2 * sub; ++i) {
                const double theta = t * dTheta + (i / 2 + 0.5 + (i % 2 ? offset : -offset)) * hT;
                const double sinT = std::sin(theta), cosT = std::cos(theta);
                for (int j = 0; j < 2 * sub; ++j) {
                    const double phi = p * dPhi + (j / 2 + 0.5 + (j % 2 ? offset : -offset)) * hP;
                    const Vec3 wi(static_cast<float>(sinT * std::cos(phi)),
                                  static_cast<float>(sinT * std::sin(phi)),
                                  static_cast<float>(cosT));
                    sum += bsdf.pdf(wo, wi) * sinT;
                }
            }
            cells[static_cast<size_t>(t * grid.phiRes + p)] = sum * hT * hP / 4.0;
        }
    }
    return cells;
}

// ---- Chi-square goodness of fit -------------------------------------------------

// Regularised upper incomplete gamma Q(a, x) (series below a + 1, Lentz's
// continued fraction above).
inline double gammaQ(double a, double x) {
    if (x <= 0.0) return 1.0;
    const double logPrefix = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1.0) {
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 1000 && term > sum * 1e-15; ++n) {
            term *= x / (a + n);
            sum += term;
        }
        return 1.0 - sum * std::exp(logPrefix);
    }
    constexpr double kTiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 1000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::abs(d) < kTiny) d = kTiny;
        c = b + an / c;
        if (std::abs(c) < kTiny) c = kTiny;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1.0) < 1e-15) break;
    }
    return std::exp(logPrefix) * h;
}

struct Chi2Result {
    bool ok = false;
    double pValue = 0.0;
    std::string message;
};

// pbrt-v3's test (Jakob): histogram n samples of sample() over the grid, compare
// with the expected counts n * integral of pdf per cell, pool cells expecting
// fewer than 5, and reject at `significance`. Delta samples are left out (pdf()
// does not describe them); a sample in a cell of zero expectation fails at once.
inline Chi2Result chi2Test(const Bsdf& bsdf, const Vec3& wo, int n, uint64_t seed,
                           double significance, const SphereGrid& grid = {}) {
    std::vector<double> observed(static_cast<size_t>(grid.cells()), 0.0);
    Pcg32 rng(seed, 11);
    for (int i = 0; i < n; ++i) {
        const float uLobe = rng.nextFloat();
        const auto s = bsdf.sample(wo, uLobe, next2D(rng));
        if (s && !s->specular) observed[static_cast<size_t>(grid.cellOf(s->wi))] += 1.0;
    }
    std::vector<double> expected = integratePdfCells(bsdf, wo, grid);
    for (double& e : expected) e *= n;

    Chi2Result r;
    double chi2 = 0.0, pooledObs = 0.0, pooledExp = 0.0;
    int dof = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] <= 0.0 && observed[i] > 0.0) {
            r.message = "sample in cell " + std::to_string(i) + " of zero expected frequency";
            return r;
        }
        if (expected[i] < 5.0) {
            pooledObs += observed[i];
            pooledExp += expected[i];
        } else {
            chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
            ++dof;
        }
    }
    if (pooledExp > 0.0) {
        chi2 += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
        ++dof;
    } else if (pooledObs > 0.0) {
        r.message = "samples in cells of zero expected frequency";
        return r;
    }
    dof -= 1;  // the counts are constrained by their total
    if (dof < 1) {
        r.message = "too few cells with enough expected samples";
        return r;
    }
    r.pValue = gammaQ(0.5 * dof, 0.5 * chi2);
    r.ok = r.pValue >= significance;
    r.message = "chi2 = " + std::to_string(chi2) + ", dof = " + std::to_string(dof) +
                ", p = " + std::to_string(r.pValue);
    return r;
}

}  // namespace strahl::test
