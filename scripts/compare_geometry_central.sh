#!/usr/bin/env bash
# Side by side with geometry-central: our automatic singularity placement (--auto: the singularities of the
# globally smoothest N-direction field, Knoeppel et al. 2013, then the trivial connection with exactly them;
# refined, the program's default, and with --no-refine) against geometry-central's smoothest face direction field and its vertex indices.
# Whole processes (reading the mesh included) are timed; our trivial connection is also solved with
# geometry-central's singularities, so that the energies compare where the singularities are, not the solvers.
#
#   bash scripts/compare_geometry_central.sh PEER_BINARY [PROGRAM] [MESH.off ...]
#
# PEER_BINARY: a small program built OUTSIDE the project (e.g. in /tmp/peers/gc) against geometry-central
# (github.com/nmwsharp/geometry-central, with its deps/happly submodule; CMake Release -O3 -DNDEBUG,
# GC_EIGEN_LOCATION=/usr/include/eigen3 so that nothing is downloaded; SuiteSparse is used when found, as
# geometry-central does by default), called as PEER_BINARY MESH.off N SINGULARITIES_OUT: readManifoldSurfaceMesh,
# computeSmoothestFaceDirectionField(geometry, N) (inverse power iteration, 50 sparse LU solves),
# computeVertexIndex(geometry, field, N) (the face-field counterpart of computeFaceIndex), and it writes the
# singular interior vertices as 'v p/N' lines (our --singularities format, 0-based vertex index in file order).
# Nothing of geometry-central is in this repository.
# PROGRAM: our command-line program built Release (default /tmp/b2/trivial_connections).
# Our two command lines are PROGRAM MESH --n N followed by $TC_OURS_SMOOTHEST (default "--auto --no-refine": the
# smoothest field's singularities, no refinement, what compares with geometry-central's) and by $TC_OURS_REFINED
# (default "--auto": refined to a local minimum with cancellations, the same as --auto --refine --cancel-pairs).
# A program older than --no-refine needs TC_OURS_SMOOTHEST=--auto TC_OURS_REFINED="--auto --refine --cancel-pairs".
# N takes the values of TC_COMPARE_N (default 4; e.g. TC_COMPARE_N="1 2 4").
# Whole processes are timed by the shell's clock (wall seconds, to the millisecond) and /usr/bin/time (maximum resident
# size); the median of TC_COMPARE_REPS runs, default 3; the peak is that of the median run. Outputs and logs go to TC_COMPARE_DIR (default
# /tmp/peers/runs_gc). A run that fails is reported in its cell instead of stopping the script.
# Prints a Markdown table.
set -euo pipefail
peer=${1:?usage: compare_geometry_central.sh PEER_BINARY [PROGRAM] [MESH.off ...]}
program=${2:-/tmp/b2/trivial_connections}
shift $(( $# >= 2 ? 2 : 1 ))
here=$(cd "$(dirname "$0")/.." && pwd)
data="$here/.cgal-data/data/meshes"
meshes=("$@")
[ ${#meshes[@]} -gt 0 ] || meshes=("$data/bunny00.off" "$data/armadillo.off" "$data/refined_elephant.off" \
  "$data/femur.off" "$data/elephant.off" "$data/fandisk.off")
read -r -a ours_smoothest <<< "${TC_OURS_SMOOTHEST:---auto --no-refine}"
read -r -a ours_refined <<< "${TC_OURS_REFINED:---auto}"
out=${TC_COMPARE_DIR:-/tmp/peers/runs_gc}
mkdir -p "$out"

reps=${TC_COMPARE_REPS:-3}
timed() { # LOG CMD...: runs CMD $reps times, stdout+stderr to LOG; prints the median "seconds max_rss_MB",
          # or "failed <exit status>" (and stops repeating) when CMD fails
  local log=$1; shift
  : > "$log.times"
  for _ in $(seq "$reps"); do
    local status=0 begin end
    begin=$EPOCHREALTIME # microseconds: /usr/bin/time's %e has 10 ms, a tenth of a small mesh's run
    /usr/bin/time -f '%M' -o "$log.time" "$@" > "$log" 2>&1 || status=$?
    end=$EPOCHREALTIME
    if [ "$status" -ne 0 ]; then echo "failed $status"; return 0; fi
    echo "$(awk -v a="$begin" -v b="$end" 'BEGIN{printf "%.4f", b - a}') $(tail -1 "$log.time")" >> "$log.times"
  done
  sort -n "$log.times" | awk '{t[NR] = $1; m[NR] = $2} END {h = int((NR + 1) / 2); printf "%.3f %.0f", t[h], m[h] / 1024}'
}
energy() { grep -o '^energy: [-+0-9.eE]*' "$1" | tail -1 | awk '{print $2}' || true; }
count() { # LOG: the number of singularities our program used ('singularities: S; ...'), else the refinement's
          # 'S0 -> S1 singularities' or the placement's '...; S singularities'
  local s
  s=$(grep -o '^singularities: [0-9]*' "$1" | tail -1 | awk '{print $2}' || true)
  [ -n "$s" ] || s=$(grep '^refinement:' "$1" | grep -o '[0-9]* singularities' | tail -1 | awk '{print $1}' || true)
  [ -n "$s" ] || s=$(grep '^placement:' "$1" | grep -o '[0-9]* singularities' | tail -1 | awk '{print $1}' || true)
  echo "${s:-?}"
}
why() { # LOG: the last line of a failed run's output, for the table
  tail -1 "$1" 2>/dev/null | tr '|' '/' | cut -c1-120 || true
}

echo "| mesh | faces | N | geometry-central: whole run, peak | its singularities | ours \`${ours_smoothest[*]}\`: singularities, energy, whole run | ours \`${ours_refined[*]}\`: singularities, energy, whole run, peak | ratio: ours refined / geometry-central (whole runs) | ours with geometry-central's singularities: energy |"
echo "|---|---|---|---|---|---|---|---|---|"
for mesh in "${meshes[@]}"; do
  name=$(basename "$mesh" .off)
  for n in ${TC_COMPARE_N:-4}; do
    tag="$out/$name.n$n"
    files=(--connection "$tag.connection.txt" --field "$tag.field.txt")
    # geometry-central
    read -r t_peer m_peer <<< "$(timed "$tag.gc.log" "$peer" "$mesh" "$n" "$tag.gc.sing")"
    if [ "$t_peer" = failed ]; then
      peer_cell="failed (exit $m_peer: $(why "$tag.gc.log"))"; nsing_peer="-"
    else
      peer_cell="${t_peer} s, ${m_peer} MB"; nsing_peer=$(grep -vc '^#' "$tag.gc.sing" || true)
    fi
    # ours, the smoothest field's singularities
    read -r t_s m_s <<< "$(timed "$tag.smoothest.log" "$program" "$mesh" --n "$n" "${ours_smoothest[@]}" "${files[@]}")"
    if [ "$t_s" = failed ]; then
      s_cell="failed (exit $m_s: $(why "$tag.smoothest.log"))"
    else
      s_cell="$(count "$tag.smoothest.log"), $(energy "$tag.smoothest.log"), ${t_s} s"
    fi
    # ours, refined
    read -r t_r m_r <<< "$(timed "$tag.refined.log" "$program" "$mesh" --n "$n" "${ours_refined[@]}" "${files[@]}")"
    if [ "$t_r" = failed ]; then
      r_cell="failed (exit $m_r: $(why "$tag.refined.log"))"
    else
      r_cell="$(count "$tag.refined.log"), $(energy "$tag.refined.log"), ${t_r} s, ${m_r} MB"
    fi
    # the ratio of whole runs
    ratio="-"
    if [ "$t_peer" != failed ] && [ "$t_r" != failed ]; then
      ratio=$(awk -v a="$t_r" -v b="$t_peer" 'BEGIN{if (b > 0) printf "%.2f", a / b; else print "-"}')
    fi
    # ours with geometry-central's singularities (one run: only its energy is reported)
    with_cell="-"
    if [ "$t_peer" != failed ]; then
      status=0
      "$program" "$mesh" --n "$n" --singularities "$tag.gc.sing" "${files[@]}" > "$tag.with_gc.log" 2>&1 || status=$?
      if [ "$status" -ne 0 ]; then
        with_cell="failed (exit $status: $(why "$tag.with_gc.log"))"
      else
        with_cell=$(energy "$tag.with_gc.log")
      fi
    fi
    faces=$(grep -ho '^mesh: .* [0-9]* faces' "$tag.refined.log" "$tag.smoothest.log" 2>/dev/null | head -1 | awk '{print $(NF-1)}' || true)
    [ -n "$faces" ] || faces=$(grep -o 'faces: [0-9]*' "$tag.gc.log" 2>/dev/null | head -1 | awk '{print $2}' || true)
    echo "| $name | ${faces:-?} | $n | $peer_cell | $nsing_peer | $s_cell | $r_cell | $ratio | $with_cell |"
  done
done
