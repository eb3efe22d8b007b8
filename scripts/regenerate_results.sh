#!/usr/bin/env bash
# Regenerates benchmark/RESULTS.md on this machine with one command (issue 42): every measurement that feeds it,
# one step after the other, then the header (date, machine, versions, the time of each step and of the whole run,
# which sections were written and which kept). Also `bash scripts/run_benchmarks.sh --everything [OPTIONS]`.
#
#   bash scripts/regenerate_results.sh [--dry-run] [--tables-only] [--no-build] [--skip STEP,...] [--only STEP,...]
#                                      [--gc PEER_BINARY] [--directional PEER_BINARY] [--tcods PEER_BINARY]
#                                      [--out FILE]
#
# Steps, in order (estimated wall time on the 2-core VM of December 2026, from the earlier runs of each step):
#   build            the benchmarks, the program, the Python module and the editor (build-bench, and
#                    build-bench-cholmod with CHOLMOD when it is installed); not with --no-build   ~15 min
#   suite-small      run_benchmarks.sh --floor --sizes small, every backend available (ldlt, cholmod, auto,
#                    all from the CHOLMOD build so that every floor has CHOLMOD), then --table-only    ~5 min
#   suite-large      the same, --sizes large (~1.2M faces)                                           ~8 min
#   suite-huge       the same, --sizes huge (4.8M faces)                                             ~13 min
#   placement-small  run_benchmarks.sh --placement --sizes small (ldlt, cholmod)                     ~5 min
#   placement-large  run_benchmarks.sh --placement --sizes large                                     ~15 min
#   integers         run_benchmarks.sh --integers                                                    ~20 s
#   python           run_benchmarks.sh --python                                                      ~1 min
#   editor           run_benchmarks.sh --editor (headless Chromium; needs the editor's build)        ~4 min
#   batch            run_benchmarks.sh --batch                                                       ~3 min
#   pins             trivial_connections_feature_pins_benchmark + scripts/feature_pins_table.py      ~5 min
#   gc               scripts/compare_geometry_central.sh, only with --gc                             ~2 min
#   directional      scripts/compare_directional.sh, only with --directional                         ~1 min
#   tcods            scripts/compare_tcods.sh, only with --tcods                                     ~1 min
# In all 1 h 12 min with the build and without the peers on 2026-12-05 (placement-large 27 min, suite-huge 18 min;
# the estimates above are older); the header of RESULTS.md gives the time of the last run, step by step.
#
# Every step writes its sections into a working copy of FILE (default benchmark/RESULTS.md); the sections of a
# step that is skipped, fails or has no peer given are kept as they were, with their own "Measured ..." line, and
# the output (and the header) says which. FILE is replaced at the end only, atomically (FILE.tmp, then renamed),
# and only if no section of it vanished. A step that fails does not stop the others (exit status 3 at the end).
#   --dry-run      print the steps, their commands and estimated times; nothing is run or written.
#   --tables-only  run no measurement: rewrite the tables that can be made from the JSON files of earlier runs
#                  (build-bench/benchmark-results/), keep the others, write the header; seconds.
#   --no-build     use the binaries as they are.
#   --skip/--only  comma lists of the step names above.
#   --gc, --directional, --tcods  the peers' scratch builds (outside the project, see each compare_* script's
#                  header), or TC_PEER_GC, TC_PEER_DIRECTIONAL, TC_PEER_TCODS. TC_COMPARE_REPS as the scripts take it
#                  (default 3, and 9 for TCODS).
# Environment: JOBS (build parallelism, default 2).
set -uo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="$ROOT/benchmark/RESULTS.md"
DRY=0
TABLES_ONLY=0
BUILD=1
SKIP=","
ONLY=""
PEER_GC="${TC_PEER_GC:-}"
PEER_DIRECTIONAL="${TC_PEER_DIRECTIONAL:-}"
PEER_TCODS="${TC_PEER_TCODS:-}"
JOBS="${JOBS:-2}"
COMMAND="bash scripts/regenerate_results.sh $*"

while [ $# -gt 0 ]; do
  case "$1" in
    --dry-run) DRY=1; shift ;;
    --tables-only) TABLES_ONLY=1; BUILD=0; shift ;;
    --no-build) BUILD=0; shift ;;
    --skip) SKIP=",$2,"; shift 2 ;;
    --only) ONLY=",$2,"; shift 2 ;;
    --gc) PEER_GC="$2"; shift 2 ;;
    --directional) PEER_DIRECTIONAL="$2"; shift 2 ;;
    --tcods) PEER_TCODS="$2"; shift 2 ;;
    --out) OUT="$2"; shift 2 ;;
    -h|--help) sed -n '2,42p' "$0"; exit 0 ;;
    *) echo "regenerate_results.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
COMMAND="${COMMAND% }"

PYTHON=python3
command -v python3 >/dev/null 2>&1 || PYTHON=/usr/bin/python3
RESULTS_DIR="$ROOT/build-bench/benchmark-results"
export TC_BENCH_MESH_CACHE="${TC_BENCH_MESH_CACHE:-$ROOT/build-bench/benchmark-meshes}"  # as run_benchmarks.sh's
HAVE_CHOLMOD=0
if [ -f /usr/include/suitesparse/cholmod.h ] || [ -f /usr/include/cholmod.h ]; then HAVE_CHOLMOD=1; fi
BACKENDS=ldlt
[ "$HAVE_CHOLMOD" = 1 ] && BACKENDS="ldlt cholmod auto"
# the build of the program, the module and the editor, with CHOLMOD when it is installed (as run_benchmarks.sh's)
MODULE_DIR="$ROOT/build-bench"
[ "$HAVE_CHOLMOD" = 1 ] && MODULE_DIR="$ROOT/build-bench-cholmod"

# name | estimated seconds | sections it writes (benchmark_tables/sections.py's short names) | what it runs
STEPS=(
  "build|900||cmake --build build-bench (and build-bench-cholmod) of the benchmarks, program, module, editor"
  "suite-small|300|$BACKENDS program controls floor slopes|bash scripts/run_benchmarks.sh --no-build --floor --sizes small, then --table-only"
  "suite-large|480|$BACKENDS program controls floor slopes|bash scripts/run_benchmarks.sh --no-build --floor --sizes large, then --table-only"
  "suite-huge|780|$BACKENDS program controls floor slopes|bash scripts/run_benchmarks.sh --no-build --floor --sizes huge, then --table-only"
  "placement-small|300|placement|bash scripts/run_benchmarks.sh --placement --no-build --sizes small"
  "placement-large|900|placement|bash scripts/run_benchmarks.sh --placement --no-build --sizes large"
  "integers|20|integers|bash scripts/run_benchmarks.sh --integers --no-build"
  "python|60|python|bash scripts/run_benchmarks.sh --python --no-build"
  "editor|240|editor|bash scripts/run_benchmarks.sh --editor --no-build"
  "batch|180|batch|bash scripts/run_benchmarks.sh --batch --no-build"
  "pins|300|pins|${MODULE_DIR#$ROOT/}/benchmark/trivial_connections_feature_pins_benchmark + scripts/feature_pins_table.py"
  "gc|120|gc|bash scripts/compare_geometry_central.sh ${PEER_GC:-PEER} ${MODULE_DIR#$ROOT/}/trivial_connections"
  "directional|60|directional|bash scripts/compare_directional.sh ${PEER_DIRECTIONAL:-PEER} ${MODULE_DIR#$ROOT/}"
  "tcods|60|tcods|bash scripts/compare_tcods.sh ${PEER_TCODS:-PEER} ${MODULE_DIR#$ROOT/}/trivial_connections"
)

wanted() { # STEP: whether --only / --skip let it run
  [[ "$SKIP" == *",$1,"* ]] && return 1
  [ -z "$ONLY" ] || [[ "$ONLY" == *",$1,"* ]]
}
# why a step does not run (empty: it runs)
why_not() {
  local name=$1 reason=""
  wanted "$name" || { echo "not selected: --skip or --only"; return; }
  case "$name" in
    build) [ "$BUILD" = 1 ] || reason="--no-build" ;;
    gc) [ -n "$PEER_GC" ] || reason="peer not given: --gc PEER_BINARY or TC_PEER_GC" ;;
    directional) [ -n "$PEER_DIRECTIONAL" ] || reason="peer not given: --directional PEER_BINARY or TC_PEER_DIRECTIONAL" ;;
    tcods) [ -n "$PEER_TCODS" ] || reason="peer not given: --tcods PEER_BINARY or TC_PEER_TCODS" ;;
  esac
  if [ -z "$reason" ] && [ "$TABLES_ONLY" = 1 ]; then
    case "$name" in
      suite-large|suite-huge) reason="--tables-only: suite-small writes the suite's tables from all its JSON files" ;;
      placement-large) reason="--tables-only: placement-small writes the section from all placement JSON files" ;;
      integers|batch|gc|directional|tcods) reason="--tables-only: its script writes its table, there is no JSON to make it from" ;;
      python) [ -f "$RESULTS_DIR/python-binding.json" ] || reason="--tables-only: no JSON of an earlier run" ;;
      editor) [ -f "$RESULTS_DIR/editor-latency.json" ] || reason="--tables-only: no JSON of an earlier run" ;;
      pins) [ -f "$RESULTS_DIR/feature-pins.json" ] || reason="--tables-only: no JSON of an earlier run" ;;
    esac
  fi
  echo "$reason"
}
fmt() { awk -v t="$1" 'BEGIN { t = int(t + 0.5); if (t < 60) printf "%d s", t; else if (t < 3600) { if (t % 60) printf "%d min %02d s", t / 60, t % 60; else printf "%d min", t / 60 } else printf "%d h %02d min", t / 3600, (t % 3600) / 60 }'; }

if [ "$DRY" = 1 ]; then
  echo "regenerate_results.sh --dry-run: $OUT; nothing is run"
  total=0
  for s in "${STEPS[@]}"; do
    IFS='|' read -r name est keys what <<< "$s"
    reason="$(why_not "$name")"
    if [ -n "$reason" ]; then
      printf '  %-16s %-10s skipped: %s\n' "$name" "-" "$reason"
    else
      [ "$TABLES_ONLY" = 1 ] && est=1
      total=$((total + est))
      printf '  %-16s ~%-9s %s\n' "$name" "$(fmt "$est")" "$what"
    fi
  done
  printf '  %-16s ~%-9s %s\n' "header" "1 s" "python3 scripts/benchmark_table.py --header-only --run-info STEPS.tsv, then $OUT.tmp renamed to $OUT"
  echo "estimated total: ~$(fmt "$total") (an estimate from earlier runs of each step on this 2-core VM)"
  exit 0
fi

[ -f "$OUT" ] || { echo "regenerate_results.sh: $OUT missing" >&2; exit 1; }
WORK="$(mktemp -d /tmp/regenerate_results.XXXXXX)"
W="$WORK/RESULTS.md"
cp "$OUT" "$WORK/previous.md"
cp "$OUT" "$W"
INFO="$WORK/steps.tsv"
START_EPOCH="$(date +%s.%N)"
{
  printf 'command\t%s\n' "$COMMAND"
  printf 'start\t%s\n' "$(date -u '+%Y-%m-%d %H:%M')"
  [ "$TABLES_ONLY" = 1 ] && printf 'mode\ttables-only\n'
} > "$INFO"
mkdir -p "$RESULTS_DIR"
echo "regenerate_results.sh: working copy $W (logs in $WORK)"

COMMIT="$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
if ! git -C "$ROOT" diff --quiet HEAD -- include examples 2>/dev/null; then COMMIT="$COMMIT+modified"; fi
MACHINE="$(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'))"

build_all() {
  local status=0 extra=()
  cmake -S "$ROOT" -B "$ROOT/build-bench" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF \
        -DTRIVIAL_CONNECTIONS_BUILD_BENCHMARKS=ON >/dev/null || return 1
  for t in trivial_connections trivial_connections_benchmark trivial_connections_placement_benchmark \
           trivial_connections_integer_benchmark trivial_connections_feature_pins_benchmark; do
    cmake --build "$ROOT/build-bench" -j "$JOBS" --target "$t" || { echo "build: $t failed" >&2; status=1; }
  done
  if [ "$HAVE_CHOLMOD" = 1 ]; then
    extra=(-DTRIVIAL_CONNECTIONS_WITH_CHOLMOD=ON)
  fi
  cmake -S "$ROOT" -B "$MODULE_DIR" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF \
        -DTRIVIAL_CONNECTIONS_BUILD_BENCHMARKS=ON -DTRIVIAL_CONNECTIONS_WITH_PYTHON=ON "${extra[@]}" >/dev/null || return 1
  for t in trivial_connections trivial_connections_benchmark trivial_connections_placement_benchmark \
           trivial_connections_feature_pins_benchmark trivial_connections_python trivial_connections_editor; do
    cmake --build "$MODULE_DIR" -j "$JOBS" --target "$t" || { echo "build: $t failed" >&2; status=1; }
  done
  return $status
}

# a section of FILE from a generated table: heading, the measurement line, a description, the table
pins_step() {
  local exe="$MODULE_DIR/benchmark/trivial_connections_feature_pins_benchmark" json="$RESULTS_DIR/feature-pins.json"
  if [ "$TABLES_ONLY" = 0 ]; then
    [ -x "$exe" ] || { echo "pins: $exe not built" >&2; return 1; }
    # in the working folder: its program runs write their connection and field files where they run
    (cd "$WORK" && "$exe" --benchmark_out="$json.tmp" --benchmark_out_format=json --benchmark_context=commit="$COMMIT") || return 1
    mv "$json.tmp" "$json"
  fi
  [ -f "$json" ] || { echo "pins: no $json" >&2; return 1; }
  local date commit section="$WORK/pins.md"
  # when and at which commit the JSON was made (a --tables-only run rewrites the table of an earlier run)
  read -r date commit <<< "$("$PYTHON" -c '
import datetime, json, sys
ctx = json.load(open(sys.argv[1])).get("context", {})
try:
    when = datetime.datetime.fromisoformat(ctx["date"]).astimezone(datetime.timezone.utc).strftime("%Y-%m-%d_%H:%M_UTC")
except (KeyError, ValueError):
    when = "unknown_date"
print(when, ctx.get("commit", "unknown"))' "$json")"
  date="${date//_/ }"
  {
    echo "### Feature pins"
    echo
    echo "Measured $date on $MACHINE, commit $commit, by \`bash scripts/regenerate_results.sh\` (step pins: \`benchmark/Trivial_connections/benchmark_feature_pins.cpp\` in \`${MODULE_DIR#$ROOT/}\`, Release; its JSON in \`build-bench/benchmark-results/feature-pins.json\`, the tables by \`scripts/feature_pins_table.py\`). One iteration per row. The analysis of the first run (issue 37, 2026-12-04: the targets, the links, the run before b35798f) is in this file's history (git log -p benchmark/RESULTS.md)."
    echo
    echo "Issue 37, items 2 and 5: every face beside a sharp edge pinned to the edge's direction, against the same mesh without pins in the same run. **Target (item 2)**: whole process and peak memory with 5–10 % of the faces pinned <= 1.5 x the same mesh without pins."
    echo
    echo "- **Meshes**: CGAL's \`fandisk.off\` (13k faces) and \`fandisk_large.off\` (32k), and fandisk_large split 1-to-4 by edge midpoints once (\`_mid1\`, 127k) and twice (\`_mid2\`, 507k), made by the benchmark in its mesh cache (never committed)."
    echo "- **Pins** (n = 4): \`features\` = \`CGAL::Trivial_connections::feature_aligned_faces(mesh, 30 degrees, symmetry_order(4))\` (faces beside the kept feature curves, with the curve's fitted direction); \`band\` = those plus the faces within r vertex rings, r the smallest reaching 5 % of the faces, the last ring cut at 10 %; \`50k\` = the first 50,000 faces of the same growth on the 507k mesh. In the library the pins go to the constructor (and to \`set_constraints()\`) as \`constrained_faces\` with their \`face_directions\`. \"Disagreeing pairs\": neighbouring pinned faces whose directions differ by more than 5 degrees modulo 90."
    echo
    "$PYTHON" "$ROOT/scripts/feature_pins_table.py" "$json" || return 1
  } > "$section" || return 1
  "$PYTHON" "$ROOT/scripts/benchmark_table.py" --insert "$section" --out "$W"
}

# SECTION_FILE HEADING PROSE TABLE: a peer's section (its heading, what was measured, the comparison script's
# table) written to SECTION_FILE and put into the working copy in place of the one there
insert_peer_section() {
  printf '%s\n\n%s\n\n' "$2" "$3" > "$1"
  cat "$4" >> "$1"
  "$PYTHON" "$ROOT/scripts/benchmark_table.py" --insert "$1" --out "$W"
}

gc_step() {
  local table="$WORK/gc-table.md" section="$WORK/gc.md" reps="${TC_COMPARE_REPS:-3}"
  TC_COMPARE_REPS="$reps" bash "$ROOT/scripts/compare_geometry_central.sh" "$PEER_GC" "$MODULE_DIR/trivial_connections" > "$table" || return 1
  insert_peer_section "$section" "### Against geometry-central's smoothest field" "Measured $(date -u '+%Y-%m-%d %H:%M') UTC on $MACHINE, by \`TC_COMPARE_REPS=$reps bash scripts/compare_geometry_central.sh $PEER_GC ${MODULE_DIR#$ROOT/}/trivial_connections\` (within \`$COMMAND\`) with our program of commit $COMMIT (Release; the program's solver traits: SimplicialLDLT or CHOLMOD by predicted cost). geometry-central: the peer program built outside the project as the script's header says. Whole processes, medians of $reps runs; ours \`--auto --no-refine\` is the smoothest field's singularities (what compares with geometry-central's), \`--auto\` refines them to a local minimum (issue 38's target: our refined whole run at most 0.5 of geometry-central's)." "$table"
}

directional_step() {
  local table="$WORK/directional-table.md" section="$WORK/directional.md" reps="${TC_COMPARE_REPS:-3}"
  TC_COMPARE_REPS="$reps" bash "$ROOT/scripts/compare_directional.sh" "$PEER_DIRECTIONAL" "$MODULE_DIR" > "$table" || return 1
  insert_peer_section "$section" "#### Side by side with Directional (item 5)" "Measured $(date -u '+%Y-%m-%d %H:%M') UTC on $MACHINE, by \`TC_COMPARE_REPS=$reps bash scripts/compare_directional.sh $PEER_DIRECTIONAL ${MODULE_DIR#$ROOT/}\` (within \`$COMMAND\`) with our program of commit $COMMIT: the \`features\` pins above for Directional's power field with hard constraints (the peer program built outside the project as the script's header says) and for our program, with Directional's singularities and with our \`--auto --no-refine\` placement; whole processes, medians of $reps runs." "$table"
}

tcods_step() {
  local table="$WORK/tcods-table.md" section="$WORK/tcods.md" reps="${TC_COMPARE_REPS:-9}"
  TC_COMPARE_REPS="$reps" bash "$ROOT/scripts/compare_tcods.sh" "$PEER_TCODS" "$MODULE_DIR/trivial_connections" > "$table" || return 1
  insert_peer_section "$section" "### Against the peers: Crane's TCODS" "Measured $(date -u '+%Y-%m-%d %H:%M') UTC on $MACHINE, by \`TC_COMPARE_REPS=$reps bash scripts/compare_tcods.sh $PEER_TCODS ${MODULE_DIR#$ROOT/}/trivial_connections\` (within \`$COMMAND\`) with our program of commit $COMMIT: whole processes, wall time, $reps runs of each program interleaved, medians. TCODS is Keenan Crane's reference code of the SGP 2010 paper, built outside this repository as the script's header says, and run as a user would: \`tcods PROBLEM\` reads the OBJ mesh (the same vertices and faces as CGAL's OFF file), solves, propagates a field and writes the mesh with one vector per face. Ours: \`trivial_connections MESH.off --singularities S --n 1 --connection C --field F\` (reads the OFF file, solves, propagates, writes the connection and the field). Same singularities: bunny00 (genus 0) +1 at vertices 24276 and 34482; refined_elephant (genus 3) −1 at vertices 41605, 41381, 24533 and 35695 (TCODS leaves the generators' integers at 0, ours chooses them to minimise the energy). Target of issue 20: ≥ 10 × faster." "$table"
}

run_step() {
  local name=$1
  local rb=(bash "$ROOT/scripts/run_benchmarks.sh" --no-build --out "$W")
  local table=()
  [ "$TABLES_ONLY" = 1 ] && table=(--table-only)
  case "$name" in
    build) build_all ;;
    # --floor: every backend from the CHOLMOD build, so that every backend's floor has CHOLMOD; then every table
    suite-small)
      if [ "$TABLES_ONLY" = 1 ]; then "${rb[@]}" --table-only
      else "${rb[@]}" --floor --sizes small && "${rb[@]}" --table-only; fi ;;
    suite-large) "${rb[@]}" --floor --sizes large && "${rb[@]}" --table-only ;;
    suite-huge) "${rb[@]}" --floor --sizes huge && "${rb[@]}" --table-only ;;
    placement-small) "${rb[@]}" --placement --sizes small "${table[@]}" ;;
    placement-large) "${rb[@]}" --placement --sizes large ;;
    integers) "${rb[@]}" --integers ;;
    python)
      if [ "$TABLES_ONLY" = 1 ]; then
        "$PYTHON" "$ROOT/scripts/benchmark_table.py" --section python --out "$W" "$RESULTS_DIR/python-binding.json"
      else "${rb[@]}" --python; fi ;;
    editor)
      if [ "$TABLES_ONLY" = 1 ]; then
        "$PYTHON" "$ROOT/scripts/benchmark_table.py" --section editor --out "$W" "$RESULTS_DIR/editor-latency.json"
      else "${rb[@]}" --editor; fi ;;
    batch) "${rb[@]}" --batch ;;
    pins) pins_step ;;
    gc) gc_step ;;
    directional) directional_step ;;
    tcods) tcods_step ;;
  esac
}

FAILED=()
for s in "${STEPS[@]}"; do
  IFS='|' read -r name est keys what <<< "$s"
  reason="$(why_not "$name")"
  if [ -n "$reason" ]; then
    printf 'step\t%s\t0\tskipped\t%s\t%s\n' "$name" "$keys" "$reason" >> "$INFO"
    for k in $keys; do printf 'kept\t%s\t%s\n' "$k" "$reason" >> "$INFO"; done
    echo "== $name: not run ($reason)"
    continue
  fi
  if [ "$TABLES_ONLY" = 1 ]; then echo "== $name: its tables from the JSON files"; else echo "== $name (estimated ~$(fmt "$est")): $what"; fi
  t0="$(date +%s.%N)"
  export TC_SECTIONS_LOG="$WORK/$name.sections"  # benchmark_table.py names there the sections it writes
  : > "$TC_SECTIONS_LOG"
  run_step "$name" 2>&1 | tee "$WORK/$name.log"
  status=${PIPESTATUS[0]}
  unset TC_SECTIONS_LOG
  t1="$(date +%s.%N)"
  seconds="$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')"
  if [ "$status" = 0 ]; then
    state=done
    [ "$TABLES_ONLY" = 1 ] && state=tables
    # batch_throughput.py writes its section itself
    [ "$name" = batch ] && echo "## The batch (trivial_connections-batch)" >> "$WORK/$name.sections"
    while IFS= read -r title; do printf 'wrote\t%s\t%s\n' "$name" "$title" >> "$INFO"; done < "$WORK/$name.sections"
  else
    state=failed; FAILED+=("$name")
    for k in $keys; do printf 'kept\t%s\t%s\n' "$k" "step $name failed, see its log" >> "$INFO"; done
  fi
  printf 'step\t%s\t%s\t%s\t%s\t%s\n' "$name" "$seconds" "$state" "$keys" "" >> "$INFO"
  echo "== $name: $state in $(fmt "$seconds")"
done
printf 'kept\trefinement\tprose, no measurement of its own\n' >> "$INFO"

END_EPOCH="$(date +%s.%N)"
printf 'total\t%s\n' "$(awk -v a="$START_EPOCH" -v b="$END_EPOCH" 'BEGIN { printf "%.1f", b - a }')" >> "$INFO"
shopt -s nullglob
"$PYTHON" "$ROOT/scripts/benchmark_table.py" --header-only --run-info "$INFO" --out "$W" "$RESULTS_DIR"/*.json \
  || { echo "regenerate_results.sh: the header could not be written; $OUT unchanged, the working copy is $W" >&2; exit 1; }
# no section of the previous file may vanish
"$PYTHON" -c '
import sys
sys.path.insert(0, sys.argv[1])
from benchmark_tables.sections import missing, split_file
lost = missing(split_file(sys.argv[2])[1], split_file(sys.argv[3])[1])
if lost:
    sys.exit("regenerate_results.sh: sections would vanish: " + "; ".join(lost))
' "$ROOT/scripts" "$WORK/previous.md" "$W" || { echo "regenerate_results.sh: $OUT unchanged, the working copy is $W" >&2; exit 1; }
cp "$W" "$OUT.tmp" && mv "$OUT.tmp" "$OUT"
echo "regenerate_results.sh: wrote $OUT in $(fmt "$(awk -v a="$START_EPOCH" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')")" \
     "(steps and logs in $WORK)${FAILED[*]:+; failed: ${FAILED[*]} (their sections kept)}"
[ ${#FAILED[@]} -eq 0 ] || exit 3
