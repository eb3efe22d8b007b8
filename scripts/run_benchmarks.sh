#!/usr/bin/env bash
# Runs the Google Benchmark suite (benchmark/) with JSON output and writes benchmark/RESULTS.md.
#
#   bash scripts/run_benchmarks.sh [--sizes small|large|huge|all|LIST] [--backends ldlt,cholmod,auto]
#                                  [--repetitions N] [--no-build] [--table-only] [--out FILE]
#   bash scripts/run_benchmarks.sh --integers [--no-build] [--out FILE]
#   bash scripts/run_benchmarks.sh --placement [--sizes ...] [--backends ...] [--repetitions N] [--no-build]
#                                  [--table-only] [--out FILE]
#   bash scripts/run_benchmarks.sh --python [--repetitions N] [--no-build] [--out FILE]
#   bash scripts/run_benchmarks.sh --editor [--repetitions EDITS] [--no-build] [--out FILE]
#   bash scripts/run_benchmarks.sh --batch [--no-build] [--out FILE]
#   bash scripts/run_benchmarks.sh --everything [OPTIONS]    = bash scripts/regenerate_results.sh [OPTIONS]
#
#   --everything   every measurement of FILE on this machine in one command, the modes below one after the other
#                  and the peers when given, then the header (versions, the time of each step); its --dry-run
#                  lists the steps with their estimated times. See scripts/regenerate_results.sh.
#   --sizes        small (default, a few minutes): CGAL meshes 5k-90k faces and a 300k subdivision;
#                  large: ~1.2M faces (genus 0, 11, 133); huge: ~5M faces; all; or a comma list.
#   --backends     ldlt (build dir build-bench), cholmod and auto (Automatic_solver_traits, the program's choice;
#                  both in build-bench-cholmod, built with -DTRIVIAL_CONNECTIONS_WITH_CHOLMOD=ON); default: all
#                  three (the last two only if CHOLMOD is installed).
#   --repetitions  repetitions of the small meshes (default 3; large and huge run once).
#   --floor        the suite as above, but only the section "Against the fastest factorization of the machine"
#                  of benchmark/RESULTS.md is rewritten, from the JSON files of the backends (the rest is kept).
#   --no-build     use the existing binaries.   --table-only   only rewrite the table from the JSON files.
#   --integers     instead of the suite: trivial_connections_integer_benchmark (the choice of the free integers
#                  against their number, about 15 s, build-bench) into build-bench/integer-choice.json, and its
#                  table as the section "Integer choice per dimension" of FILE (replaced in place, the other
#                  sections kept).
#   --placement    instead of the suite: trivial_connections_placement_benchmark (automatic singularity placement,
#                  n = 4, against the suite's reference factorization, and for n = 1, 2, 4 the placement then the
#                  refinement to a local minimum; small: femur (7.8k faces) and 52k-302k faces, about 1 min per
#                  repetition and backend; large: ~1.2M faces, several minutes per mesh) into
#                  build-bench/benchmark-results/placement-BACKEND-SIZE.json, and its table as the section
#                  "Automatic placement" of FILE (replaced in place, the other sections kept as they are). The suite
#                  also writes that section, from the same JSON files.
#   --python       instead of the suite: the Python module (built in build-bench-cholmod, or build-bench without
#                  CHOLMOD) against the C++ calls it makes, benchmark/python/binding_overhead.py on five CGAL meshes
#                  (5k-89k faces; 9 repetitions unless --repetitions, about 1 min) into
#                  build-bench/benchmark-results/python-binding.json, and its table as the section "The Python
#                  binding" of FILE (replaced in place). The suite also writes that section, from the same file.
#   --editor       instead of the suite: the field editor's latency in headless Chromium (same build as --python,
#                  with the editor), benchmark/editor/latency.mjs on refined_elephant (89k faces) and on
#                  fandisk_large with every face split in four (127k faces, benchmark/editor/split_faces.py,
#                  cached), each with the whole mesh in view and six times closer; 100 edits each unless
#                  --repetitions, about 4 min. Into build-bench/benchmark-results/editor-latency.json and the section
#                  "The field editor" of FILE (replaced in place). The suite also writes that section.
#
# JSON results go to build-bench/benchmark-results/BACKEND-SIZE.json and accumulate across runs: the table is
# made from all of them (the newest result of each mesh wins), so the large meshes can be run separately. The suite
# rewrites FILE's header and the sections it has JSON for, and keeps every other section of FILE as it is.
# Subdivided meshes are cached in $TC_BENCH_MESH_CACHE (default build-bench/benchmark-meshes).
# Environment: JOBS (build parallelism, default 2).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SIZES=small
BACKENDS=""
REPETITIONS=3
BUILD=1
TABLE_ONLY=0
OUT="$ROOT/benchmark/RESULTS.md"
JOBS="${JOBS:-2}"
INTEGERS=0
PLACEMENT=0
FLOOR=0
PYTHON_BINDING=0
EDITOR=0
BATCH=0
REPETITIONS_GIVEN=0

ALL_ARGS=("$@")
for a in "$@"; do [ "$a" = --everything ] && set -- --everything; done
while [ $# -gt 0 ]; do
  case "$1" in
    --sizes) SIZES="$2"; shift 2 ;;
    --backends) BACKENDS="$2"; shift 2 ;;
    --repetitions) REPETITIONS="$2"; REPETITIONS_GIVEN=1; shift 2 ;;
    --no-build) BUILD=0; shift ;;
    --table-only) TABLE_ONLY=1; shift ;;
    --out) OUT="$2"; shift 2 ;;
    --integers) INTEGERS=1; shift ;;
    --placement) PLACEMENT=1; shift ;;
    --floor) FLOOR=1; shift ;;
    --python) PYTHON_BINDING=1; shift ;;
    --editor) EDITOR=1; shift ;;
    --batch) BATCH=1; shift ;;
    --everything)  # the other arguments are regenerate_results.sh's
      args=(); for a in "${ALL_ARGS[@]}"; do [ "$a" = --everything ] || args+=("$a"); done
      exec bash "$ROOT/scripts/regenerate_results.sh" "${args[@]}" ;;
    -h|--help) sed -n '2,53p' "$0"; exit 0 ;;
    *) echo "run_benchmarks.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ "$SIZES" = all ] && SIZES=small,large,huge

if [ -z "$BACKENDS" ]; then
  BACKENDS=ldlt
  if [ -f /usr/include/suitesparse/cholmod.h ] || [ -f /usr/include/cholmod.h ]; then
    BACKENDS=ldlt,cholmod,auto
  fi
fi

PYTHON=python3
command -v python3 >/dev/null 2>&1 || PYTHON=/usr/bin/python3

if [ "$INTEGERS" = 1 ]; then
  dir="$ROOT/build-bench"
  if [ "$BUILD" = 1 ]; then
    cmake -S "$ROOT" -B "$dir" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF \
          -DTRIVIAL_CONNECTIONS_BUILD_BENCHMARKS=ON >/dev/null
    cmake --build "$dir" -j "$JOBS" --target trivial_connections_integer_benchmark
  fi
  exe="$dir/benchmark/trivial_connections_integer_benchmark"
  [ -x "$exe" ] || { echo "run_benchmarks.sh: $exe not built" >&2; exit 1; }
  [ -f "$OUT" ] || { echo "run_benchmarks.sh: $OUT missing (run the suite first)" >&2; exit 1; }
  COMMIT="$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  if ! git -C "$ROOT" diff --quiet HEAD -- include 2>/dev/null; then COMMIT="$COMMIT with uncommitted changes in include/"; fi
  md="$(mktemp)"
  TC_BENCH_MARKDOWN="$md" "$exe" --benchmark_out="$dir/integer-choice.json" --benchmark_out_format=json \
    --benchmark_context=commit="${COMMIT%% *}"
  section="$(mktemp)"
  {
    echo "### Integer choice per dimension"
    echo
    echo "Measured $(date -u +%Y-%m-%d) on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')), commit $COMMIT, by \`bash scripts/run_benchmarks.sh --integers\` (\`benchmark/Trivial_connections/benchmark_integer_choice.cpp\`, Eigen::SimplicialLDLT)."
    echo "k: the free integers (the loops not prescribed but one boundary loop per bordered component, which Poincaré–Hopf fixes, plus the constraint links); annulus_mM and holes_pP are generated (align_with_boundary: a constraint link per boundary vertex but one), the others are CGAL's meshes. Reduction: the constructor's loop_metric phase (the metric of the integers + LLL with deep insertions). Choice: the loop_integers phase of a solve (nearest plane, descent, budgeted enumeration) and the whole solve, medians over 9 solves of each of two singularity sets. Rel. gap = (energy − energy_lower_bound) / energy (energy with the guidance energy, 0 here), the larger of the two sets (0 when proven); proven: sets whose choice is proven optimal; rounding excess: (rounding_energy − energy) / energy, what rounding the integers one by one would cost more, the larger of the two sets."
    echo
    cat "$md"
  } > "$section"
  # the section replaced in place (the rest of FILE kept; written atomically)
  "$PYTHON" "$ROOT/scripts/benchmark_table.py" --insert "$section" --out "$OUT"
  rm -f "$md" "$section"
  exit 0
fi

RESULTS_DIR="$ROOT/build-bench/benchmark-results"
export TC_BENCH_MESH_CACHE="${TC_BENCH_MESH_CACHE:-$ROOT/build-bench/benchmark-meshes}"
mkdir -p "$RESULTS_DIR" "$TC_BENCH_MESH_CACHE"

HAVE_CHOLMOD=0
if [ -f /usr/include/suitesparse/cholmod.h ] || [ -f /usr/include/cholmod.h ]; then HAVE_CHOLMOD=1; fi

# the build of --python and --editor: the Python module (and the editor), with CHOLMOD when it is installed
MODULE_DIR="$ROOT/build-bench"
[ "$HAVE_CHOLMOD" = 1 ] && MODULE_DIR="$ROOT/build-bench-cholmod"
build_module_targets() {
  [ "$BUILD" = 1 ] || return 0
  local extra=()
  [ "$HAVE_CHOLMOD" = 1 ] && extra=(-DTRIVIAL_CONNECTIONS_WITH_CHOLMOD=ON)
  cmake -S "$ROOT" -B "$MODULE_DIR" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF \
        -DTRIVIAL_CONNECTIONS_BUILD_BENCHMARKS=ON -DTRIVIAL_CONNECTIONS_WITH_PYTHON=ON "${extra[@]}" >/dev/null
  cmake --build "$MODULE_DIR" -j "$JOBS" --target "$@"
}

# --batch: trivial_connections-batch (Dask, python3-distributed) with 1 and 2 local workers on the data set's 30
# largest meshes, and its overhead per mesh on the 40 smallest (benchmark/batch/batch_throughput.py, about 3 min);
# the section "The batch" of FILE (replaced in place). Run it alone on the machine: it measures a ratio of cores.
if [ "$BATCH" = 1 ]; then
  dir="$ROOT/build-bench"
  if [ "$BUILD" = 1 ]; then
    cmake -S "$ROOT" -B "$dir" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF >/dev/null
    cmake --build "$dir" -j "$JOBS" --target trivial_connections
  fi
  [ -x "$dir/trivial_connections" ] || { echo "run_benchmarks.sh: $dir/trivial_connections not built" >&2; exit 1; }
  [ -f "$ROOT/.cgal-data/data/meshes/elephant.off" ] || { echo "run_benchmarks.sh: CGAL's meshes are missing: run bash scripts/fetch_cgal_data.sh" >&2; exit 1; }
  COMMIT="$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  if ! git -C "$ROOT" diff --quiet HEAD -- include python examples 2>/dev/null; then COMMIT="$COMMIT+modified"; fi
  mkdir -p "$ROOT/build-bench/benchmark-results"
  /usr/bin/python3 "$ROOT/benchmark/batch/batch_throughput.py" "$dir/trivial_connections" "$ROOT/.cgal-data/data/meshes" \
    --json "$ROOT/build-bench/benchmark-results/batch.json" --markdown "$OUT" --commit "$COMMIT"
  exit 0
fi

if [ "$EDITOR" = 1 ]; then
  dir="$MODULE_DIR"
  build_module_targets trivial_connections_python trivial_connections_editor
  [ -x "$dir/trivial_connections-serve" ] || { echo "run_benchmarks.sh: no editor in $dir (node, npm and npm's registry are needed)" >&2; exit 1; }
  [ -f "$OUT" ] || { echo "run_benchmarks.sh: $OUT missing (run the suite first)" >&2; exit 1; }
  data="$ROOT/.cgal-data/data/meshes"
  [ -f "$data/refined_elephant.off" ] || { echo "run_benchmarks.sh: CGAL's meshes are missing: run bash scripts/fetch_cgal_data.sh" >&2; exit 1; }
  cache="${TC_BENCH_MESH_CACHE:-$ROOT/build-bench/benchmark-meshes}"
  mkdir -p "$cache" "$RESULTS_DIR/editor"
  [ -f "$cache/fandisk_large_split.off" ] || /usr/bin/python3 "$ROOT/benchmark/editor/split_faces.py" "$data/fandisk_large.off" "$cache/fandisk_large_split.off"
  edits=100
  [ "$REPETITIONS_GIVEN" = 1 ] && edits="$REPETITIONS"
  runs=()
  for mesh in "$data/refined_elephant.off" "$cache/fandisk_large_split.off"; do
    for zoom in 1 6; do
      json="$RESULTS_DIR/editor/$(basename "$mesh" .off)-zoom$zoom.json"
      NODE_PATH="$dir/editor-npm/node_modules" node "$ROOT/benchmark/editor/latency.mjs" "$dir/trivial_connections-serve" \
        "$mesh" "$edits" --zoom "$zoom" --json "$json"
      runs+=("$json")
    done
  done
  COMMIT="$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  if ! git -C "$ROOT" diff --quiet HEAD -- include python editor 2>/dev/null; then COMMIT="$COMMIT+modified"; fi
  /usr/bin/python3 - "$COMMIT" "$RESULTS_DIR/editor-latency.json" "${runs[@]}" <<'PY'
import datetime, json, sys
commit, out, runs = sys.argv[1], sys.argv[2], sys.argv[3:]
with open(out, "w") as f:
    json.dump({"editor_latency": [json.load(open(r)) for r in runs], "commit": commit,
               "date": datetime.datetime.now().isoformat(timespec="seconds")}, f, indent=1)
PY
  /usr/bin/python3 "$ROOT/scripts/benchmark_table.py" --section editor --out "$OUT" "$RESULTS_DIR/editor-latency.json"
  exit 0
fi

if [ "$PYTHON_BINDING" = 1 ]; then
  dir="$MODULE_DIR"
  build_module_targets trivial_connections_python
  ls "$dir"/python/trivial_connections*.so >/dev/null 2>&1 || { echo "run_benchmarks.sh: the Python module is not built in $dir/python" >&2; exit 1; }
  [ -f "$OUT" ] || { echo "run_benchmarks.sh: $OUT missing (run the suite first)" >&2; exit 1; }
  meshes=()
  for m in elephant cheese turbine bunny00 refined_elephant; do meshes+=("$ROOT/.cgal-data/data/meshes/$m.off"); done
  [ -f "${meshes[0]}" ] || { echo "run_benchmarks.sh: CGAL's meshes are missing: run bash scripts/fetch_cgal_data.sh" >&2; exit 1; }
  COMMIT="$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  if ! git -C "$ROOT" diff --quiet HEAD -- include python 2>/dev/null; then COMMIT="$COMMIT+modified"; fi
  reps=9
  [ "$REPETITIONS_GIVEN" = 1 ] && reps="$REPETITIONS"
  PYTHONPATH="$dir/python" /usr/bin/python3 "$ROOT/benchmark/python/binding_overhead.py" "${meshes[@]}" \
    --repetitions "$reps" --json "$RESULTS_DIR/python-binding.json.tmp" --commit "$COMMIT"
  mv "$RESULTS_DIR/python-binding.json.tmp" "$RESULTS_DIR/python-binding.json"
  /usr/bin/python3 "$ROOT/scripts/benchmark_table.py" --section python --out "$OUT" "$RESULTS_DIR/python-binding.json"
  exit 0
fi

# the suite, or the placement benchmark (its JSON files named placement-BACKEND-SIZE.json)
TARGET=trivial_connections_benchmark
PREFIX=""
if [ "$PLACEMENT" = 1 ]; then
  TARGET=trivial_connections_placement_benchmark
  PREFIX=placement-
fi

# with --floor every backend runs from the CHOLMOD build (when CHOLMOD is installed), whose floor has CHOLMOD too
build_dir() {
  case "$1" in
    ldlt) if [ "$FLOOR" = 1 ] && [ "$HAVE_CHOLMOD" = 1 ]; then echo "$ROOT/build-bench-cholmod"; else echo "$ROOT/build-bench"; fi ;;
    cholmod|auto) echo "$ROOT/build-bench-cholmod" ;;
    *) echo "run_benchmarks.sh: unknown backend $1 (ldlt, cholmod, auto)" >&2; exit 2 ;;
  esac
}

if [ "$TABLE_ONLY" = 0 ]; then
  if [ ! -d "$ROOT/.cgal-data/data/meshes" ]; then
    echo "run_benchmarks.sh: CGAL's meshes are missing: run bash scripts/fetch_cgal_data.sh" >&2
    exit 1
  fi
  # the commit checked out when the suite runs (+modified: include/ differs from it); `built` below is the time
  # the binary was linked, which matters with --no-build
  COMMIT="$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  if ! git -C "$ROOT" diff --quiet HEAD -- include 2>/dev/null; then COMMIT="$COMMIT+modified"; fi
  for backend in ${BACKENDS//,/ }; do
    # the placement benchmark has no `auto` backend (its pencil is factored the same way whatever the backend)
    if [ "$PLACEMENT" = 1 ] && [ "$backend" = auto ]; then continue; fi
    dir="$(build_dir "$backend")"
    if [ "$BUILD" = 1 ]; then
      extra=()
      [ "$dir" = "$ROOT/build-bench-cholmod" ] && extra=(-DTRIVIAL_CONNECTIONS_WITH_CHOLMOD=ON)
      cmake -S "$ROOT" -B "$dir" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF \
            -DTRIVIAL_CONNECTIONS_BUILD_BENCHMARKS=ON "${extra[@]}" >/dev/null
      cmake --build "$dir" -j "$JOBS" --target "$TARGET"
    fi
    exe="$dir/benchmark/$TARGET"
    [ -x "$exe" ] || { echo "run_benchmarks.sh: $exe not built" >&2; exit 1; }
    built="$(date -u -r "$exe" +%Y-%m-%dT%H:%MZ)"
    for size in ${SIZES//,/ }; do
      reps=1
      [ "$size" = small ] && reps="$REPETITIONS"
      json="$RESULTS_DIR/$PREFIX$backend-$size.json"
      echo "== $TARGET: $backend, $size meshes, $reps repetition(s) -> $json"
      TC_BENCH_SIZES="$size" "$exe" \
        --benchmark_filter="^$backend/" \
        --benchmark_repetitions="$reps" --benchmark_display_aggregates_only=true \
        --benchmark_context=commit="$COMMIT",built="$built",backend="$backend",sizes="$size" \
        --benchmark_out="$json.tmp" --benchmark_out_format=json
      mv "$json.tmp" "$json"
    done
  done
fi

shopt -s nullglob
if [ "$PLACEMENT" = 1 ]; then
  files=("$RESULTS_DIR"/placement-*.json)
  [ ${#files[@]} -gt 0 ] || { echo "run_benchmarks.sh: no placement results in $RESULTS_DIR" >&2; exit 1; }
  [ -f "$OUT" ] || { echo "run_benchmarks.sh: $OUT missing (run the suite first)" >&2; exit 1; }
  "$PYTHON" "$ROOT/scripts/benchmark_table.py" --section placement --out "$OUT" "${files[@]}"
  exit 0
fi
if [ "$FLOOR" = 1 ]; then
  # every size measured so far (the sizes can be run separately; results without a floor are left out)
  files=()
  for backend in ${BACKENDS//,/ }; do
    for json in "$RESULTS_DIR/$backend"-*.json; do files+=("$json"); done
  done
  [ ${#files[@]} -gt 0 ] || { echo "run_benchmarks.sh: no results in $RESULTS_DIR" >&2; exit 1; }
  [ -f "$OUT" ] || { echo "run_benchmarks.sh: $OUT missing (run the suite first)" >&2; exit 1; }
  "$PYTHON" "$ROOT/scripts/benchmark_table.py" --section floor --out "$OUT" "${files[@]}"
  exit 0
fi
files=("$RESULTS_DIR"/*.json)
[ ${#files[@]} -gt 0 ] || { echo "run_benchmarks.sh: no results in $RESULTS_DIR" >&2; exit 1; }
"$PYTHON" "$ROOT/scripts/benchmark_table.py" --out "$OUT" "${files[@]}"
