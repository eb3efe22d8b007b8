#!/usr/bin/env bash
# Makes the figures of the user manual from real meshes (CGAL's data set, scripts/fetch_cgal_data.sh) and
# the default example: runs the program, then renders with scripts/render_field.py. Used by the CMake
# target `doc` (doc_figures); by hand:
#   bash scripts/make_figures.sh PROGRAM PYTHON CGAL_MESH_DIR OUT_DIR
# PYTHON must have numpy and matplotlib (Debian: /usr/bin/python3). Figures are written to OUT_DIR; the
# intermediate files go to OUT_DIR/work.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
program="$1" python="$2" meshes="$3" out="$4"
data="$root/test/Trivial_connections/data"
for f in cow.off elk.off pig.off fandisk.off bunny00.off; do
  [ -f "$meshes/$f" ] || { echo "make_figures.sh: $meshes/$f is missing (bash scripts/fetch_cgal_data.sh)" >&2; exit 1; }
done
mkdir -p "$out/work"
work="$out/work"

# figure NAME MESH RENDER_ARGS... -- PROGRAM_ARGS...: one picture
figure() {
  local name="$1" mesh="$2"
  shift 2
  local render=()
  while [ "$1" != "--" ]; do render+=("$1"); shift; done
  shift
  "$program" "$mesh" "$@" --connection "$work/$name.connection.txt" --field "$work/$name.field.txt" \
    --vtk "$work/$name.vtk" --streamlines "$work/$name.streamlines.vtk" > "$work/$name.report.txt"
  "$python" "$root/scripts/render_field.py" "$work/$name.vtk" "${render[@]}" -o "$out/$name.png" > /dev/null
  echo "make_figures.sh: $out/$name.png"
}

# introduction: a vector field on the cow with two +1 singularities, as streamlines
figure cow_vector "$meshes/cow.off" --streamlines "$work/cow_vector.streamlines.vtk" --size 900 600 -- \
  --singularities "$data/cow.sing" --streamline-seeds 300
# the package picture: the same, small
"$python" "$root/scripts/render_field.py" "$work/cow_vector.vtk" --streamlines "$work/cow_vector.streamlines.vtk" \
  --size 240 160 -o "$out/package_picture.png" > /dev/null
# a cross field (n = 4) with eight +1/4 singularities, as crosses
figure cow_cross "$meshes/cow.off" --glyphs 1500 --size 900 600 -- --singularities "$data/cow_quarters.sing" --n 4
# genus 1 without singularities: the free integers of the two generators
figure elk_vector "$meshes/elk.off" --streamlines "$work/elk_vector.streamlines.vtk" --size 900 600 -- \
  --streamline-seeds 100
# boundary alignment: a cross field following the seven holes of the pig
figure pig_aligned "$meshes/pig.off" --glyphs 1500 --size 900 600 -- --n 4 --align-boundary
# feature alignment: a cross field on fandisk pinned along its sharp curves, singularities placed with the pins
figure fandisk_feature_field "$meshes/fandisk.off" --streamlines "$work/fandisk_feature_field.streamlines.vtk" \
  --features "$work/fandisk_feature_field.features.vtk" --view 20 50 --size 900 600 -- \
  --auto --n 4 --align-features --feature-lines "$work/fandisk_feature_field.features.vtk" --streamline-seeds 60
# quad meshes (--quad-mesh): fandisk with its sharp edges on iso-lines, and an organic mesh, drawn over the surface
figure fandisk_quads "$meshes/fandisk.off" --quads "$work/fandisk_quads.obj" --features "$work/fandisk_quads.features.vtk" \
  --view 20 50 --size 900 600 -- --auto --n 4 --align-features --feature-lines "$work/fandisk_quads.features.vtk" \
  --quad-mesh "$work/fandisk_quads.obj" --target-faces 2000 --streamline-seeds 1
figure bunny00_quads "$meshes/bunny00.off" --quads "$work/bunny00_quads.obj" --view 0 10 --size 900 700 -- \
  --auto --n 4 --quad-mesh "$work/bunny00_quads.obj" --target-faces 2000 --streamline-seeds 1
