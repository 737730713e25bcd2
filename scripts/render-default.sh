#!/usr/bin/env bash
# README command 1: set up, build Release, render the default scene to
# out/default.exr and out/default.png.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
cmake --build "$root/build" --target strahl
mkdir -p "$root/out"
"$root/build/bin/strahl" render "$root/scenes/default.json" \
  -o "$root/out/default.exr" -o "$root/out/default.png"
echo "rendered: $root/out/default.exr (scene-linear, with normal/depth/albedo/variance AOVs)"
echo "rendered: $root/out/default.png (sRGB display)"
