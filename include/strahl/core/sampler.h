#pragma once
// The low-discrepancy sampler: Owen-scrambled Sobol points, padded in pairs of
// dimensions, as Burley 2020 ("Practical Hash-based Owen Scrambling", JCGT
// 9(4)) describes and pbrt-v4's PaddedSobolSampler uses.
//
// Every value is a pure function of (seed, pixel, sample index, dimension):
//  - dimension pair k of a pixel gets its own hash h = H(seed, pixel, k);
//  - the sample index is shuffled by a nested uniform scramble seeded by h,
//    which decorrelates the pairs from each other;
//  - the shuffled index picks a point of the first two Sobol dimensions (a
//    (0,2)-sequence in base 2), each Owen-scrambled with a seed derived from h.
// Hence any 2^m consecutive samples of one pair are stratified in every
// elementary interval of area 2^-m, and the image depends neither on threads
// nor on tile order. Consumers draw dimensions in a fixed order per sample.

#include <cstdint>

#include "strahl/core/math.h"
#include "strahl/core/rng.h"

namespace strahl {

namespace sobol {

// The bits within each byte reversed, then the bytes by one byte swap (an
// instruction), instead of two more swap steps.
constexpr uint32_t reverseBits(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    return __builtin_bswap32(x);
}

// Burley's improved Laine-Karras hash: a random permutation of the integers
// that only lets higher bits depend on lower ones, i.e. an Owen scramble of
// the bit-reversed value. The constants are Burley's (listing 3).
constexpr uint32_t laineKarrasPermutation(uint32_t x, uint32_t seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

// Owen scramble of a 32-bit binary fraction (most significant bit = 1/2).
constexpr uint32_t nestedUniformScramble(uint32_t x, uint32_t seed) {
    return reverseBits(laineKarrasPermutation(reverseBits(x), seed));
}

// The first Sobol dimension: the van der Corput sequence (bit reversal).
constexpr uint32_t dimension0(uint32_t index) { return reverseBits(index); }

// nestedUniformScramble(dimension0(index), seed), with the two bit reversals
// that cancel (reverseBits(reverseBits(i)) = i) left out.
constexpr uint32_t scrambledDimension0(uint32_t index, uint32_t seed) {
    return reverseBits(laineKarrasPermutation(index, seed));
}

// The second Sobol dimension: generator matrix = Pascal's triangle mod 2, whose
// columns follow v_{k+1} = v_k ^ (v_k >> 1) from v_0 = 2^31. This is the
// definition, one column per set bit: the reference the table below is built
// from and tested against.
constexpr uint32_t dimension1BitByBit(uint32_t index) {
    uint32_t result = 0;
    for (uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1)
        if (index & 1u) result ^= v;
    return result;
}

// The matrix-vector product over GF(2) is linear in the index, so it splits
// into the four bytes of the index: dimension1(i) = T[0][byte 0] ^ ... ^
// T[3][byte 3], with T[k][b] = dimension1BitByBit(b << 8k). Four loads and
// three XORs instead of a loop of up to 32 iterations with an unpredictable
// branch each (the index is scrambled, so its bits are random): the loop was
// the largest cost of eyelight rendering (issue 20). 4 KiB (8 with the
// reversed copy below), built at compile time; the values are identical bit
// for bit.
struct Dimension1Table {
    uint32_t byByte[4][256];
};
// reversed: the same table with every entry bit-reversed. Bit reversal is
// linear over XOR, so it gives reverseBits(dimension1(i)), the form the Owen
// scramble starts from, without reversing at run time.
constexpr Dimension1Table makeDimension1Table(bool reversed) {
    Dimension1Table t{};
    for (uint32_t k = 0; k < 4; ++k)
        for (uint32_t b = 0; b < 256; ++b) {
            const uint32_t column = dimension1BitByBit(b << (8 * k));
            t.byByte[k][b] = reversed ? reverseBits(column) : column;
        }
    return t;
}
inline constexpr Dimension1Table kDimension1Table = makeDimension1Table(false);
inline constexpr Dimension1Table kReversedDimension1Table = makeDimension1Table(true);

constexpr uint32_t byTable(const Dimension1Table& table, uint32_t index) {
    const auto& t = table.byByte;
    return t[0][index & 0xFFu] ^ t[1][(index >> 8) & 0xFFu] ^ t[2][(index >> 16) & 0xFFu] ^
           t[3][index >> 24];
}
constexpr uint32_t dimension1(uint32_t index) { return byTable(kDimension1Table, index); }

// nestedUniformScramble(dimension1(index), seed), its first bit reversal
// taken from the reversed table.
constexpr uint32_t scrambledDimension1(uint32_t index, uint32_t seed) {
    return reverseBits(laineKarrasPermutation(byTable(kReversedDimension1Table, index), seed));
}

// A 32-bit fraction to a float in [0, 1): the top 24 bits, so 1 is never returned.
constexpr float toUnitFloat(uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

}  // namespace sobol

class Sampler {
public:
    Sampler() = default;
    Sampler(uint64_t seed, int px, int py, uint32_t sampleIndex)
        : pixelHash_(mixBits(seed ^ mixBits((static_cast<uint64_t>(static_cast<uint32_t>(py)) << 32) |
                                            static_cast<uint32_t>(px)))),
          index_(sampleIndex),
          reversedIndex_(sobol::reverseBits(sampleIndex)) {}

    // The next dimension (a pair is used for it; the second half is dropped so
    // that 1D and 2D requests stay aligned to pairs).
    float get1D() {
        const uint64_t h = pairHash();
        const uint32_t i = shuffledIndex(h);
        return sobol::toUnitFloat(sobol::scrambledDimension0(i, static_cast<uint32_t>(h >> 32)));
    }
    // The next pair of dimensions.
    Vec2 get2D() {
        const uint64_t h = pairHash();
        const uint32_t i = shuffledIndex(h);
        const uint64_t h2 = mixBits(h ^ 0x5851F42D4C957F2DULL);
        return Vec2(sobol::toUnitFloat(
                        sobol::scrambledDimension0(i, static_cast<uint32_t>(h >> 32))),
                    sobol::toUnitFloat(sobol::scrambledDimension1(i, static_cast<uint32_t>(h2))));
    }

    // Skips the next pair of dimensions without drawing it, for a consumer
    // that would not use its values (a pinhole camera's lens sample). Each
    // pair's values depend only on its position, so the pairs after it are
    // those that drawing it would have given.
    void skip2D() { ++pair_; }

    uint32_t sampleIndex() const { return index_; }
    uint32_t dimension() const { return pair_; }  // pairs drawn so far

private:
    uint64_t pairHash() { return mixBits(pixelHash_ + 0x9E3779B97F4A7C15ULL * ++pair_); }
    // nestedUniformScramble(index_, h), with the index's bit reversal done once
    // per sample instead of once per pair.
    uint32_t shuffledIndex(uint64_t h) const {
        return sobol::reverseBits(sobol::laineKarrasPermutation(reversedIndex_, static_cast<uint32_t>(h)));
    }

    uint64_t pixelHash_ = 0;
    uint32_t index_ = 0;
    uint32_t reversedIndex_ = 0;  // sobol::reverseBits(index_)
    uint32_t pair_ = 0;
};

}  // namespace strahl
