#!/usr/bin/env bash
# Installs the Debian 12 packages of scripts/packages.txt (only those missing), then
# configures the CMake build in build/ (Release unless BUILD_TYPE says otherwise)
# with MPI on (STRAHL_MPI: strahl render --distributed, docs/distributed.md).
# Usage: scripts/setup.sh            (run from anywhere; uses sudo when not root)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

"$root/scripts/install-packages.sh"   # the Debian packages of scripts/packages.txt

generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f "$root/build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$root/build" "${generator[@]}" -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" \
    -DSTRAHL_MPI=ON
elif ! grep -q '^STRAHL_MPI:BOOL=ON$' "$root/build/CMakeCache.txt"; then
  # A build/ configured before MPI was an option (or without it): turn it on.
  cmake -S "$root" -B "$root/build" -DSTRAHL_MPI=ON
fi
