// bench_sample_kernels: the per-sample kernels of issue 20, part 1, each
// against the definition it replaced, in one run (so machine load hits both):
//   - the second Sobol dimension: four byte tables vs the loop over the
//     index's bits (sobol::dimension1 vs sobol::dimension1BitByBit);
//   - Sampler::get2D as a whole (one call per camera sample and vertex);
//   - a film sample to fixed point: from the float's bits vs through a
//     double and the 128-bit library conversion (ExactSum::toFixed vs
//     toFixedByDouble);
//   - a light BVH node's importance at a shading point: from the cone's
//     cosines and sines (ImportanceBounds, what the tree's walk evaluates) vs
//     from its angles (LightBounds::importance, the definition), two per
//     level of every light choice.
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
#include "strahl/integrator/light_bounds.h"

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

    // 1024 node bounds and 1024 receivers, random like the nodes of a lamp
    // grid seen from a room: cones of every width, boxes of every size.
    std::vector<LightBounds> nodes(1024);
    std::vector<ImportanceBounds> walked(1024);
    std::vector<Vec3> points(1024), normals(1024);
    {
        uint64_t state = 5;
        const auto next = [&] {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            return float(state >> 40) / float(1 << 24);
        };
        const auto unit = [&] {
            const float z = 1.0f - 2.0f * next(), phi = 2.0f * kPi * next();
            const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
            return Vec3(r * std::cos(phi), r * std::sin(phi), z);
        };
        for (size_t k = 0; k < nodes.size(); ++k) {
            const Vec3 c(10.0f * next(), 3.0f + next(), 10.0f * next());
            nodes[k].box.expand(c);
            nodes[k].box.expand(c + Vec3(next(), 0.1f * next(), next()) * (4.0f * next()));
            nodes[k].axis = unit();
            nodes[k].thetaO = kPi * next() * next();
            nodes[k].thetaE = 0.5f * kPi;
            nodes[k].power = 1.0f + next();
            walked[k] = ImportanceBounds(nodes[k]);
            points[k] = Vec3(10.0f * next(), 3.0f * next(), 10.0f * next());
            normals[k] = unit();
        }
    }
    const auto asBits = [](float x) { return static_cast<uint64_t>(x * 1e6f); };
    const double cosines = nsPerCall(
        [&](int i) { return asBits(walked[size_t(i) & 1023].importance(points[size_t(i >> 10) & 1023], normals[size_t(i >> 10) & 1023])); },
        sink);
    const double angles = nsPerCall(
        [&](int i) { return asBits(nodes[size_t(i) & 1023].importance(points[size_t(i >> 10) & 1023], normals[size_t(i >> 10) & 1023])); },
        sink);

    std::printf("bench_sample_kernels: %d calls per round, fastest of %d rounds (checksum %llu)\n",
                kCalls, kRounds, static_cast<unsigned long long>(sink & 0xFFFF));
    std::printf("%-44s %8.2f ns\n", "sobol dimension 1, byte tables", table);
    std::printf("%-44s %8.2f ns\n", "sobol dimension 1, bit loop (definition)", loop);
    std::printf("%-44s %8.2f ns\n", "Sampler::get2D (one pair, fresh sampler)", get2D);
    std::printf("%-44s %8.2f ns\n", "film sample to fixed point, from bits", fromBits);
    std::printf("%-44s %8.2f ns\n", "film sample to fixed point, via double", byDouble);
    std::printf("%-44s %8.2f ns\n", "light BVH importance, cosines and sines", cosines);
    std::printf("%-44s %8.2f ns\n", "light BVH importance, angles (definition)", angles);
    std::printf("ratio bit loop / tables = %.2f\n", loop / table);
    std::printf("ratio via double / from bits = %.2f\n", byDouble / fromBits);
    std::printf("ratio angles / cosines = %.2f\n", angles / cosines);
    return 0;
}
