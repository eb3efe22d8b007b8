#!/usr/bin/env bash
# Side by side with Crane's TCODS (the reference code of "Trivial Connections on Discrete Surfaces", SGP 2010) for
# the section "Against the peers: Crane's TCODS" of benchmark/RESULTS.md: whole processes with the same
# singularities, n = 1, wall time, runs of the two programs interleaved, medians.
#
#   bash scripts/compare_tcods.sh TCODS_BINARY [PROGRAM] [MESH.off SINGULARITIES ...]
#
# TCODS_BINARY: TCODS built OUTSIDE the project (e.g. the public copy github.com/n-taka/tcods, TCODS v0.1 with build
# fixes, g++ -O3 -DNDEBUG against SuiteSparse: it factors its cycle matrix with SuiteSparseQR), called as users do:
# TCODS_BINARY PROBLEM, where PROBLEM holds 'in MESH.obj', 'out FIELD.eobj' and one 'vertex I K' line per
# singularity (0-based vertex, index K); it reads the OBJ mesh, solves, propagates a field and writes the mesh with
# one vector per face. The OBJ is written from the OFF file here (the same vertices and faces, in the same order).
# Nothing of TCODS is in this repository.
# PROGRAM: our command-line program built Release (default build-bench-cholmod/trivial_connections, else
# build-bench/trivial_connections), run as PROGRAM MESH.off --singularities S --n 1 --connection C --field F.
# Meshes: by default CGAL's bunny00 (genus 0: +1 at vertices 24276 and 34482) and refined_elephant (genus 3: -1 at
# 41605, 41381, 24533 and 35695; TCODS leaves the generators' integers at 0, ours chooses them); or pairs of an OFF
# file and a singularity file in our format ('v k' lines, k an integer: n = 1).
# Each program runs TC_COMPARE_REPS times (default 9), interleaved; the median of the wall times (the shell's
# clock, to the millisecond) is reported. Outputs and logs go to TC_COMPARE_DIR (default /tmp/peers/runs_tcods).
# Prints a Markdown table.
set -euo pipefail
peer=${1:?usage: compare_tcods.sh TCODS_BINARY [PROGRAM] [MESH.off SINGULARITIES ...]}
here=$(cd "$(dirname "$0")/.." && pwd)
program=${2:-}
if [ -z "$program" ]; then
  program="$here/build-bench-cholmod/trivial_connections"
  [ -x "$program" ] || program="$here/build-bench/trivial_connections"
fi
shift $(( $# >= 2 ? 2 : 1 ))
out=${TC_COMPARE_DIR:-/tmp/peers/runs_tcods}
reps=${TC_COMPARE_REPS:-9}
mkdir -p "$out"
data="$here/.cgal-data/data/meshes"
pairs=("$@")
if [ ${#pairs[@]} -eq 0 ]; then
  printf '24276 1\n34482 1\n' > "$out/bunny00.sing"
  printf '41605 -1\n41381 -1\n24533 -1\n35695 -1\n' > "$out/refined_elephant.sing"
  pairs=("$data/bunny00.off" "$out/bunny00.sing" "$data/refined_elephant.off" "$out/refined_elephant.sing")
fi
[ $(( ${#pairs[@]} % 2 )) -eq 0 ] || { echo "compare_tcods.sh: meshes and singularity files go in pairs" >&2; exit 2; }

off_to_obj() { # OFF OBJ: the same vertices and faces, in order (comments and blank lines of the OFF skipped)
  awk 'function next_line() { while ((getline line < f) > 0) { sub(/#.*/, "", line); if (line ~ /[^ \t\r]/) return 1 } return 0 }
       BEGIN { f = ARGV[1]; ARGV[1] = ""; next_line(); n = split(line, h)
               if (h[1] ~ /^OFF/) { if (n == 1) { next_line(); n = split(line, h); nv = h[1]; nf = h[2] } else { nv = h[2]; nf = h[3] } }
               for (i = 0; i < nv; i++) { next_line(); split(line, p); print "v", p[1], p[2], p[3] }
               for (i = 0; i < nf; i++) { next_line(); k = split(line, p); s = "f"; for (j = 2; j <= p[1] + 1; j++) s = s " " p[j] + 1; print s } }' "$1" > "$2"
}
now() { echo "$EPOCHREALTIME"; }
median() { sort -n | awk '{ t[NR] = $1 } END { printf "%.3f", t[int((NR + 1) / 2)] }'; }

echo "| mesh | faces | TCODS | trivial_connections | TCODS / ours |"
echo "|---|---:|---:|---:|---:|"
for ((i = 0; i < ${#pairs[@]}; i += 2)); do
  mesh=${pairs[i]}; sing=${pairs[i + 1]}
  name=$(basename "$mesh" .off)
  obj="$out/$name.obj"
  off_to_obj "$mesh" "$obj"
  faces=$(grep -c '^f ' "$obj")
  {
    echo "in $obj"
    echo "out $out/$name.eobj"
    grep -v '^#' "$sing" | awk 'NF >= 2 { print "vertex", $1, $2 }'
  } > "$out/$name.problem"
  : > "$out/$name.tcods.times"; : > "$out/$name.ours.times"
  for _ in $(seq "$reps"); do
    b=$(now); "$peer" "$out/$name.problem" > "$out/$name.tcods.log" 2>&1; e=$(now)
    awk -v a="$b" -v b="$e" 'BEGIN { print b - a }' >> "$out/$name.tcods.times"
    b=$(now)
    "$program" "$mesh" --singularities "$sing" --n 1 --connection "$out/$name.connection.txt" \
      --field "$out/$name.field.txt" > "$out/$name.ours.log" 2>&1
    e=$(now)
    awk -v a="$b" -v b="$e" 'BEGIN { print b - a }' >> "$out/$name.ours.times"
  done
  t_peer=$(median < "$out/$name.tcods.times"); t_ours=$(median < "$out/$name.ours.times")
  ratio=$(awk -v a="$t_peer" -v b="$t_ours" 'BEGIN { printf "%.1f", a / b }')
  k=$(awk -v f="$faces" 'BEGIN { if (f >= 10000) printf "%.0fk", f / 1000; else printf "%.1fk", f / 1000 }')
  echo "| $name | $k | ${t_peer} s | ${t_ours} s | $ratio |"
done
