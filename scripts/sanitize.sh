#!/usr/bin/env bash
# Builds the whole project (library, strahl, every test; no benches) with
# AddressSanitizer + LeakSanitizer + UndefinedBehaviorSanitizer in build-asan/
# and runs the whole ctest suite under them; ends with ctest's pass/fail count
# and exits non-zero on any test failure or any sanitizer report.
# See docs/reliability.md, "Sanitizers".
#
# Usage: scripts/sanitize.sh            build, then test
#        scripts/sanitize.sh build      only configure + build (hold the build lock for this)
#        scripts/sanitize.sh test       only run the suite on an existing build-asan/
# Environment: SANITIZE_BUILD_DIR (default <root>/build-asan), CTEST_JOBS (default nproc).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SANITIZE_BUILD_DIR:-$root/build-asan}"
step="${1:-all}"
case "$step" in all | build | test) ;; *) echo "usage: $0 [build|test]" >&2; exit 2 ;; esac

# gcc (Debian's default compiler, whose libasan/libubsan come with build-essential).
# -fsanitize=undefined in gcc leaves out float-cast-overflow (a double -> int
# conversion out of range is undefined behaviour), so it is asked for too;
# float-divide-by-zero is not: IEEE division by zero is well defined and the ray
# tracer relies on it (1/direction gives ±inf slabs).
# _GLIBCXX_ASSERTIONS: libstdc++'s own checks (vector/string/span/array
# operator[] within size() — ASan alone only sees past the allocation —,
# front()/back() of an empty container, *optional without a value, ...); it
# does not change the ABI, so the uninstrumented libraries mix with it.
# -g1 (line tables, no variable or type information) is all a sanitizer's
# stack trace needs (function, file and line) and compiles and links faster
# than full -g: the sanitizer build is the longest stage of CI.
# STRAHL_SANITIZED lets a test scale down heavy workloads (pixels, rays) under
# the sanitizers only (tests/sanitizers/sanitized.h); the normal build never
# defines it.
sanitize="-fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=undefined,float-cast-overflow"
cxx_flags="$sanitize -fno-omit-frame-pointer -D_GLIBCXX_ASSERTIONS -DSTRAHL_SANITIZED=1"
link_flags="-fsanitize=address,undefined,float-cast-overflow"

# Every process that runs instrumented code — ctest's test binaries, the strahl
# binary the CLI tests start, and gtest_discover_tests' listing at build time —
# writes its ASan/LSan report into $logs (one file per process) instead of
# stderr, so a report from a child whose stderr a test captures is never lost;
# any such file fails the run. (UBSan, linked with ASan, ignores log_path and
# prints to stderr: the test's own output, which ctest shows, or for strahl
# the stderr runStrahl captures and prints — tests/app/cli_runner.h.)
logs="$build/sanitizer-logs"
# exitcode=86: a process stopped by a sanitizer never exits with the 0, 1, 2 or
# 128 + signal that the CLI tests expect from strahl; runStrahl fails on 86.
# new_delete_type_mismatch=0: OpenImageIO 2.4's TextureSystem::destroy (the
# only way its API gives to free a TextureSystem) runs ~TextureSystemImpl and
# then calls operator delete(p, 1) on the 184-byte object it allocated in
# TextureSystem::create — a sized-delete mismatch wholly inside
# libOpenImageIO.so (harmless with glibc's allocator, which ignores the size).
# ASan cannot suppress this check per library or function, only switch it off;
# our own code is covered by -Wdelete-non-virtual-dtor (-Wall) and
# -Wnon-virtual-dtor. Every other ASan check stays on.
asan="detect_leaks=1:halt_on_error=1:abort_on_error=0:exitcode=86"
asan+=":detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1"
asan+=":new_delete_type_mismatch=0"
export ASAN_OPTIONS="$asan:log_path=$logs/asan"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=86"
supp="$root/tests/sanitizers/lsan.supp"
if [ -f "$supp" ]; then
  export LSAN_OPTIONS="suppressions=$supp:print_suppressions=0"
fi

# Prints every sanitizer report in $logs; succeeds only if there is none.
no_reports() {
  local found=0 f
  shopt -s nullglob
  for f in "$logs"/asan.*; do
    found=1
    echo "==== sanitizer report: $f"
    cat "$f"
  done
  shopt -u nullglob
  return $found
}

if [ "$step" != test ]; then
  "$root/scripts/setup.sh"   # Debian packages (and the normal build/ configure)
  generator=()
  command -v ninja >/dev/null && generator=(-G Ninja)
  rm -rf "$logs"
  mkdir -p "$logs"
  cmake -S "$root" -B "$build" "${generator[@]}" \
    -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_C_COMPILER=gcc -DCMAKE_CXX_COMPILER=g++ \
    -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
    -DCMAKE_CXX_FLAGS="$cxx_flags" \
    -DCMAKE_EXE_LINKER_FLAGS="$link_flags" \
    -DCMAKE_SHARED_LINKER_FLAGS="$link_flags" \
    -DSTRAHL_BUILD_TESTS=ON -DSTRAHL_BUILD_BENCH=OFF -DSTRAHL_BUILD_FUZZERS=OFF
  start=$SECONDS
  if ! cmake --build "$build"; then
    no_reports || true
    exit 1
  fi
  echo "sanitize: build took $((SECONDS - start)) s"
  if ! no_reports; then
    echo "sanitize: sanitizer reports while building (test discovery)" >&2
    exit 1
  fi
fi

if [ "$step" != build ]; then
  [ -f "$build/CTestTestfile.cmake" ] || { echo "sanitize: no build in $build; run '$0 build' first" >&2; exit 1; }
  rm -rf "$logs"
  mkdir -p "$logs"
  start=$SECONDS
  status=0
  (cd "$build" && ctest --output-on-failure --timeout 900 -j "${CTEST_JOBS:-$(nproc)}") 2>&1 |
    tee "$build/ctest.log" || status=$?
  echo "sanitize: ctest took $((SECONDS - start)) s"
  if ! no_reports; then
    echo "sanitize: sanitizer reports above (one file per process in $logs)" >&2
    status=1
  fi
  # End with ctest's pass/fail count, as scripts/test.sh does.
  summary="$(grep -E 'tests passed, [0-9]+ tests? failed out of' "$build/ctest.log" | tail -1 || true)"
  if [ "$status" -ne 0 ]; then
    echo "sanitize: FAILED: ${summary:-ctest did not finish}" >&2
    exit 1
  fi
  echo "sanitize: no sanitizer report; $summary"
fi
