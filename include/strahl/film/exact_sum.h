#pragma once
// ExactSum: a sum of float samples in fixed point, so that sums can be split
// and added up again without a single bit of difference.
//
// Float addition is not associative: the sum of samples [0, K) plus the sum of
// [K, N) is in general not the sequential sum of [0, N). Integer addition is,
// so the film accumulates radiance and the mean AOVs as integers: a signed
// 128-bit integer holding value * 2^64 (Q63.64), each sample truncated toward
// zero to a multiple of 2^-64. Then a render split by sample ranges on several
// machines (`--sample-offset`, `strahl merge`, docs/farm.md) adds up to
// exactly the single-machine image, whatever the order of the parts.
//
// Range: every sample is clamped to [-2^32, 2^32] (kBound), so one sample adds
// at most 2^96 to the integer and 2^31 - 1 samples (kMaxSamples, more than any
// pixel can get: the CLI allows 65536 spp per render, and strahl merge checks
// the total) stay below 2^127, the largest 128-bit magnitude. Nothing a camera
// sample produces comes near 2^32 (radiance, normals, albedo, depths and
// positions of real scenes are many orders smaller).
//
// Precision: a float's last bit is 2^-23 of its leading one, so every float of
// magnitude at least 2^-41 is held exactly (its last bit is >= 2^-64); smaller
// ones lose their lowest bits, which is far below what a float sum keeps.
//
// Non-finite samples: the integrators drop a non-finite radiance to black
// before it reaches the film (integrator/camera_sample.h) and the AOVs are
// finite by construction; should one arrive anyway, NaN adds 0 and +-inf adds
// the bound, so one bad sample cannot poison a pixel.
//
// Resolving: double(sum) * 2^-64 / n, rounded to float. The integer to double
// conversion rounds to nearest; every step is a fixed function of the integer,
// so equal sums give equal pixels.

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace strahl {

// GCC and Clang's 128-bit integer; __extension__ keeps -Wpedantic quiet.
__extension__ typedef __int128 Int128;
__extension__ typedef unsigned __int128 UInt128;

class ExactSum {
public:
    static constexpr int kFractionBits = 64;
    static constexpr double kBound = 0x1p32;  // samples are clamped to [-kBound, kBound]
    static constexpr uint32_t kMaxSamples = 0x7fffffffu;  // 2^31 - 1: 2^31 * 2^96 would overflow

    ExactSum() = default;

    void add(float sample) { bits_ += toFixed(sample); }
    ExactSum& operator+=(const ExactSum& other) {
        bits_ += other.bits_;
        return *this;
    }

    double value() const { return static_cast<double>(bits_) * 0x1p-64; }
    // The mean of n samples as a float; 0 for n = 0 (a pixel without samples is black).
    float mean(uint32_t n) const {
        return n == 0 ? 0.0f : static_cast<float>(value() / static_cast<double>(n));
    }

    // The raw integer: for files and tests. fromValue approximates a double by
    // the nearest fixed-point number below it in magnitude (for images that
    // carry only means, not exact sums).
    Int128 raw() const { return bits_; }
    static ExactSum fromRaw(Int128 bits) {
        ExactSum s;
        s.bits_ = bits;
        return s;
    }
    static ExactSum fromValue(double value) {
        ExactSum s;
        // The bound for a sum of kMaxSamples samples; NaN reads as 0.
        const double limit = kBound * static_cast<double>(kMaxSamples);
        if (std::isnan(value)) return s;
        s.bits_ = static_cast<Int128>(std::fmax(-limit, std::fmin(limit, value)) * 0x1p64);
        return s;
    }

    friend bool operator==(const ExactSum& a, const ExactSum& b) { return a.bits_ == b.bits_; }

    // A sample as fixed point: sign(x) * floor(min(|x|, kBound) * 2^64), 0 for
    // NaN. The definition, through a double and the compiler's double to
    // 128-bit conversion (a library call, __fixunsdfti, that was 4 % of a
    // path-traced frame, issue 20): the reference toFixed is tested against.
    static Int128 toFixedByDouble(float sample) {
        if (std::isnan(sample)) return 0;
        // The float is exact in double, and scaling by 2^64 is exact; the cast
        // truncates toward zero.
        const double clamped = std::fmax(-kBound, std::fmin(kBound, static_cast<double>(sample)));
        return static_cast<Int128>(clamped * 0x1p64);
    }

    // The same integer from the float's bits: a finite float is m * 2^(E - 150)
    // with the 24-bit integer m (implicit leading one for normal numbers) and
    // the biased exponent E, so x * 2^64 = m * 2^(E - 86): a shift of m, left
    // (exact) or right (floor of the magnitude, i.e. truncation toward zero).
    static Int128 toFixed(float sample) {
        const uint32_t bits = std::bit_cast<uint32_t>(sample);
        const bool negative = (bits >> 31) != 0;
        const uint32_t biased = (bits >> 23) & 0xFFu;
        const uint32_t fraction = bits & 0x7FFFFFu;
        // |x| >= 2^32 = kBound (biased exponent 127 + 32), infinities included.
        constexpr uint32_t kBoundBiased = 127 + 32;
        UInt128 magnitude;
        if (biased == 0xFFu && fraction != 0) return 0;  // NaN
        if (biased >= kBoundBiased) {
            magnitude = UInt128(1) << 96;  // kBound * 2^64
        } else {
            // Subnormals (E = 0) have no implicit one and the exponent of E = 1;
            // at most 2^-126 * 2^64, they shift out to 0 either way.
            const uint64_t m = biased == 0 ? fraction : (fraction | 0x800000u);
            const int shift = int(biased == 0 ? 1 : biased) - 86;  // <= 158 - 86 = 72
            magnitude = shift >= 0 ? UInt128(m) << shift : (shift > -24 ? m >> -shift : 0);
        }
        return negative ? -Int128(magnitude) : Int128(magnitude);
    }

private:
    Int128 bits_ = 0;
};

// One sum per colour channel or vector component.
using ExactSum3 = std::array<ExactSum, 3>;

}  // namespace strahl
