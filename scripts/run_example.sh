#!/usr/bin/env bash
# Builds the command-line program and runs it on the default example, on a fresh Debian bookworm machine: a cross
# field (n = 4) with automatically placed singularities, aligned with the principal curvature directions, on
# CGAL's fandisk.off (from CGAL's data set, fetched by scripts/fetch_cgal_data.sh into .cgal-data/). Outputs go to
# out/, with the singularities used (out/example.sing) and a picture of the field, out/example.png
# (scripts/render_field.py).
# Usage: bash scripts/run_example.sh [MESH [SINGULARITIES]]
#   MESH alone: the same automatic, curvature-aligned cross field on MESH;
#   MESH SINGULARITIES: a vector field (n = 1) with the singularities of that file.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"

bash scripts/install_dependencies.sh
if [ $# -lt 1 ]; then
  bash scripts/fetch_cgal_data.sh
  mesh=".cgal-data/data/meshes/fandisk.off"
else
  mesh="$1"
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "${JOBS:-2}" --target trivial_connections

mkdir -p out
rm -f out/example.sing
if [ $# -ge 2 ]; then
  design=(--singularities "$2" --n 1)
else
  design=(--auto --n 4 --align-curvature --write-singularities out/example.sing)
fi
./build/trivial_connections "$mesh" "${design[@]}" \
  --connection out/example.connection.txt --field out/example.field.txt \
  --vtk out/example.vtk --streamlines out/example.streamlines.vtk --streamline-seeds 80
# the picture: Debian's python3 (it has python3-numpy and python3-matplotlib; a python3 earlier on PATH may not)
/usr/bin/python3 scripts/render_field.py out/example.vtk --streamlines out/example.streamlines.vtk \
  -o out/example.png --view 20 50
echo
echo "Outputs:"
echo "  connection (one line 'i j x w' per interior edge): $root/out/example.connection.txt"
echo "  field      (one unit vector 'x y z' per face):     $root/out/example.field.txt"
echo "  viewers    (ParaView, MeshLab: mesh + field, streamlines): $root/out/example.vtk, $root/out/example.streamlines.vtk"
echo "  picture    (shaded mesh, streamlines, singularities): $root/out/example.png"
if [ -f out/example.sing ]; then
  echo "  singularities used (the --singularities format; edit and run again): $root/out/example.sing"
fi
