#pragma once
// Heavy test workloads, scaled down under the sanitizers only.
//
// scripts/sanitize.sh builds everything with ASan + UBSan at -O1 and defines
// STRAHL_SANITIZED. There the naive tracer and the implicit/parametric root
// finders (stack-heavy double-precision glm code, every stack temporary
// poisoned and checked) run 15-40x slower than in Release, and a handful of
// tests would take minutes each. Such a test scales the *amount of work* it
// does — pixels, rays, samples — with these helpers; what it asserts about
// that work stays the same (a count threshold scales with the count). The
// normal build never defines STRAHL_SANITIZED and runs the full workload.

#include <algorithm>

namespace strahl::test {

#ifdef STRAHL_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

// The exit status of a process a sanitizer stopped (exitcode= in the
// ASAN_OPTIONS and UBSAN_OPTIONS of scripts/sanitize.sh): never one of
// strahl's own (0, 1, 2, 128 + a signal).
inline constexpr int kSanitizerExitCode = 86;

// `full` in the normal build, `reduced` under the sanitizers.
template <class T>
constexpr T fullOrSanitized(T full, T reduced) {
    return kSanitized ? reduced : full;
}

// Under the sanitizers, divides the film resolution of a SceneDesc by `factor`
// in each dimension (at least 8 x 8 pixels): the same view, fewer pixels. A
// no-op in the normal build.
template <class Desc>
void shrinkFilmWhenSanitized(Desc& desc, int factor) {
    if constexpr (kSanitized) {
        desc.film.width = std::max(8, desc.film.width / factor);
        desc.film.height = std::max(8, desc.film.height / factor);
    }
}

}  // namespace strahl::test
