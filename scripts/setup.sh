#!/usr/bin/env bash
# Installs the Debian 12 packages strahl builds with (only those missing), then
# configures the CMake build in build/ (Release unless BUILD_TYPE says otherwise)
# with MPI on (STRAHL_MPI: strahl render --distributed, docs/distributed.md).
# Usage: scripts/setup.sh            (run from anywhere; uses sudo when not root)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

packages=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libopenimageio-dev libopenexr-dev libopencolorio-dev
  libglm-dev libtbb-dev libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev libtinygltf-dev
  clang-14 libclang-rt-14-dev
  libopenmpi-dev openmpi-bin
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
fi

generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f "$root/build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$root/build" "${generator[@]}" -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" \
    -DSTRAHL_MPI=ON
elif ! grep -q '^STRAHL_MPI:BOOL=ON$' "$root/build/CMakeCache.txt"; then
  # A build/ configured before MPI was an option (or without it): turn it on.
  cmake -S "$root" -B "$root/build" -DSTRAHL_MPI=ON
fi
