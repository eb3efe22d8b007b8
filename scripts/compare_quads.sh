#!/usr/bin/env bash
# Side by side of the quad meshes (issue 43): a peer's seamless integration and mesher on OUR cross field, and
# our program's --quad-mesh, with the same quad size H, every quad mesh measured by scripts/quad_quality.py.
#
#   bash scripts/compare_quads.sh PEER_BINARY [BUILD_DIR] [MESH.off ...]
#
# PEER_BINARY: a small program built OUTSIDE the project (e.g. in /tmp/peers) against a peer's headers, called as
#   PEER_BINARY MESH.off FIELD.txt SINGULARITIES.txt H OUT.obj
# It reads our field (--field: one line 'x y z' per face, one of the 4 directions) and singularities
# (--write-singularities: lines 'v k'), builds its own raw field from the 4 directions (its matching and cuts do
# the rest), integrates with one unit of the parameters per length H along the field, meshes the integer
# isolines if it can, and prints 'key: value' lines, at least integration_seconds (the integration alone, no
# I/O), folded_triangles (negative (u, v) area), meshed (1 if OUT.obj was written). Nothing of a peer is in this
# repository. The peer measured so far: Directional (github.com/avaxman/Directional, commit 2573873, header-only,
# g++ -std=c++20 -O2 -DNDEBUG -DUSE_GMP_ENABLED, Eigen 3.4, GMP), a self-written program calling readOFF,
# PCFaceTangentBundle::init, CartesianField::init(RAW_FIELD, 4) + set_intrinsic_field (d, Jd, -d, -Jd per face),
# principal_matching, setup_integration, integrate (integralSeamless, roundSeams = false, lengthRatio = H / the
# bounding box diagonal: one unit per H along unit vectors), then setup_mesher and mesher (timed apart). libigl's
# MIQ (igl/copyleft/comiso/miq.h) was removed from libigl in 2024 and needs CoMISo: not measured.
# BUILD_DIR: holds trivial_connections (default build/ of this checkout). When it has --quad-mesh, our program is
# run once more with --quad-mesh and --quad-size H and timed as a whole process (field and quads); otherwise
# the table says so. MESH.off: default CGAL's fandisk and bunny00; meshes named in TC_QUAD_FEATURES (default
# "fandisk") get --align-features.
# H: TC_QUAD_SIZE if set, else sqrt(area / TC_QUAD_TARGET) per mesh (default 3000 quads).
# Runs TC_COMPARE_REPS times (default 1: the peer's integration can take minutes) and keeps the median time.
# The peer is stopped after TC_PEER_TIMEOUT seconds (default 1200; its mesher can run that long), its integration
# results kept when it printed them. Outputs in TC_COMPARE_DIR (default /tmp/peers/quads). Prints a Markdown table.
set -euo pipefail
peer=${1:?usage: compare_quads.sh PEER_BINARY [BUILD_DIR] [MESH.off ...]}
here=$(cd "$(dirname "$0")/.." && pwd)
build=${2:-$here/build}
shift $(( $# >= 2 ? 2 : 1 ))
data="$here/.cgal-data/data/meshes"
meshes=("$@")
[ ${#meshes[@]} -gt 0 ] || meshes=("$data/fandisk.off" "$data/bunny00.off")
program="$build/trivial_connections"
py=${TC_PYTHON:-/usr/bin/python3}
quality="$here/scripts/quad_quality.py"
out=${TC_COMPARE_DIR:-/tmp/peers/quads}
reps=${TC_COMPARE_REPS:-1}
peer_timeout=${TC_PEER_TIMEOUT:-1200}
features=" ${TC_QUAD_FEATURES:-fandisk} "
mkdir -p "$out"
[ -x "$program" ] || { echo "compare_quads.sh: no program at $program (build the target trivial_connections)" >&2; exit 1; }
[ -x "$peer" ] || { echo "compare_quads.sh: no peer program at $peer" >&2; exit 1; }
has_quads=0
help=$("$program" --help 2>&1 || true) # captured whole: grep -q on a pipe could cut the program short (pipefail)
[[ "$help" == *--quad-mesh* ]] && has_quads=1

median() { awk NF | sort -g | awk '{t[NR] = $1} END {if (NR) print t[int((NR + 1) / 2)]; else print "?"}'; }
value() { grep -m1 "^$2: " "$1" | cut -d' ' -f2 || true; } # LOG KEY: a 'key: value' line's value

# quality cells from quad_quality.py's JSON: quads | non-quads | valence errors | flipped | angle | area | Hausdorff/H
cells() {
  "$py" - "$1" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
c, v, d, h = r["counts"], r["valence"], r["distortion"], r["hausdorff"]
dist = (f"{d['angle_deviation_degrees_mean']:.1f} / {d['angle_deviation_degrees_max']:.1f}",
        f"{d['area_over_h2_mean']:.2f} ± {d['area_over_h2_std']:.2f}") if d else ("-", "-")
topo = r["edges"]
extra = []
if topo["open"] or topo["non_manifold"]:
    extra.append(f"{topo['open']} open, {topo['non_manifold']} non-manifold edges")
if v.get("singularities_unmatched"):
    extra.append(f"{v['singularities_unmatched']} singularities not at a quad vertex")
print(" | ".join([str(c["quads"]), str(c["non_quads"]), str(v.get("errors", "?")) + (f" ({'; '.join(extra)})" if extra else ""),
                  str(r["flipped"]["quads"]), *dist, f"{h['max_over_h']:.3f}"]))
EOF
}

echo "| mesh | faces | H | who | time | folded triangles | quads | non-quads | valence errors | flipped quads | angle deviation, mean / max (degrees) | area / H² | Hausdorff / H |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for mesh in "${meshes[@]}"; do
  name=$(basename "$mesh" .off)
  extra=()
  [[ "$features" == *" $name "* ]] && extra=(--align-features)
  faces=$(awk '/^[ \t]*#/ || NF == 0 {next} n == 1 {print $2; exit} {n++}' "$mesh")
  if [ -n "${TC_QUAD_SIZE:-}" ]; then
    H=$TC_QUAD_SIZE
  else
    H=$("$py" -c '
import sys, numpy as np
sys.path.insert(0, sys.argv[1])
from quad_quality import read_mesh, fans
p, f = read_mesh(sys.argv[2]); t, _ = fans(f)
a = 0.5 * np.linalg.norm(np.cross(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]]), axis=1).sum()
print("%.6g" % (a / float(sys.argv[3])) ** 0.5)' "$here/scripts" "$mesh" "${TC_QUAD_TARGET:-3000}")
  fi
  # our field and singularities, the peer's input
  "$program" "$mesh" --auto --n 4 "${extra[@]}" --field "$out/$name.field.txt" \
    --write-singularities "$out/$name.sing" --connection "$out/$name.connection.txt" > "$out/$name.field.log" 2>&1
  # the peer
  : > "$out/$name.peer.times"
  for _ in $(seq "$reps"); do
    rm -f "$out/$name.peer.obj"
    status=0
    timeout "$peer_timeout" "$peer" "$mesh" "$out/$name.field.txt" "$out/$name.sing" "$H" "$out/$name.peer.obj" \
      > "$out/$name.peer.log" 2>&1 || status=$?
    value "$out/$name.peer.log" integration_seconds >> "$out/$name.peer.times"
  done
  t_peer=$(median < "$out/$name.peer.times")
  t_mesher=$(value "$out/$name.peer.log" mesher_seconds)
  folded=$(value "$out/$name.peer.log" folded_triangles)
  time_cell="integration ${t_peer} s${t_mesher:+ (mesher ${t_mesher} s)}"
  if [ "$(value "$out/$name.peer.log" meshed)" = 1 ] && [ -s "$out/$name.peer.obj" ]; then
    "$py" "$quality" "$mesh" "$out/$name.peer.obj" --singularities "$out/$name.sing" --quad-size "$H" --json \
      > "$out/$name.peer.quality.json"
    echo "| $name | $faces | $H | peer | $time_cell | ${folded:-?} | $(cells "$out/$name.peer.quality.json") |"
  else
    why="its mesher failed"
    [ "$status" = 124 ] && why="stopped after ${peer_timeout} s"
    [ "$status" != 0 ] && [ "$status" != 124 ] && why="exit status $status"
    echo "| $name | $faces | $H | peer | $time_cell | ${folded:-?} | no quad mesh ($why: see $out/$name.peer.log) | | | | | | |"
  fi
  # ours: the whole process, field and quads
  if [ $has_quads = 1 ]; then
    : > "$out/$name.ours.times"
    for _ in $(seq "$reps"); do
      /usr/bin/time -f '%e' -o "$out/$name.ours.time" "$program" "$mesh" --auto --n 4 "${extra[@]}" \
        --quad-mesh "$out/$name.ours.obj" --quad-size "$H" --write-singularities "$out/$name.ours.sing" \
        --field "$out/$name.ours.field.txt" --connection "$out/$name.ours.connection.txt" > "$out/$name.ours.log" 2>&1 || true
      tail -1 "$out/$name.ours.time" >> "$out/$name.ours.times"
    done
    t_ours=$(median < "$out/$name.ours.times")
    ofolded=$(grep -o 'folded triangles [0-9]*' "$out/$name.ours.log" | head -1 | awk '{print $3}' || true)
    if [ -s "$out/$name.ours.obj" ]; then
      "$py" "$quality" "$mesh" "$out/$name.ours.obj" --singularities "$out/$name.ours.sing" --quad-size "$H" --json \
        > "$out/$name.ours.quality.json"
      echo "| $name | $faces | $H | ours | whole run ${t_ours} s | ${ofolded:-?} | $(cells "$out/$name.ours.quality.json") |"
    else
      echo "| $name | $faces | $H | ours | whole run ${t_ours} s | ${ofolded:-?} | no quad mesh: $(tail -1 "$out/$name.ours.log") | | | | | | |"
    fi
  else
    echo "| $name | $faces | $H | ours | the program has no --quad-mesh yet | | | | | | | | |"
  fi
done
