#pragma once
// Deterministic random numbers. Every camera sample draws from a generator
// seeded by (seed, pixel, sample index) alone, never by thread or tile order, so
// an image is identical for any thread count (pbrt-v4 StartPixelSample idea).

#include <cstdint>

namespace strahl {

// 64-bit finaliser of MurmurHash3: a bijective mix with full avalanche.
constexpr uint64_t mixBits(uint64_t v) {
    v ^= v >> 33;
    v *= 0xff51afd7ed558ccdULL;
    v ^= v >> 33;
    v *= 0xc4ceb9fe1a85ec53ULL;
    v ^= v >> 33;
    return v;
}

// PCG32 (O'Neill 2014, pcg32_random_r): small state, good statistics, streams.
class Pcg32 {
public:
    Pcg32() = default;  // an unseeded placeholder; reseed() before use
    Pcg32(uint64_t seed, uint64_t stream) { reseed(seed, stream); }

    void reseed(uint64_t seed, uint64_t stream) {
        state_ = 0;
        inc_ = (stream << 1u) | 1u;
        nextUint();
        state_ += seed;
        nextUint();
    }
    uint32_t nextUint() {
        const uint64_t old = state_;
        state_ = old * 6364136223846793005ULL + inc_;
        const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
    }
    // Uniform in [0, 1): 24 random bits scaled by 2^-24, so 1.0 is never returned.
    float nextFloat() { return static_cast<float>(nextUint() >> 8) * 0x1p-24f; }

private:
    uint64_t state_ = 0;
    uint64_t inc_ = 1;
};

// The generator for one camera sample.
inline Pcg32 pixelSampleRng(uint64_t seed, uint32_t px, uint32_t py, uint32_t sample) {
    const uint64_t pixel = (static_cast<uint64_t>(py) << 32) | px;
    return Pcg32(mixBits(seed ^ mixBits(pixel)), mixBits(sample + 0x9E3779B97F4A7C15ULL * seed));
}

}  // namespace strahl
