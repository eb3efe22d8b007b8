#!/usr/bin/env bash
# Builds the command-line program and runs it on the default example (an icosphere with two +1
# singularities at antipodal vertices), on a fresh Debian bookworm machine. Outputs go to out/, with a
# picture of the field, out/example.png (scripts/render_field.py).
# Usage: bash scripts/run_example.sh [MESH [SINGULARITIES]]   (default examples/data/sphere.off/.sing)
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
mesh="${1:-examples/data/sphere.off}"
sing="${2:-}"
if [ $# -lt 1 ]; then sing="examples/data/sphere.sing"; fi

bash scripts/install_dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "${JOBS:-2}" --target trivial_connections

mkdir -p out
sing_args=()
if [ -n "$sing" ]; then sing_args=(--singularities "$sing"); fi
./build/trivial_connections "$mesh" "${sing_args[@]}" --n 1 \
  --connection out/example.connection.txt --field out/example.field.txt \
  --vtk out/example.vtk --streamlines out/example.streamlines.vtk
# the picture: Debian's python3 (it has python3-numpy and python3-matplotlib; a python3 earlier on PATH may not)
/usr/bin/python3 scripts/render_field.py out/example.vtk --streamlines out/example.streamlines.vtk \
  -o out/example.png --view 20 50
echo
echo "Outputs:"
echo "  connection (one line 'i j x w' per interior edge): $root/out/example.connection.txt"
echo "  field      (one unit vector 'x y z' per face):     $root/out/example.field.txt"
echo "  viewers    (ParaView, MeshLab: mesh + field, streamlines): $root/out/example.vtk, $root/out/example.streamlines.vtk"
echo "  picture    (shaded mesh, streamlines, singularities): $root/out/example.png"
