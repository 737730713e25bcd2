#pragma once
// Internal to the benchmark module: the clock the benchmarks time their
// phases with (bench_suite.cpp, path_bench.cpp).

#include <chrono>

namespace strahl::bench_detail {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace strahl::bench_detail
