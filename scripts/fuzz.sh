#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ with clang, AddressSanitizer (leak
# detection on) and UndefinedBehaviorSanitizer in build-fuzz/, then runs each for
# a bounded time on a copy of its seed corpus (the committed corpus is never
# grown). Prints one line per target and a summary; exits non-zero if any target
# found a crash, a leak, undefined behaviour, a timeout or an out-of-memory.
# Inputs that failed are kept in build-fuzz/fuzz-artifacts/<target>/ (replay
# one with build-fuzz/bin/<target> <file>). docs/reliability.md, "Fuzzing".
#
# Usage: scripts/fuzz.sh [--seconds N] [--jobs N] [target...]
#   --seconds N   fuzzing time per target (default 30)
#   --jobs N      targets fuzzed at once, each in its own process on one core
#                 (default: the number of cores; the time per target is the same)
#   target        fuzz_scene_json, fuzz_mitsuba_xml, fuzz_pbrt, fuzz_ply, fuzz_serialized, fuzz_obj,
#                 fuzz_gltf, fuzz_formula (default: all)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build-fuzz"
all_targets=(fuzz_scene_json fuzz_mitsuba_xml fuzz_pbrt fuzz_ply fuzz_serialized fuzz_obj fuzz_gltf fuzz_formula)

seconds=30
jobs="$(nproc)"
targets=()
# Ends the script with a usage error unless option $1's value $2 is a positive
# whole number.
need_positive() {
  [[ "${2:-}" =~ ^[0-9]+$ && "$2" -gt 0 ]] || {
    echo "fuzz: $1 needs a positive whole number" >&2
    exit 2
  }
}
while (($#)); do
  case "$1" in
    --seconds | --jobs)
      need_positive "$1" "${2:-}"
      if [ "$1" = --seconds ]; then seconds="$2"; else jobs="$2"; fi
      shift 2
      ;;
    -h | --help)
      sed -n '2,15p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
      exit 0
      ;;
    fuzz_*)
      [[ " ${all_targets[*]} " == *" $1 "* ]] || { echo "fuzz: unknown target '$1'" >&2; exit 2; }
      targets+=("$1")
      shift
      ;;
    *)
      echo "fuzz: unknown argument '$1' (usage: scripts/fuzz.sh [--seconds N] [--jobs N] [target...])" >&2
      exit 2
      ;;
  esac
done
((${#targets[@]})) || targets=("${all_targets[@]}")

# clang with libFuzzer and the sanitizer runtimes (clang-14, libclang-rt-14-dev
# in scripts/packages.txt).
"$root/scripts/install-packages.sh"
cc=clang
cxx=clang++
command -v "$cxx" >/dev/null || { cc=clang-14; cxx=clang++-14; }

# The libraries get coverage instrumentation and the sanitizers; the fuzz targets
# add -fsanitize=fuzzer (fuzz/CMakeLists.txt). -O1 with line tables: fast enough
# to fuzz, quick to build, readable stack traces; assertions stay on. UBSan's
# vptr check is off for the libraries: it makes tinygltf's and nlohmann::json's
# templates (gltf_parse.cpp) take about six times longer to compile, and the
# parsers do no downcasts for it to check.
sanitize="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=vptr"
sanitize+=" -fno-sanitize-recover=undefined"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
start=$SECONDS
CC="$cc" CXX="$cxx" cmake -S "$root" -B "$build" "${generator[@]}" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS="$sanitize -fno-omit-frame-pointer" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DSTRAHL_BUILD_FUZZERS=ON -DSTRAHL_BUILD_TESTS=OFF -DSTRAHL_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" --target "${targets[@]}"
echo "fuzz: built ${#targets[@]} targets in $((SECONDS - start)) s"

# Runtime options: leaks are errors, UB halts with a stack trace, and an input
# that fails leaves its artifact behind for a regression test.
export ASAN_OPTIONS="detect_leaks=1:symbolize=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:${UBSAN_OPTIONS:-}"
work="$(mktemp -d "${TMPDIR:-/tmp}/strahl-fuzz.XXXXXX")"
trap 'rm -rf "$work"' EXIT
artifacts="$build/fuzz-artifacts"
logs="$build/fuzz-logs"
mkdir -p "$logs"

# One target's run; its exit status goes to $work/<target>/status (the function
# itself always succeeds, so that `wait` below never stops the script).
fuzz_target() {
  local t="$1" status=0 dict=()
  [ -f "$root/fuzz/dict/$t.dict" ] && dict=("-dict=$root/fuzz/dict/$t.dict")
  # TMPDIR: the harness's scratch folder and the glTF loader's extracted images
  # land in the work folder, which is removed afterwards.
  TMPDIR="$work/$t/tmp" "$build/bin/$t" "$work/$t/corpus" "${dict[@]}" \
    -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$artifacts/$t/" >"$logs/$t.log" 2>&1 || status=$?
  echo "$status" >"$work/$t/status"
}

# libFuzzer runs one process on one core: --jobs targets run side by side,
# each for the same --seconds as alone.
running=0
for t in "${targets[@]}"; do
  rm -rf "${artifacts:?}/$t"
  mkdir -p "$work/$t/corpus" "$work/$t/tmp" "$artifacts/$t"
  cp "$root/fuzz/corpus/$t/"* "$work/$t/corpus/"
  fuzz_target "$t" &
  running=$((running + 1))
  if ((running >= jobs)); then
    wait -n
    running=$((running - 1))
  fi
done
wait

# The results, in the targets' order.
clean=0
for t in "${targets[@]}"; do
  status="$(cat "$work/$t/status" 2>/dev/null || echo "?")"
  # The final stats, or the last status line of a run that did not get there.
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$logs/$t.log" | tail -n 1)"
  [ -n "$runs" ] || runs="$(sed -n 's/^#\([0-9][0-9]*\).*/\1/p' "$logs/$t.log" | tail -n 1)"
  found=("$artifacts/$t"/*)
  [ -e "${found[0]}" ] || found=()
  if [ "$status" -eq 0 ] && ((${#found[@]} == 0)); then
    result="clean"
    clean=$((clean + 1))
    rmdir "$artifacts/$t"
  else
    kind="FAILED (exit $status)"
    grep -q "ERROR: libFuzzer: deadly signal" "$logs/$t.log" && kind="CRASH"
    grep -q "ERROR: LeakSanitizer" "$logs/$t.log" && kind="LEAK"
    grep -q "ERROR: AddressSanitizer" "$logs/$t.log" && kind="CRASH (AddressSanitizer)"
    grep -q "runtime error:" "$logs/$t.log" && kind="UNDEFINED BEHAVIOUR"
    grep -q "ERROR: libFuzzer: timeout" "$logs/$t.log" && kind="TIMEOUT"
    grep -q "ERROR: libFuzzer: out-of-memory" "$logs/$t.log" && kind="OUT OF MEMORY"
    result="$kind: ${found[*]:-no artifact}; log $logs/$t.log"
  fi
  printf '%-16s %10s runs  %s\n' "$t" "${runs:-?}" "$result"
  if [ "$result" != "clean" ]; then
    # The report and the input, so that a failure on a CI machine (whose
    # build folder is gone afterwards) can be reproduced from its log alone.
    echo "---- $t: the report (from the first error line, at most 40 lines) ----"
    # (sed may be cut off by head: pipefail must not end the script here)
    sed -n '/ERROR\|runtime error:\|terminate called\|what():/,$p' "$logs/$t.log" | head -n 40 || true
    for f in "${found[@]}"; do
      echo "---- $t: $(basename "$f") ($(stat -c %s "$f") bytes), base64 (first 8 KiB) ----"
      head -c 8192 "$f" | base64
    done
    echo "---- end of $t ----"
  fi
done
echo "fuzz: $((SECONDS - start)) s in all, build included"
echo "fuzz: ${#targets[@]} targets, $clean clean"
[ "$clean" -eq "${#targets[@]}" ]
