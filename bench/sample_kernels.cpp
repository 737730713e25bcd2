// bench_sample_kernels: the per-sample kernels of issue 20, part 1, each
// against the definition it replaced, in one run (so machine load hits both):
//   - the second Sobol dimension: four byte tables vs the loop over the
//     index's bits (sobol::dimension1 vs sobol::dimension1BitByBit);
//   - Sampler::get2D as a whole (one call per camera sample and vertex);
//   - a film sample to fixed point: from the float's bits vs through a
//     double and the 128-bit library conversion (ExactSum::toFixed vs
//     toFixedByDouble).
// Indices and samples are scrambled like the real ones (random bits), so the
// bit loop's branches are as unpredictable as in a render. Prints ns per
// call (fastest of 5 rounds) and the ratios. Usage: bench_sample_kernels

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "strahl/core/sampler.h"
#include "strahl/film/exact_sum.h"

namespace {

using namespace strahl;

constexpr int kCalls = 1 << 22;
constexpr int kRounds = 5;

// Random 32-bit values (an LCG's high bits).
std::vector<uint32_t> randomBits(uint64_t seed) {
    std::vector<uint32_t> out(kCalls);
    for (uint32_t& v : out) {
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        v = static_cast<uint32_t>(seed >> 32);
    }
    return out;
}

// ns per call of f(i) over i < kCalls, fastest of kRounds; `sink` keeps the
// results alive.
template <class F>
double nsPerCall(F&& f, uint64_t& sink) {
    double best = 1e30;
    for (int round = 0; round < kRounds; ++round) {
        const auto start = std::chrono::steady_clock::now();
        uint64_t acc = 0;
        for (int i = 0; i < kCalls; ++i) acc += f(i);
        const std::chrono::duration<double, std::nano> t = std::chrono::steady_clock::now() - start;
        sink += acc;
        best = std::min(best, t.count() / kCalls);
    }
    return best;
}

}  // namespace

int main() {
    const std::vector<uint32_t> bits = randomBits(1);
    std::vector<float> samples(kCalls);
    // Radiance-like samples: positive, magnitudes spread from 2^-36 to 2^11.
    for (int i = 0; i < kCalls; ++i)
        samples[size_t(i)] = std::ldexp(float(bits[size_t(i)] & 0xFFFFu) / 65536.0f,
                                        int(bits[size_t(i)] >> 27) - 20);
    uint64_t sink = 0;

    const double table = nsPerCall([&](int i) { return sobol::dimension1(bits[size_t(i)]); }, sink);
    const double loop =
        nsPerCall([&](int i) { return sobol::dimension1BitByBit(bits[size_t(i)]); }, sink);
    const double get2D = nsPerCall(
        [&](int i) {
            Sampler sampler(7, i & 1023, i >> 10, static_cast<uint32_t>(i));
            const Vec2 u = sampler.get2D();
            return static_cast<uint64_t>((u.x + u.y) * 1024.0f);
        },
        sink);
    const auto low64 = [](Int128 v) { return static_cast<uint64_t>(v); };
    const double fromBits =
        nsPerCall([&](int i) { return low64(ExactSum::toFixed(samples[size_t(i)])); }, sink);
    const double byDouble = nsPerCall(
        [&](int i) { return low64(ExactSum::toFixedByDouble(samples[size_t(i)])); }, sink);

    std::printf("bench_sample_kernels: %d calls per round, fastest of %d rounds (checksum %llu)\n",
                kCalls, kRounds, static_cast<unsigned long long>(sink & 0xFFFF));
    std::printf("%-44s %8.2f ns\n", "sobol dimension 1, byte tables", table);
    std::printf("%-44s %8.2f ns\n", "sobol dimension 1, bit loop (definition)", loop);
    std::printf("%-44s %8.2f ns\n", "Sampler::get2D (one pair, fresh sampler)", get2D);
    std::printf("%-44s %8.2f ns\n", "film sample to fixed point, from bits", fromBits);
    std::printf("%-44s %8.2f ns\n", "film sample to fixed point, via double", byDouble);
    std::printf("ratio bit loop / tables = %.2f\n", loop / table);
    std::printf("ratio via double / from bits = %.2f\n", byDouble / fromBits);
    return 0;
}
