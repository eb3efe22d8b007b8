#!/usr/bin/env bash
# The program's viewer outputs (--vtk, --ply, --singularity-points) on the example sphere with n = 4: each
# written, with the mesh's counts and the N direction arrays; with an output that cannot be written, no file
# is left at all. Used by ctest.
# Usage: cli_viewer.sh PROGRAM OUT_DIR SPHERE_OFF SINGULARITIES
set -euo pipefail
cli="$1" out="$2" mesh="$3" sing="$4"
rm -rf "$out"
mkdir -p "$out"
"$cli" "$mesh" --singularities "$sing" --n 4 --connection "$out/c.txt" --field "$out/f.txt" \
  --vtk "$out/field.vtk" --ply "$out/field.ply" --singularity-points "$out/sing.txt" \
  --streamlines "$out/lines.vtk" --streamline-seeds 20 > "$out/report.txt"
fail() { echo "cli_viewer.sh: $*" >&2; exit 1; }
faces=$(grep -cv '^#' "$out/f.txt")
[ "$(head -1 "$out/field.vtk")" = "# vtk DataFile Version 3.0" ] || fail "not a legacy VTK file"
grep -q "^POLYGONS $faces $((4 * faces))$" "$out/field.vtk" || fail "VTK: not $faces triangles"
[ "$(grep -c '^VECTORS direction_[0-3] double$' "$out/field.vtk")" = 4 ] || fail "VTK: not 4 direction arrays"
grep -q "^SCALARS singularity_index double 1$" "$out/field.vtk" || fail "VTK: no singularity_index"
[ "$(head -1 "$out/field.ply")" = "ply" ] || fail "not a PLY file"
grep -q "^element face $faces$" "$out/field.ply" || fail "PLY: not $faces faces"
[ "$(grep -c '^property double d[0-3]_[xyz]$' "$out/field.ply")" = 12 ] || fail "PLY: not 4 directions"
[ "$(grep -cv '^#' "$out/sing.txt")" = "$(grep -cvE '^[[:space:]]*(#|$)' "$sing")" ] || fail "points: not one per singularity"
grep -qE "^LINES (2[0-9]|[3-9][0-9]) [0-9]+$" "$out/lines.vtk" || fail "streamlines: not 20-99 polylines (20 seeds, two lines each for n = 4)"
echo "ok: VTK, PLY, point and streamline files written ($faces faces)"
# an output that cannot be written: nothing at all is left
rm -f "$out"/c2.txt "$out"/f2.txt
if "$cli" "$mesh" --singularities "$sing" --n 4 --connection "$out/c2.txt" --field "$out/f2.txt" \
     --vtk "$out/no_such_dir/field.vtk" > /dev/null 2> "$out/error.txt"; then
  fail "exit status 0 with an unwritable --vtk"
fi
[ ! -e "$out/c2.txt" ] && [ ! -e "$out/f2.txt" ] || fail "files left behind after a failed write"
echo "ok: $(cat "$out/error.txt")"
