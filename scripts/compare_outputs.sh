#!/usr/bin/env bash
# Proves that a change leaves the program's outputs bitwise identical: builds trivial_connections at
# BASE_REV and at the working tree, runs both on the same cases, and compares every file each run leaves
# (byte for byte, with cmp), its stdout and stderr, and its exit status.
#
# Usage: bash scripts/compare_outputs.sh [BASE_REV]
#   BASE_REV  the commit to compare with. Default b84a70f: the last commit before the architecture
#             rewrite, whose outputs the rewrite must keep.
#   JOBS      (environment) parallel build jobs, default 2
# Needs CGAL's data set (bash scripts/fetch_cgal_data.sh) and python3 (test scripts, generated inputs).
#
# Both builds are Release with -DBUILD_TESTING=OFF (the options of scripts/test.sh otherwise) and are
# reused when up to date. Everything goes under build-compare/ (git-ignored):
#   base-<commit>/src, base-<commit>/build   BASE_REV's files (git archive) and their build
#   head/                                    the working tree's build
#   inputs/                                  the input files this script writes
#   runs/base/CASE, runs/head/CASE           what each run left: files/, stdout, stderr, status
# Each case runs in the same folder (runs/work) with the same program path, so that the paths the program
# prints are the same for both. In stdout and stderr the elapsed times (the report's `time:` line, --progress
# lines, which no case asks for) and the random name of a temporary folder of bad_inputs.py are masked.
# OMP_NUM_THREADS=1 and OPENBLAS_NUM_THREADS=1: CHOLMOD's threads cannot reorder sums between the runs.
#
# Cases: every configuration of the command-line tests of CMakeLists.txt (tc_add_cli_check,
# tc_add_cli_design_check, cli_viewer.sh, check_render.py, cli_version), the scripts cli_errors.sh,
# cli_triangulate.py and bad_inputs.py run whole with each program, and a spread over CGAL's meshes
# (closed, bordered, high genus, several components, quads with --triangulate, every design control and
# output, bad inputs and command lines).
# Prints one line per case (`same`, `DIFFERENT` with the first thing that differs, or `NOT RUN` with why)
# and a summary. Exit status: 0 every case the same, 1 a case differs or could not run, 2 the script
# itself could not start (usage, missing data, build failure).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

if [ $# -gt 1 ] || [[ "${1:-}" == -* ]]; then
  sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
  exit 2
fi
base_rev="${1:-b84a70f}"
jobs="${JOBS:-2}"
data="$root/.cgal-data/data/meshes"
tests="$root/test/Trivial_connections"
tdata="$tests/data"
examples="$root/examples/data"
out="$root/build-compare"
inputs="$out/inputs"
runs="$out/runs"
work="$runs/work"
program="$runs/bin/trivial_connections"
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1

die() { echo "compare_outputs.sh: $*" >&2; exit 2; }
[ -d "$data" ] || die "CGAL's data set is missing at $data (run: bash scripts/fetch_cgal_data.sh)"
command -v python3 > /dev/null || die "python3 not found"
base_commit=$(git rev-parse --verify --quiet "$base_rev^{commit}") || die "unknown revision '$base_rev'"
start=$SECONDS

# ---- builds
build() { # SOURCE_DIR BUILD_DIR
  echo "building $2"
  if ! { cmake -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF &&
         cmake --build "$2" -j "$jobs" --target trivial_connections; } > "$2.log" 2>&1; then
    tail -n 30 "$2.log" >&2
    die "the build in $2 failed (log: $2.log)"
  fi
}
base_dir="$out/base-${base_commit:0:12}"
if [ ! -e "$base_dir/src/.extracted" ]; then # extracted once: the files keep their times and the build is reused
  rm -rf "$base_dir/src"
  mkdir -p "$base_dir/src"
  git archive "$base_commit" | tar -x -C "$base_dir/src"
  touch "$base_dir/src/.extracted"
fi
build "$base_dir/src" "$base_dir/build"
build "$root" "$out/head"

# ---- inputs written here: singularities, directions and boundary indices (a few vertices and faces)
rm -rf "$inputs"
mkdir -p "$inputs"
python3 - "$data" "$inputs" << 'EOF'
import sys
from fractions import Fraction
data, inputs = sys.argv[1], sys.argv[2]

def write(name, lines):
    with open(f"{inputs}/{name}", "w") as f:
        f.write("# written by scripts/compare_outputs.sh\n" + "".join(line + "\n" for line in lines))

def read_off_faces(path):
    words = [w for line in open(path) for w in line.split("#", 1)[0].split()]
    nv, nf = int(words[1]), int(words[2])
    at, faces = 4 + 3 * nv, []
    for _ in range(nf):
        k = int(words[at])
        faces.append([int(w) for w in words[at + 1:at + 1 + k]])
        at += 1 + k
    return faces

def boundary_loops(faces):
    """The boundary loops as sets of vertices, ordered by their smallest vertex."""
    directed = {(f[i], f[(i + 1) % len(f)]) for f in faces for i in range(len(f))}
    parent = {}
    def find(v):
        while parent.setdefault(v, v) != v:
            v = parent[v]
        return v
    for a, b in directed:
        if (b, a) not in directed:
            parent[find(a)] = find(b)
    loops = {}
    for v in parent:
        loops.setdefault(find(v), set()).add(v)
    return sorted(loops.values(), key=min)

# closed meshes: indices that sum to the Euler characteristic
write("dino.sing", ["0 1", "3000 1"])
write("bunny00.sing", ["0 1", "20000 1"])
write("homer.sing", ["100 2"])
write("quarters_0_to_7.sing", ["%d 1/4" % v for v in range(8)])
write("sphere_stl_halves.sing", ["%d 1/2" % v for v in (0, 10, 20, 30)])
write("cheese.sing", ["%d -1" % (30 * i) for i in range(264)])            # genus 133
write("turbine.sing", ["%d -1" % (400 * i) for i in range(20)])           # genus 11
write("anchor.sing", ["%d -1" % (80 * i) for i in range(6)])              # genus 4
write("double_torus.sing", ["0 -1", "40 -1"])                             # genus 2
# errors: Poincare-Hopf violated (cow.off, chi = 2), a vertex that does not exist
write("cow_one.sing", ["0 1"])
write("cow_missing_vertex.sing", ["0 1", "99999 1"])
# directional constraints and guides: face, direction
write("head.dirs", ["10 1 0 0", "500 0 1 0", "1500 0.3 0.2 1", "2900 -1 1 0"])
write("pinion.dirs", ["0 1 0 0", "650 0 0 1"])
write("pinion_guides.dirs", ["100 1 1 0", "900 0 1 1", "1200 1 0 1"])
write("dino_guides.dirs", ["5 1 0 0", "4000 0 1 0", "7000 0 0 1"])
# the index of every boundary loop, named by its smallest vertex; the indices sum to chi
for mesh, chi, second in (("holes", -5, "-1"), ("lion", -3, "-3/2")):
    loops = boundary_loops(read_off_faces(f"{data}/{mesh}.off"))
    others = [Fraction(second)] + [Fraction(-1)] * (len(loops) - 2)
    indices = [chi - sum(others)] + others
    write(f"{mesh}_boundary.idx", ["%d %s" % (min(l), k) for l, k in zip(loops, indices)])
EOF
cp "$examples/sphere.sing" "$inputs/sphere_copy.sing"

# ---- running and comparing
masked() { # FILE: its text without elapsed times and temporary folder names
  sed -E -e '/^time: /s/[0-9]+\.[0-9]+/#/g' -e 's/\[ *[0-9]+\.[0-9]+ s\]/[# s]/g' \
         -e 's/\( *[0-9]+\.[0-9]+ s\)/(# s)/g' -e 's/tc_bad_inputs_[A-Za-z0-9_]+/tc_bad_inputs_#/g' "$1"
}

# run_in_work SIDE NAME COMMAND...: runs the command in an empty $work with SIDE's program, keeps what
# it left in $runs/SIDE/NAME
run_in_work() {
  local side="$1" name="$2"
  shift 2
  local kept="$runs/$side/$name" status=0
  rm -rf "$work" "$kept"
  mkdir -p "$work" "$kept"
  cp "$out/$side-program" "$program"
  (cd "$work" && exec timeout 600 "$@") > "$kept/stdout" 2> "$kept/stderr" || status=$?
  echo "$status" > "$kept/status"
  mv "$work" "$kept/files"
}

first_difference() { # BASE_DIR HEAD_DIR: prints the first thing that differs, nothing if none does
  local a="$1" b="$2" f list_a list_b type path
  for f in status stdout stderr; do
    if ! cmp -s <(masked "$a/$f") <(masked "$b/$f"); then echo "$f"; return; fi
  done
  list_a=$(cd "$a/files" && find . -mindepth 1 -printf '%y %p\n' | LC_ALL=C sort)
  list_b=$(cd "$b/files" && find . -mindepth 1 -printf '%y %p\n' | LC_ALL=C sort)
  if [ "$list_a" != "$list_b" ]; then
    LC_ALL=C comm -3 <(echo "$list_a") <(echo "$list_b") | head -n 1 |
      sed -E 's/^\t(. \.\/)?(.*)/\2 (only in the working tree)/; s/^. \.\/(.*)/\1 (only in base)/'
    return
  fi
  while read -r type path; do
    if [ "$type" = f ] && ! cmp -s "$a/files/$path" "$b/files/$path"; then echo "${path#./}"; return; fi
  done <<< "$list_a"
}

cases=0 same=0 different=0 not_run=0
report() { # NAME VERDICT [DETAIL]
  cases=$((cases + 1))
  case "$2" in
    same) same=$((same + 1)); printf '%-10s %s\n' same "$1" ;;
    DIFFERENT) different=$((different + 1)); printf '%-10s %s: %s\n' DIFFERENT "$1" "$3" ;;
    *) not_run=$((not_run + 1)); printf '%-10s %s: %s\n' "NOT RUN" "$1" "$3" ;;
  esac
}

# compare EXPECTED_STATUS NAME COMMAND...: COMMAND (where the word PROGRAM stands for the program) with
# both programs; BASE_REV must exit with EXPECTED_STATUS, or the case does not test what it says
compare() {
  local expected="$1" name="$2" side status arg argv=()
  shift 2
  for arg in "$@"; do
    if [ "$arg" = PROGRAM ]; then argv+=("$program"); else argv+=("$arg"); fi
  done
  for side in base head; do
    run_in_work "$side" "$name" "${argv[@]}"
  done
  for side in base head; do
    status=$(cat "$runs/$side/$name/status")
    if [ "$status" = 124 ] || [ "$status" -ge 126 ]; then
      report "$name" "NOT RUN" "the $side program timed out, crashed or could not start (status $status)"
      return
    fi
  done
  status=$(cat "$runs/base/$name/status")
  if [ "$status" != "$expected" ]; then
    local why
    why=$(head -c 300 "$runs/base/$name/stderr" | tr '\n' ' ')
    report "$name" "NOT RUN" "$base_rev exited with $status, the case expects $expected: $why"
    return
  fi
  local difference
  difference=$(first_difference "$runs/base/$name" "$runs/head/$name")
  if [ -z "$difference" ]; then report "$name" same; else report "$name" DIFFERENT "$difference"; fi
}
# check EXPECTED_STATUS NAME MESH [OPTIONS...]: the program on MESH, with --connection c.txt --field f.txt
check() {
  local expected="$1" name="$2" mesh="$3"
  shift 3
  compare "$expected" "$name" PROGRAM "$mesh" "$@" --connection c.txt --field f.txt
}

cp "$base_dir/build/trivial_connections" "$out/base-program"
cp "$out/head/trivial_connections" "$out/head-program"
rm -rf "$runs"
mkdir -p "$runs/bin"
echo "comparing $base_rev ($base_commit) with the working tree"

# ---- the configurations of the command-line tests (CMakeLists.txt)
compare 0 cli_version PROGRAM --version
compare 0 help PROGRAM --help
check 0 cli_default_example "$examples/sphere.off" --singularities "$examples/sphere.sing" --n 1 --weights hodge
check 0 cli_default_example_n4 "$examples/sphere.off" --singularities "$tdata/sphere_quarters.sing" --n 4 \
  --weights hodge
check 0 cli_default_example_unit "$examples/sphere.off" --singularities "$examples/sphere.sing" --n 1 --weights unit
for n in 1 4; do
  check 0 "cli_cow_n$n" "$data/cow.off" --singularities "$tdata/cow.sing" --n $n --weights hodge
  check 0 "cli_knot1_n$n" "$data/knot1.off" --n $n --weights hodge
  check 0 "cli_rotor_n$n" "$data/rotor.off" --n $n --weights hodge
  check 0 "cli_elephant_n$n" "$data/elephant.off" --singularities "$tdata/elephant.sing" --n $n --weights hodge
  check 0 "cli_pig_n$n" "$data/pig.off" --n $n --weights hodge
  check 0 "cli_mesh_with_border_n$n" "$data/mesh_with_border.off" --singularities "$tdata/mesh_with_border.sing" \
    --n $n --weights hodge
done
check 0 cli_cow_quarters_n4 "$data/cow.off" --singularities "$tdata/cow_quarters.sing" --n 4 --weights hodge
check 0 cli_pig_boundary_indices_n4 "$data/pig.off" --boundary-indices "$tdata/pig_boundary.idx" --n 4 --weights hodge
for n in 1 4; do
  check 0 "cli_elk_constraints_n$n" "$data/elk.off" --constraints "$tdata/elk.dirs" --n $n --weights hodge
  check 0 "cli_pig_constraints_aligned_n$n" "$data/pig.off" --constraints "$tdata/pig.dirs" --align-boundary \
    --n $n --weights hodge
  check 0 "cli_elk_guidance_n$n" "$data/elk.off" --guidance "$tdata/elk.dirs" --guidance-weight 2.5 --n $n \
    --weights hodge
done
check 0 cli_cow_constraints_n1 "$data/cow.off" --singularities "$tdata/cow.sing" --constraints "$tdata/cow.dirs" \
  --n 1 --weights hodge
check 0 cli_cow_constraints_n4 "$data/cow.off" --singularities "$tdata/cow_quarters.sing" \
  --constraints "$tdata/cow.dirs" --n 4 --weights hodge
check 0 cli_mesh_with_border_constraints_aligned_n2 "$data/mesh_with_border.off" \
  --singularities "$tdata/mesh_with_border.sing" --constraints "$tdata/mesh_with_border.dirs" --align-boundary \
  --n 2 --weights hodge
check 0 cli_pig_aligned_boundary_indices_n4 "$data/pig.off" --boundary-indices "$tdata/pig_boundary.idx" \
  --align-boundary --n 4 --weights hodge
check 0 cli_pig_all_controls_n4 "$data/pig.off" --constraints "$tdata/pig.dirs" --align-boundary \
  --guidance "$tdata/pig_guides.dirs" --guidance-weight 0.5 --n 4 --weights hodge
check 0 cli_viewer_outputs "$examples/sphere.off" --singularities "$tdata/sphere_quarters.sing" --n 4 \
  --vtk field.vtk --ply field.ply --singularity-points sing.txt --streamlines lines.vtk --streamline-seeds 20
check 1 cli_viewer_unwritable_output "$examples/sphere.off" --singularities "$tdata/sphere_quarters.sing" --n 4 \
  --vtk no_such_dir/field.vtk
check 0 cli_render_png_n1 "$examples/sphere.off" --singularities "$examples/sphere.sing" --vtk sphere.vtk \
  --streamlines sphere_stream.vtk
check 0 cli_render_png_n4 "$examples/sphere.off" --n 4 --singularities "$inputs/quarters_0_to_7.sing" --vtk sphere4.vtk
# the test scripts run whole: every program run they make, their verdicts and the files they leave
compare 0 cli_input_file_errors bash "$tests/cli_errors.sh" PROGRAM out "$data/pig.off" "$examples/sphere.off"
compare 0 cli_triangulate python3 "$tests/cli_triangulate.py" PROGRAM out
compare 0 bad_input_corpus python3 "$tests/bad_inputs.py" PROGRAM out

# ---- a spread over CGAL's meshes
# closed genus 0, with singularities (Poincare-Hopf), every output, other input formats
check 0 dino_n1_all_outputs "$data/dino.off" --singularities "$inputs/dino.sing" --vtk v.vtk --ply v.ply \
  --singularity-points p.txt --streamlines s.vtk --streamline-seeds 30
check 0 bunny00_n4_75k_faces "$data/bunny00.off" --singularities "$inputs/bunny00.sing" --n 4
check 0 homer_n1_index_2 "$data/homer.off" --singularities "$inputs/homer.sing"
check 0 fandisk_n4_unit "$data/fandisk.off" --singularities "$inputs/quarters_0_to_7.sing" --n 4 --weights unit
check 0 sphere_ply_n4 "$data/sphere.ply" --singularities "$inputs/quarters_0_to_7.sing" --n 4
check 0 sphere_stl_n2 "$data/sphere.stl" --singularities "$inputs/sphere_stl_halves.sing" --n 2 --vtk v.vtk
# high genus
check 0 cheese_genus133_n1 "$data/cheese.off" --singularities "$inputs/cheese.sing"
check 0 turbine_genus11_n2 "$data/turbine.off" --singularities "$inputs/turbine.sing" --n 2
check 0 anchor_genus4_n4_streamlines "$data/anchor.off" --singularities "$inputs/anchor.sing" --n 4 \
  --streamlines s.vtk --singularity-points p.txt
check 0 elephant_with_holes_genus3_n2 "$data/elephant-with-holes.off" --n 2
# bordered (the solver picks the boundary indices)
check 0 holes_n2_unit "$data/holes.off" --n 2 --weights unit --vtk v.vtk --ply v.ply
check 0 lion_n4_aligned "$data/lion.off" --n 4 --align-boundary
check 0 mech_holes_shark_n1 "$data/mech-holes-shark.off"
check 0 chinese_dragon_n4 "$data/ChineseDragon-10kv.off" --n 4
check 0 triangle_n1 "$data/triangle.off"
# several components
check 0 alstom_6_components_n2 "$data/ALSTOM_TEST4.off" --n 2
check 0 boeing_122_components_n1 "$data/boeing.off"
check 0 blobby_3cc_n4_streamlines "$data/blobby_3cc.off" --n 4 --streamlines s.vtk
check 0 knot2_2_tori_n4_unit "$data/knot2.off" --n 4 --weights unit
# the command line's other forms: --name=value, default output names
compare 0 pipe_n3_equals_syntax PROGRAM "$data/pipe.off" --n=3 --weights=unit --connection=c.txt --field=f.txt
compare 0 rotor_default_output_names PROGRAM "$data/rotor.off" --n 2
# design controls from files written above
check 0 head_constraints_n4 "$data/head.off" --constraints "$inputs/head.dirs" --n 4
check 0 pinion_constraints_guidance_n2 "$data/pinion.off" --constraints "$inputs/pinion.dirs" \
  --guidance "$inputs/pinion_guides.dirs" --guidance-weight 0.75 --n 2
check 0 dino_guidance_n1 "$data/dino.off" --singularities "$inputs/dino.sing" --guidance "$inputs/dino_guides.dirs"
check 0 holes_boundary_indices_n4 "$data/holes.off" --boundary-indices "$inputs/holes_boundary.idx" --n 4
check 0 lion_boundary_indices_aligned_n2 "$data/lion.off" --boundary-indices "$inputs/lion_boundary.idx" \
  --align-boundary --n 2
# faces of four or more corners
check 0 torus_quad_triangulate_n4 "$data/torus_quad.off" --triangulate --n 4
check 0 cube_quad_triangulate_n4 "$data/cube_quad.off" --triangulate --singularities "$inputs/quarters_0_to_7.sing" \
  --n 4
check 0 mpi_9_gons_triangulate_n1 "$data/mpi.off" --triangulate
check 0 double_torus_triangulate_n2 "$data/double-torus-example.off" --triangulate \
  --singularities "$inputs/double_torus.sing" --n 2
# bad inputs (exit status 1) and bad command lines (2)
check 1 error_poincare_hopf "$data/cow.off" --singularities "$inputs/cow_one.sing"
check 1 error_vertex_out_of_range "$data/cow.off" --singularities "$inputs/cow_missing_vertex.sing"
check 1 error_quads_without_triangulate "$data/torus_quad.off" --n 4
check 1 error_missing_mesh "$data/no_such_mesh.off"
check 2 usage_flag_with_value "$data/pig.off" --progress=1
check 2 usage_flag_twice "$data/pig.off" --triangulate --align-boundary --triangulate
check 2 usage_option_twice "$data/pig.off" --n 2 --n=4
check 2 usage_bad_values "$data/pig.off" --guidance-weight 1e999 --streamline-seeds 0 --weights cotan
compare 2 usage_same_output PROGRAM "$data/pig.off" --connection x.txt --field ./x.txt
check 2 usage_output_overwrites_input "$examples/sphere.off" --singularities "$inputs/sphere_copy.sing" \
  --vtk "$inputs/sphere_copy.sing"
compare 0 usage_help_wins PROGRAM "$data/pig.off" --n 0 --help
compare 0 usage_version_as_a_value PROGRAM "$data/pig.off" --connection --version
compare 2 usage_empty_mesh_name PROGRAM ""

echo "$cases cases: $same same, $different different, $not_run not run ($base_rev against the working tree," \
  "$((SECONDS - start)) s)"
[ "$different" = 0 ] && [ "$not_run" = 0 ]
