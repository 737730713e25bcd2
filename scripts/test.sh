#!/usr/bin/env bash
# README command 2 (and what CI runs): set up, build everything and run the
# whole test suite with ctest; then the same suite again under ASan + UBSan
# (scripts/sanitize.sh) and every libFuzzer target for a bounded time
# (scripts/fuzz.sh). Ends with one pass/fail count over all three and exits
# non-zero if anything failed. docs/reliability.md describes the last two.
#
# Usage: scripts/test.sh           everything (what CI runs, in a clean root; about 35 min on 2 cores after README command 1)
#        scripts/test.sh --quick   the Release suite only (the edit-build-test loop)
# Environment: FUZZ_SECONDS, fuzzing time per target (default 30).
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
quick=0
case "${1:-}" in
  "") ;;
  --quick) quick=1 ;;
  *) echo "usage: $0 [--quick]" >&2; exit 2 ;;
esac

"$root/scripts/setup.sh" || exit 1
cmake --build "$root/build" || { echo "test: the Release build failed" >&2; exit 1; }

# "N% tests passed, F tests failed out of T" -> "passed failed" (empty if absent).
counts() {
  sed -n 's/.*tests passed, \([0-9]*\) tests\{0,1\} failed out of \([0-9]*\).*/\1 \2/p' "$1" |
    tail -n 1 | awk '{ print $2 - $1, $1 }'
}

release_log="$root/build/ctest.log"
(cd "$root/build" && ctest --output-on-failure --timeout 900 -j "$(nproc)") 2>&1 | tee "$release_log"
read -r release_pass release_fail <<<"$(counts "$release_log")"
release_pass="${release_pass:-0}" release_fail="${release_fail:-1}"
if ((quick)); then
  echo "test: $release_pass passed, $release_fail failed (Release ctest; sanitizers and fuzzing skipped: --quick)"
  ((release_fail == 0)) && exit 0 || exit 1
fi

sanitize_log="$root/build/sanitize.log"
"$root/scripts/sanitize.sh" 2>&1 | tee "$sanitize_log"
sanitize_status=${PIPESTATUS[0]}
read -r sanitize_pass sanitize_fail <<<"$(counts "$sanitize_log")"
sanitize_pass="${sanitize_pass:-0}" sanitize_fail="${sanitize_fail:-0}"
# A sanitizer report fails the run even when every test passed: count it as a failure.
if ((sanitize_status != 0 && sanitize_fail == 0)); then sanitize_fail=1; fi

fuzz_log="$root/build/fuzz.log"
"$root/scripts/fuzz.sh" --seconds "${FUZZ_SECONDS:-30}" 2>&1 | tee "$fuzz_log"
fuzz_status=${PIPESTATUS[0]}
read -r fuzz_total fuzz_clean <<<"$(sed -n 's/^fuzz: \([0-9]*\) targets, \([0-9]*\) clean$/\1 \2/p' "$fuzz_log")"
fuzz_total="${fuzz_total:-8}" fuzz_clean="${fuzz_clean:-0}"
if ((fuzz_status != 0 && fuzz_clean == fuzz_total)); then fuzz_clean=$((fuzz_total - 1)); fi

passed=$((release_pass + sanitize_pass + fuzz_clean))
failed=$((release_fail + sanitize_fail + fuzz_total - fuzz_clean))
echo "test: $passed passed, $failed failed (Release ctest $release_pass/$((release_pass + release_fail)), sanitizer ctest $sanitize_pass/$((sanitize_pass + sanitize_fail)), fuzz targets clean $fuzz_clean/$fuzz_total)"
((failed == 0))
