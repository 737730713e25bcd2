#!/usr/bin/env bash
# Scaling of `strahl render --distributed` (docs/distributed.md), in one run:
# the same render as 1 process without MPI, then under mpirun with 2 and 3
# ranks (1 scheduler + 1 or 2 workers) on this machine. Prints, per case, the
# wall time of the whole command (MPI start-up and every rank's scene load
# included), the render time rank 0 reports (first request to last tile
# gathered), the speedup of each over 1 process, and checks that every
# distributed image equals the 1-process one bit for bit.
#
# Usage: bench/distributed_scaling.sh [SCENE [STRAHL FLAGS...]]
#        default: scenes/default.json --spp 16   (512 x 512, path tracing)
# Environment: STRAHL (the binary, default build/bin/strahl), REPEATS (runs per
# case, the fastest kept; default 1), RANKS (default "2 3").
# Needs a build with -DSTRAHL_MPI=ON and mpirun (Open MPI). Ranks may use every
# core (--bind-to none); as root, mpirun's root check is waived for this script.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
strahl="${STRAHL:-$root/build/bin/strahl}"
repeats="${REPEATS:-1}"
ranks_list="${RANKS:-2 3}"
scene="${1:-$root/scenes/default.json}"
shift || true
flags=("$@")
((${#flags[@]})) || flags=(--spp 16)
command -v mpirun >/dev/null || { echo "distributed_scaling: mpirun not found (apt-get install openmpi-bin)" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# run NAME COMMAND... : the best wall and render seconds over $repeats runs -> "wall render"
run() {
  local name="$1" best_wall="" best_render=""
  shift
  for ((i = 0; i < repeats; i++)); do
    local start end wall render
    start=$(date +%s.%N)
    "$@" -o "$work/$name.exr" 2>"$work/$name.log" >/dev/null ||
      { echo "distributed_scaling: $name failed:" >&2; cat "$work/$name.log" >&2; exit 1; }
    end=$(date +%s.%N)
    wall=$(awk -v a="$end" -v b="$start" 'BEGIN { print a - b }')
    render=$(sed -n 's/^summary: .*render \([0-9.]*\) s,.*/\1/p' "$work/$name.log")
    if [ -z "$best_wall" ] || awk -v a="$wall" -v b="$best_wall" 'BEGIN { exit !(a < b) }'; then
      best_wall=$wall best_render=$render
    fi
  done
  echo "$best_wall $best_render"
}

ratio() { awk -v a="$1" -v b="$2" 'BEGIN { print a / b }'; }

echo "scene: $scene ${flags[*]}"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "mpirun: $(mpirun --version | head -n 1)"
printf '%-28s %8s %8s %10s %10s %s\n' "case" "wall s" "render s" "speedup" "(render)" "image"

read -r wall1 render1 <<<"$(run local "$strahl" render "$scene" "${flags[@]}")"
printf '%-28s %8.2f %8.2f %10s %10s %s\n' "1 process (no MPI)" "$wall1" "$render1" "1.00" "1.00" "reference"

for n in $ranks_list; do
  read -r wall render <<<"$(run "np$n" mpirun --oversubscribe --bind-to none -np "$n" \
    "$strahl" render "$scene" "${flags[@]}" --distributed)"
  if idiff -fail 0 -warn 0 "$work/local.exr" "$work/np$n.exr" >/dev/null 2>&1; then same="bit-identical"; else same="DIFFERS"; fi
  printf '%-28s %8.2f %8.2f %10.2f %10.2f %s\n' "mpirun -np $n ($((n - 1)) worker$( ((n > 2)) && echo s))" \
    "$wall" "$render" "$(ratio "$wall1" "$wall")" "$(ratio "$render1" "$render")" "$same"
  grep '^distributed:' "$work/np$n.log" | sed 's/^/    /'
done
