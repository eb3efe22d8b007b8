#!/usr/bin/env bash
# Side by side with Directional (issue 37, item 5): the same feature pins (faces beside the sharp curves,
# feature_aligned_faces at 30 degrees, n = 4) for Directional's power field with hard constraints and for our
# program; our trivial connection with Directional's singularities vs with our --auto placement, unrefined
# (--auto --no-refine: the placement compares with Directional's power field; plain --auto refines further).
#
#   bash scripts/compare_directional.sh PEER_BINARY [BUILD_DIR] [MESH.off ...]
#
# PEER_BINARY: a small program built OUTSIDE the project (e.g. in /tmp/peers) against Directional's headers
# (github.com/avaxman/Directional; see benchmark/RESULTS.md, "Feature pins", for the commit and the calls:
# readOFF, PCFaceTangentBundle::init, power_field(..., weights -1 = hard, N = 4), power_to_raw, principal_matching),
# called as PEER_BINARY MESH.off PINS.txt SINGULARITIES_OUT 4: it reads the 'f x y z' pins and writes the field's
# singularities as 'v p/4' lines (our --singularities format). Nothing of Directional is in this repository.
# BUILD_DIR: a build with -DTRIVIAL_CONNECTIONS_BUILD_BENCHMARKS=ON (default /tmp/build_bench) holding the
# program and trivial_connections_feature_pins_benchmark (which writes the pins: --write-pins).
# Whole processes are timed by /usr/bin/time (wall seconds, maximum resident size; the median of TC_COMPARE_REPS
# runs, default 3). Prints a Markdown table.
set -euo pipefail
peer=${1:?usage: compare_directional.sh PEER_BINARY [BUILD_DIR] [MESH.off ...]}
build=${2:-/tmp/build_bench}
shift $(( $# >= 2 ? 2 : 1 ))
here=$(cd "$(dirname "$0")/.." && pwd)
data="$here/.cgal-data/data/meshes"
meshes=("$@")
[ ${#meshes[@]} -gt 0 ] || meshes=("$data/fandisk.off" "$data/fandisk_large.off" "$data/anchor_dense.off")
program="$build/trivial_connections"
pinner="$build/benchmark/trivial_connections_feature_pins_benchmark"
out=${TC_COMPARE_DIR:-/tmp/peers/runs}
mkdir -p "$out"

reps=${TC_COMPARE_REPS:-3}
timed() { # LOG CMD...: runs CMD $reps times, stdout+stderr to LOG; prints the median "seconds max_rss_MB"
  local log=$1; shift
  : > "$log.times"
  for _ in $(seq "$reps"); do
    /usr/bin/time -f '%e %M' -o "$log.time" "$@" > "$log" 2>&1
    cat "$log.time" >> "$log.times"
  done
  sort -n "$log.times" | awk '{t[NR] = $1; m[NR] = $2} END {h = int((NR + 1) / 2); printf "%.2f %.0f", t[h], m[h] / 1024}'
}
energy() { grep -o 'energy: [-+0-9.eE]*' "$1" | tail -1 | awk '{print $2}'; }

echo "| mesh | faces | pins | Directional: whole run, peak | its singularities | ours with its singularities: energy, whole run | ours --auto --no-refine: singularities, energy, whole run, peak | ratio of energies |"
echo "|---|---|---|---|---|---|---|---|"
for mesh in "${meshes[@]}"; do
  name=$(basename "$mesh" .off)
  pins="$out/$name.pins.txt"
  "$pinner" --write-pins "$mesh" "$pins" features > "$out/$name.pins.log"
  faces=$(awk 'NR==2 && $0 !~ /^#/ {print $2; exit} /^[0-9]/ && NR<=3 {print $2; exit}' "$mesh")
  npins=$(wc -l < "$pins")
  read -r t_peer m_peer <<< "$(timed "$out/$name.directional.log" "$peer" "$mesh" "$pins" "$out/$name.directional.sing" 4)"
  nsing=$(wc -l < "$out/$name.directional.sing")
  read -r t_with m_with <<< "$(timed "$out/$name.ours_with_directional.log" "$program" "$mesh" --n 4 \
    --constraints "$pins" --singularities "$out/$name.directional.sing" --write-singularities "$out/$name.ours_with_directional.sing")"
  e_with=$(energy "$out/$name.ours_with_directional.log")
  read -r t_auto m_auto <<< "$(timed "$out/$name.ours_auto.log" "$program" "$mesh" --n 4 --auto --no-refine \
    --constraints "$pins" --write-singularities "$out/$name.ours_auto.sing")"
  e_auto=$(energy "$out/$name.ours_auto.log")
  nauto=$(grep -vc "^#" "$out/$name.ours_auto.sing" || true)
  ratio=$(awk -v a="$e_auto" -v b="$e_with" 'BEGIN{printf "%.3f", a / b}')
  echo "| $name | $faces | $npins | ${t_peer} s, ${m_peer} MB | $nsing | $e_with, ${t_with} s | $nauto, $e_auto, ${t_auto} s, ${m_auto} MB | $ratio |"
done
