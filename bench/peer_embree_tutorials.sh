#!/usr/bin/env bash
# strahl against Embree's own tutorials (Debian `embree-tools`: `viewer` and
# `pathtracer`) on one scene, in one run: issue 20, part 1.
#
# The scene (written once into the cache folder, the same OBJ for both
# programs): a UV sphere of 2 million triangles on a ground quad with a small
# marker box, grey Lambert (Kd 0.8), one point light, black background.
#
# What is timed: each program's render phase alone, after the BVH is built
# and before the image is written: strahl's own statistics (timings.render);
# the tutorials, which print no time, from their system calls (strace, below).
# Every figure is the median of --repeats runs, interleaved (viewer, strahl,
# viewer, strahl, ...) so load on a shared machine hits both.
#
#   eyelight: 1 camera ray per pixel, 1024 x 1024, eyelight shading.
#             Figure: Mrays/s = 1024^2 / render time.
#   path:     512 x 512, 16 spp, the light of 4 bounces: the pathtracer's
#             --max-path-length 5 (5 hits, each with a shadow ray) against
#             strahl's --max-depth 5, no Russian roulette in either.
#             Figure: seconds per sample pass = render time / 16.
#
# Ratios printed at the end, with the targets of issue 20:
#   strahl eyelight Mrays/s / viewer Mrays/s          (target >= 2)
#   strahl path s per sample / pathtracer s per sample (target <= 0.8)
# and the ceiling of each:
#   eyelight: strahl's camera packets of the same view traced alone by
#             rtcIntersect16/8 (the machine's native width: 8 without
#             AVX-512), with no ray generation, shading or film
#             (bench_primary_rays --scene, its case (a)), against the viewer:
#             the most any renderer tracing those rays through this Embree
#             could reach;
#   path:     every query of strahl's path render recorded and replayed
#             through the same BVH with nothing else (bench_path_rays), per
#             sample, against the pathtracer's whole time per sample: while
#             Embree alone takes more than 0.8 of it, the target is out of
#             reach whatever strahl's shading costs.
#
# Usage: bench/peer_embree_tutorials.sh [--repeats N] [--threads N] [--cache DIR]
#        (run from anywhere; needs a Release build in build/ and embree-tools,
#        both installed by scripts/setup.sh)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
repeats=3
threads="$(nproc)"
cache="${XDG_CACHE_HOME:-$HOME/.cache}/strahl/peer_embree"
while (($#)); do
  case "$1" in
    --repeats) repeats="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --cache) cache="$2"; shift 2 ;;
    *) echo "usage: $0 [--repeats N] [--threads N] [--cache DIR]" >&2; exit 2 ;;
  esac
done
strahl="$root/build/bin/strahl"
bare_bench="$root/build/bin/bench_primary_rays"
path_bench="$root/build/bin/bench_path_rays"
for tool in viewer pathtracer; do
  command -v "$tool" >/dev/null || {
    echo "peer: '$tool' not found: Debian's embree-tools is missing (scripts/setup.sh installs it)" >&2
    exit 1
  }
done
for program in "$strahl" "$bare_bench" "$path_bench"; do
  [ -x "$program" ] || { echo "peer: $program not found: build first (scripts/setup.sh && cmake --build build)" >&2; exit 1; }
done

mkdir -p "$cache"
obj="$cache/sphere_scene.obj"
# 1000 rings x 1000 segments: 2 x 1000 x 999 sphere triangles (the pole rings
# are fans), plus 2 for the ground and 12 for the box.
if [ ! -s "$obj" ]; then
  echo "peer: writing the scene to $obj"
  awk 'BEGIN {
    pi = 3.14159265358979; rings = 1000; segs = 1000; cx = 0; cy = 1; cz = 0; r = 1
    print "mtllib sphere_scene.mtl"; print "usemtl grey"
    # vertices: the two poles, then rings-1 rings of segs vertices
    print "v", cx, cy + r, cz; print "v", cx, cy - r, cz
    for (i = 1; i < rings; i++) {
      th = pi * i / rings; y = cy + r * cos(th); s = r * sin(th)
      for (j = 0; j < segs; j++) {
        ph = 2 * pi * j / segs
        printf "v %.7f %.7f %.7f\n", cx + s * cos(ph), y, cz + s * sin(ph)
      }
    }
    # ring i (1-based), segment j -> vertex index (OBJ is 1-based; poles are 1 and 2)
    for (j = 0; j < segs; j++) {
      a = 3 + j; b = 3 + (j + 1) % segs
      print "f", 1, b, a
    }
    for (i = 1; i < rings - 1; i++) {
      for (j = 0; j < segs; j++) {
        a = 3 + (i - 1) * segs + j; b = 3 + (i - 1) * segs + (j + 1) % segs
        c = a + segs; d = b + segs
        print "f", a, b, d; print "f", a, d, c
      }
    }
    base = 3 + (rings - 2) * segs
    for (j = 0; j < segs; j++) {
      a = base + j; b = base + (j + 1) % segs
      print "f", 2, a, b
    }
    n = 2 + (rings - 1) * segs
    # the ground quad y = 0, 20 x 20, facing up
    print "v -10 0 -10"; print "v 10 0 -10"; print "v 10 0 10"; print "v -10 0 10"
    print "f", n + 1, n + 4, n + 3; print "f", n + 1, n + 3, n + 2
    n += 4
    # the marker box: 0.4 wide, at x = 1.6, z = 0.6
    x0 = 1.4; x1 = 1.8; y0 = 0; y1 = 0.4; z0 = 0.4; z1 = 0.8
    print "v", x0, y0, z0; print "v", x1, y0, z0; print "v", x1, y1, z0; print "v", x0, y1, z0
    print "v", x0, y0, z1; print "v", x1, y0, z1; print "v", x1, y1, z1; print "v", x0, y1, z1
    split("1 2 3 1 3 4 5 7 6 5 8 7 1 5 6 1 6 2 2 6 7 2 7 3 3 7 8 3 8 4 4 8 5 4 5 1", f, " ")
    for (k = 1; k <= 36; k += 3) print "f", n + f[k], n + f[k + 1], n + f[k + 2]
  }' >"$obj.tmp"
  mv "$obj.tmp" "$obj"
fi
printf 'newmtl grey\nKd 0.8 0.8 0.8\nKs 0 0 0\n' >"$cache/sphere_scene.mtl"

# One camera for both: eye, look-at point, up, vertical field of view.
eye=(0 1.6 4.5) at=(0 0.9 0) up=(0 1 0) fov=40
light=(3 5 4) intensity=40
cat >"$cache/sphere_scene.json" <<EOF
// Written by bench/peer_embree_tutorials.sh: the scene of issue 20.
{
  "camera": { "type": "perspective", "eye": [${eye[0]}, ${eye[1]}, ${eye[2]}],
              "look_at": [${at[0]}, ${at[1]}, ${at[2]}], "up": [${up[0]}, ${up[1]}, ${up[2]}], "fov": $fov },
  "film": { "width": 512, "height": 512, "filter": "box" },
  "render": { "integrator": "path", "spp": 16, "max_depth": 5, "russian_roulette": false },
  "shapes": [ { "type": "mesh", "file": "sphere_scene.obj" } ],
  "lights": [ { "type": "point", "position": [${light[0]}, ${light[1]}, ${light[2]}], "intensity": $intensity } ]
}
EOF

# The pathtracer's arguments for this scene (camera, light, path length), one
# per line: bench_convergence runs the tutorial with them for its sphere-scene
# curve.
printf '%s\n' -i "$obj" --vp "${eye[@]}" --vi "${at[@]}" --vu "${up[@]}" --fov "$fov" \
  --pointlight "${light[@]}" "$intensity" "$intensity" "$intensity" --max-path-length 5 \
  >"$cache/sphere_scene.pathtracer-args"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
embree_camera=(--vp "${eye[@]}" --vi "${at[@]}" --vu "${up[@]}" --fov "$fov" --threads "$threads")

# Render seconds of one tutorial run ($1: the output it writes, then its
# command). The tutorials print no render time, so it is read from the system
# calls (strace, filtered in the kernel so the rendering threads are not
# slowed): from the line "  accels[0]", which --verbose 2 prints once the BVH
# is built, to the opening of the output image, which comes right after the
# frame is rendered.
tutorial_seconds() {
  local out="$1"
  shift
  strace -f --seccomp-bpf -ttt -e trace=openat,write -o "$work/trace" \
    stdbuf -oL "$@" --verbose 2 -o "$work/$out" >"$work/log" 2>&1 ||
    { echo "peer: failed: $*" >&2; cat "$work/log" >&2; exit 1; }
  awk -v out="\"$work/$out\"" '/write\(1, "  accels\[0\]/ && !a { a = $2 }
    index($0, out) && /openat/ { b = $2 }
    END { if (!a || !b) exit 1; printf "%.4f\n", b - a }' "$work/trace" ||
    { echo "peer: no render interval in the trace of: $*" >&2; exit 1; }
}
# Render seconds of one strahl run, from its own statistics (timings.render:
# the tiles, after the BVH, before the outputs are written).
strahl_seconds() {
  "$strahl" render "$cache/sphere_scene.json" --threads "$threads" -q -o "$work/s.exr" \
    --stats "$work/stats.json" "$@" >"$work/log" 2>&1 ||
    { echo "peer: failed: strahl render $*" >&2; cat "$work/log" >&2; exit 1; }
  awk '/"render":/ { gsub(/[",]/, ""); print $2; exit }' "$work/stats.json"
}
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "peer: scene $(grep -c '^f' "$obj") triangles; $threads threads; $repeats interleaved repeats; $(dpkg-query -W -f='embree-tools ${Version}' embree-tools 2>/dev/null || echo 'embree-tools')"
declare -a viewer eyelight tracer path
for ((k = 0; k < repeats; k++)); do
  viewer+=("$(tutorial_seconds v.tga viewer -i "$obj" "${embree_camera[@]}" --shader eyelight --size 1024 1024)")
  eyelight+=("$(strahl_seconds --integrator eyelight --spp 1 --width 1024 --height 1024)")
  tracer+=("$(tutorial_seconds p.tga pathtracer -i "$obj" "${embree_camera[@]}" \
    --pointlight "${light[@]}" "$intensity" "$intensity" "$intensity" --spp 16 --max-path-length 5 --size 512 512)")
  path+=("$(strahl_seconds)")
  rays=$(awk '/"rays":/ { r = 1 } r && /"total":/ { gsub(/,/, ""); print $2; exit }' "$work/stats.json")
  echo "peer: repeat $((k + 1)): viewer ${viewer[k]} s, strahl eyelight ${eyelight[k]} s, pathtracer ${tracer[k]} s, strahl path ${path[k]} s"
done

# The ceiling (about 20 s): "(a) bare X  (b) eyelight Y" from the bench's summary.
"$bare_bench" --scene "$cache/sphere_scene.json" >"$work/bare.log" 2>&1 ||
  { echo "peer: failed: $bare_bench --scene $cache/sphere_scene.json" >&2; cat "$work/bare.log" >&2; exit 1; }
read -r bare bare_eyelight < <(sed -n 's/.*(a) bare \([0-9.]*\) *(b) eyelight \([0-9.]*\).*/\1 \2/p' "$work/bare.log")
[ -n "${bare:-}" ] || { echo "peer: no '(a) bare' figure in the output of $bare_bench" >&2; cat "$work/bare.log" >&2; exit 1; }
# The path ceiling (about 15 s): "render X s  embree Y s" per sample.
"$path_bench" --scene "$cache/sphere_scene.json" --threads "$threads" >"$work/path.log" 2>&1 ||
  { echo "peer: failed: $path_bench --scene $cache/sphere_scene.json" >&2; cat "$work/path.log" >&2; exit 1; }
read -r path_embree < <(sed -n 's/.*render [0-9.]* s *embree \([0-9.]*\) s.*/\1/p' "$work/path.log")
[ -n "${path_embree:-}" ] || { echo "peer: no 'embree' figure in the output of $path_bench" >&2; cat "$work/path.log" >&2; exit 1; }

awk -v v="$(median "${viewer[@]}")" -v e="$(median "${eyelight[@]}")" \
  -v t="$(median "${tracer[@]}")" -v p="$(median "${path[@]}")" -v rays="$rays" \
  -v bare="$bare" -v bare_eyelight="$bare_eyelight" -v path_embree="$path_embree" 'BEGIN {
  n = 1024 * 1024
  printf "eyelight 1024x1024, 1 spp: viewer %.1f Mrays/s, strahl %.1f Mrays/s\n", n / v / 1e6, n / e / 1e6
  printf "path 512x512, 16 spp: pathtracer %.4f s per sample, strahl %.4f s per sample (strahl: %.1f M rays)\n", t / 16, p / 16, rays / 1e6
  printf "ratio strahl/viewer Mrays/s         = %.2f  (target >= 2.00) %s\n", v / e, (v / e >= 2) ? "PASS" : "FAIL"
  printf "ratio strahl/pathtracer s per sample = %.2f  (target <= 0.80) %s\n", p / t, (p / t <= 0.8) ? "PASS" : "FAIL"
  printf "eyelight ceiling: Embree alone (rtcIntersect8/16) on strahl'"'"'s camera packets %.1f Mrays/s = %.2f x the viewer; strahl'"'"'s eyelight render reaches %.2f of it (bench_primary_rays, fastest rounds)\n", bare, bare / (n / v / 1e6), bare_eyelight / bare
  printf "path ceiling: Embree alone on strahl'"'"'s recorded path queries %.4f s per sample = %.2f x the pathtracer'"'"'s whole time (bench_path_rays, fastest round)\n", path_embree, path_embree / (t / 16)
}'
