#!/usr/bin/env bash
# Runs the command-line program on a mesh, then the independent checker on what it wrote.
# Fails (non-zero) when either fails or an output file is missing. Used by ctest (CMakeLists.txt).
# Usage: cli_check.sh --cli PROGRAM --checker check_connection.py --out DIR --mesh MESH
#                     [--python PY] [--singularities FILE|none] [--n N] [--weights hodge|unit]
#                     [--boundary-indices FILE]  (then every loop of the file must be reported prescribed)
#                     [--constraints FILE] [--align-boundary] [--guidance FILE] [--guidance-weight MU]
#                     (then check_constraints.py checks the targets, the guides and the optimality; the checker
#                     runs with --no-optimality)
#                     [--auto] [--no-refine] [--align-curvature] [--refine]  (automatic placement, refined unless
#                     --no-refine: the program writes the singularities it used with --write-singularities, and the
#                     checker checks against them; with the curvature guidance the checker runs with --no-optimality)
set -euo pipefail
cli="" checker="" python="" out="" mesh="" sing="none" n=1 weights=hodge boundary="" constraints="" align="" guidance="" guidance_weight=1
design=()
guided_by_curvature=0
while [ $# -gt 0 ]; do
  case "$1" in
    --cli) cli="$2"; shift 2 ;;
    --checker) checker="$2"; shift 2 ;;
    --python) python="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --mesh) mesh="$2"; shift 2 ;;
    --singularities) sing="$2"; shift 2 ;;
    --n) n="$2"; shift 2 ;;
    --weights) weights="$2"; shift 2 ;;
    --boundary-indices) boundary="$2"; shift 2 ;;
    --constraints) constraints="$2"; shift 2 ;;
    --align-boundary) align="--align-boundary"; shift ;;
    --guidance) guidance="$2"; shift 2 ;;
    --guidance-weight) guidance_weight="$2"; shift 2 ;;
    --auto|--no-refine|--align-curvature|--refine) design+=("$1"); shift ;;
    *) echo "cli_check.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
for var in cli checker out mesh; do
  if [ -z "${!var}" ]; then echo "cli_check.sh: --$var is required" >&2; exit 2; fi
done
if [ ! -f "$mesh" ]; then
  echo "cli_check.sh: mesh not found: $mesh (CGAL meshes: bash scripts/fetch_cgal_data.sh)" >&2
  exit 1
fi
if [ -z "$python" ]; then
  # the checker needs numpy; the python3 on PATH may lack it while Debian's has python3-numpy
  for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null 2>&1 && "$p" -c 'import numpy' 2>/dev/null; then python="$p"; break; fi
  done
  if [ -z "$python" ]; then echo "cli_check.sh: no python3 with numpy found" >&2; exit 1; fi
fi

mkdir -p "$out"
conn="$out/connection.txt"
field="$out/field.txt"
rm -f "$conn" "$field"

sing_args=()
if [ "$sing" != "none" ] && [ -n "$sing" ]; then sing_args=(--singularities "$sing"); fi

boundary_args=()
if [ -n "$boundary" ]; then boundary_args=(--boundary-indices "$boundary"); fi

constraint_args=()
if [ -n "$constraints" ]; then constraint_args=(--constraints "$constraints"); fi
if [ -n "$align" ]; then constraint_args+=("$align"); fi
if [ -n "$guidance" ]; then constraint_args+=(--guidance "$guidance" --guidance-weight "$guidance_weight"); fi

if [ ${#design[@]} -gt 0 ]; then
  rm -f "$out/used.sing"
  design+=(--write-singularities "$out/used.sing")
fi
echo "+ $cli $mesh ${sing_args[*]} ${boundary_args[*]} ${constraint_args[*]} ${design[*]} --n $n --weights $weights --connection $conn --field $field"
"$cli" "$mesh" "${sing_args[@]}" "${boundary_args[@]}" "${constraint_args[@]}" "${design[@]}" --n "$n" --weights "$weights" \
  --connection "$conn" --field "$field" | tee "$out/report.txt"
if [ ${#design[@]} -gt 0 ]; then
  # the singularities actually used; kept file singularities must be among them
  if [ ! -f "$out/used.sing" ]; then echo "cli_check.sh: --write-singularities wrote nothing" >&2; exit 1; fi
  sing_args=(--singularities "$out/used.sing")
  for d in "${design[@]}"; do
    if [ "$d" = "--align-curvature" ]; then guided_by_curvature=1; fi
  done
fi

if [ -n "$boundary" ]; then
  given=$(grep -cvE '^[[:space:]]*(#|$)' "$boundary")
  reported=$(grep -cE 'boundary, index .* \(prescribed\)' "$out/report.txt" || true)
  if [ "$given" != "$reported" ]; then
    echo "cli_check.sh: $given boundary loops given, $reported reported prescribed" >&2; exit 1
  fi
fi

for f in "$conn" "$field"; do
  if [ ! -s "$f" ]; then echo "cli_check.sh: the program exited 0 but did not write $f" >&2; exit 1; fi
done

optimality_args=()
if [ ${#constraint_args[@]} -gt 0 ] || [ "$guided_by_curvature" = 1 ]; then optimality_args=(--no-optimality); fi
echo "+ $python $checker $mesh --connection $conn --field $field ${sing_args[*]} --n $n ${optimality_args[*]}"
"$python" "$checker" "$mesh" --connection "$conn" --field "$field" "${sing_args[@]}" --n "$n" "${optimality_args[@]}"
if [ ${#constraint_args[@]} -gt 0 ]; then
  here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
  echo "+ $python $here/check_constraints.py $mesh --connection $conn --field $field ${constraint_args[*]} --n $n"
  skip=()
  if [ "$guided_by_curvature" = 1 ]; then skip=(--no-optimality); fi # the program chose the guides
  "$python" "$here/check_constraints.py" "$mesh" --connection "$conn" --field "$field" "${constraint_args[@]}" --n "$n" "${skip[@]}"
fi
