#!/usr/bin/env bash
# README command 2 (and what CI runs): set up, build everything, run the whole
# test suite with ctest and end with its pass/fail count.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
cmake --build "$root/build"
cd "$root/build"
ctest --output-on-failure --timeout 900 -j "$(nproc)"
