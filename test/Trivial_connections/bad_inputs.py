"""The bad-input corpus of the program: every case is written by this script (no third-party file), run
through the program, and must give its exact exit status and the words that say what is wrong, on one
line of stderr, with no output file left behind; the accepted edge cases must give finite outputs.
Used by ctest (bad_input_corpus). The corpus stays in OUT_DIR/corpus/CASE/ for inspection.
Usage: bad_inputs.py PROGRAM OUT_DIR
Exit status 0 when every case behaves, 1 otherwise (each failure is listed).
"""
import atexit
import math
import os
import shutil
import subprocess
import sys
import tempfile

program, out = sys.argv[1], os.path.abspath(sys.argv[2])
corpus = os.path.join(out, "corpus")
shutil.rmtree(corpus, ignore_errors=True)
os.makedirs(corpus)

TET_V = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
TET_F = "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n"
TET = "OFF\n4 4 0\n" + TET_V + TET_F
# a flat square of 2 x 2 quads split into 8 triangles: vertex 4 is the only interior vertex
DISK = ("OFF\n9 8 0\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n0 2 0\n1 2 0\n2 2 0\n"
        "3 0 1 4\n3 0 4 3\n3 1 2 5\n3 1 5 4\n3 3 4 7\n3 3 7 6\n3 4 5 8\n3 4 8 7\n")
TWO_TETS = ("OFF\n8 8 0\n" + TET_V + "5 0 0\n6 0 0\n5 1 0\n5 0 1\n" + TET_F +
            "3 4 6 5\n3 4 5 7\n3 5 6 7\n3 6 4 7\n")

failures = []

# Permissions do not stop root: as root (CI), the cases about unreadable files and unwritable folders run the
# program as the user nobody (setpriv, util-linux), which then cannot read a file of mode 000 nor write into
# the case's folder (root's, mode 755).
# The build tree may be where nobody cannot go (/root): those cases and a copy of the program are in a
# temporary folder of mode 755 under the system's temporary directory.
AS_OTHER_USER = []
other_root, other_program = None, program
if os.geteuid() == 0:
    other_root = tempfile.mkdtemp(prefix="tc_bad_inputs_")
    atexit.register(shutil.rmtree, other_root, True)
    os.chmod(other_root, 0o755)
    other_program = os.path.join(other_root, "trivial_connections")
    shutil.copy2(program, other_program)
    probe = ["setpriv", "--reuid=nobody", "--regid=nogroup", "--clear-groups", other_program, "--version"]
    try:
        if subprocess.run(probe, capture_output=True, timeout=60).returncode == 0:
            AS_OTHER_USER = probe[:4]
    except OSError:
        pass


def case(name, files, args, status, words=(), outputs=("c.txt", "f.txt"), unreadable=(), as_other_user=False):
    """Writes `files` (name -> content) into the case's folder, runs the program with `args` (file names
    are replaced by their paths) and --connection/--field outputs there, and checks the outcome.
    `unreadable`: files made mode 000; `as_other_user`: as root, run as nobody (see AS_OTHER_USER)."""
    if (unreadable or as_other_user) and os.geteuid() == 0 and not AS_OTHER_USER:
        print("skipped %-27s as root, and setpriv cannot run the program as nobody" % name)
        return
    other = (unreadable or as_other_user) and os.geteuid() == 0
    folder = os.path.join(other_root if other else corpus, name)
    os.makedirs(folder)
    for f, content in files.items():
        with open(os.path.join(folder, f), "w") as h:
            h.write(content)
    for f in unreadable:
        os.chmod(os.path.join(folder, f), 0)
    if as_other_user and os.geteuid() != 0:
        os.chmod(folder, 0o555)  # not root: the folder itself is made read-only
    argv = (AS_OTHER_USER if other else []) + [other_program if other else program] + \
        [os.path.join(folder, a) if a in files else a for a in args]
    out_paths = [os.path.join(folder, o) for o in outputs]
    if outputs:
        argv += ["--connection", out_paths[0], "--field", out_paths[1]]
    run = subprocess.run(argv, capture_output=True, text=True, timeout=120)
    os.chmod(folder, 0o755)
    for f in unreadable:
        os.chmod(os.path.join(folder, f), 0o644)
    err = run.stderr.strip()
    problems = []
    if run.returncode != status:
        problems.append("exit status %d, expected %d" % (run.returncode, status))
    if status != 0:
        if len(err.splitlines()) != 1:
            problems.append("stderr is not one line: %r" % err)
        for w in words:
            if w not in err:
                problems.append("message lacks %r" % w)
        left = [p for p in out_paths if os.path.exists(p)] + \
               [f for f in os.listdir(folder) if f.startswith(".") or ".tmp" in f]
        if left:
            problems.append("files left behind: %s" % left)
    else:
        for p in out_paths:
            for line in open(p):
                if line.startswith("#"):
                    continue
                if any(not math.isfinite(float(t)) for t in line.split()):
                    problems.append("%s has a non-finite value: %s" % (os.path.basename(p), line.strip()))
                    break
    if problems:
        failures.append("%s: %s (stderr: %s)" % (name, "; ".join(problems), err))
    else:
        print("ok %-32s %s" % (name, err if err else "accepted"))


# ---- meshes
case("empty_mesh", {"m.off": "OFF\n0 0 0\n"}, ["m.off"], 1, ["m.off", "no face"])
case("vertices_without_faces", {"m.off": "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"}, ["m.off"], 1,
     ["no face", "3 vertices, 0 faces"])
case("quad_face", {"m.off": "OFF\n5 4 0\n" + TET_V + "1 1 1\n3 0 2 1\n4 0 1 4 3\n3 1 2 3\n3 2 0 3\n"},
     ["m.off"], 1, ["face 1 has 4 vertices", "--triangulate"])
case("two_vertex_face", {"m.off": "OFF\n4 2 0\n" + TET_V + "3 0 2 1\n2 0 1\n"}, ["m.off"], 1, ["face 1", "2 vertices"])
case("non_manifold_edge", {"m.off": "OFF\n6 3 0\n" + TET_V + "1 1 1\n-1 0 0\n3 0 1 2\n3 1 0 3\n3 0 1 4\n"},
     ["m.off"], 1, ["non-manifold edge", "shared by 3 faces"])
case("non_manifold_vertex", {"m.off": "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n3 0 1 2\n3 0 3 4\n"},
     ["m.off"], 1, ["non-manifold vertex 0", "2 separate fans"])
case("inconsistent_orientation", {"m.off": "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 2 3\n"},
     ["m.off"], 1, ["inconsistent orientation", "faces 0 and 1"])
case("zero_area_face", {"m.off": "OFF\n4 4 0\n0 0 0\n1 0 0\n2 0 0\n0 0 1\n" + TET_F}, ["m.off"], 1,
     ["face 0 is degenerate", "zero area"])
case("repeated_vertex_in_face", {"m.off": "OFF\n4 4 0\n" + TET_V + "3 0 2 1\n3 0 1 3\n3 1 1 3\n3 2 0 3\n"},
     ["m.off"], 1, ["face 2", "same vertex"])
# two vertices at the same place, one face using both: a zero-length edge
case("duplicate_vertex_in_a_face", {"m.off": "OFF\n4 2 0\n0 0 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"},
     ["m.off"], 1, ["face 0 is degenerate"])
for bad in ("nan", "inf", "-inf", "1e999"):
    case("coordinate_" + bad.replace("-", "minus_"), {"m.off": "OFF\n4 4 0\n0 0 0\n1 0 0\n0 %s 0\n0 0 1\n" % bad + TET_F},
         ["m.off"], 1, ["m.off:5", "vertex 2", "not a finite number"])
case("vertex_index_out_of_range", {"m.off": "OFF\n4 4 0\n" + TET_V + "3 0 2 1\n3 0 1 3\n3 1 2 7\n3 2 0 3\n"},
     ["m.off"], 1, ["face 2", "vertex 7", "4 vertices"])
case("truncated_mesh", {"m.off": "OFF\n4 4 0\n0 0 0\n1 0 0\n"}, ["m.off"], 1, ["unexpected end of file", "4 vertices"])
case("garbage_mesh", {"m.off": "this is not a mesh\n"}, ["m.off"], 1, ["m.off"])
case("garbage_obj", {"m.obj": "v 0 0 0\nv 1 0 zero\nf 1 2 3\n"}, ["m.obj"], 1, ["m.obj"])
# found by the fuzzer (test/fuzz/findings): files CGAL's readers must not see
case("off_negative_index", {"m.off": "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n"}, ["m.off"], 1,
     ["m.off:6", "face 0", "vertex -1"])
case("off_face_size_beyond_its_line", {"m.off": "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000000 0 1 2\n"}, ["m.off"], 1,
     ["m.off:6", "face 0", "expected 1000000000 vertex indices"])
case("off_face_size_overflows", {"m.off": "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n9999999999999999999 0 1 2\n"},
     ["m.off"], 1, ["m.off:6", "face 0"])
case("off_huge_vertex_count", {"m.off": "\nOFF\n1088749890\n3 5"}, ["m.off"], 1, ["m.off"])
case("ply_element_count_negative", {"m.ply": "ply\nformat ascii 1.0\nelement foo -1\nend_header\n"}, ["m.ply"], 1,
     ["m.ply:3", "non-negative integer"])
case("ply_element_without_property", {"m.ply": "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n"}, ["m.ply"], 1,
     ["m.ply:4", "no property"])
case("ply_property_before_element", {"m.ply": "ply\nformat ascii 1.0\nproperty double x\nend_header\n"}, ["m.ply"], 1,
     ["m.ply:3", "a property before any element"])
case("ply_without_end_header", {"m.ply": "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\n"}, ["m.ply"], 1,
     ["no end_header"])
case("off_counts_line_extra_numbers", {"m.off": "OFF\n3 1 0 0 0 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 1 2\n"}, ["m.off"], 1,
     ["m.off:2", "three integers on one line"])
case("off_binary", {"m.off": "OFF BINARY\n\x00\x00\x00\x03\x00\x00\x00\x01\x00\x00\x00\x00"}, ["m.off"], 1,
     ["m.off:1", "binary OFF is not supported"])
case("off_homogeneous", {"m.off": "4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1\n1000000000 0 1 2\n"}, ["m.off"], 1,
     ["m.off:1", "'4OFF'", "not supported"])
case("off_n_dimensional", {"m.off": "nOFF\n3\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 1 2\n"}, ["m.off"], 1,
     ["m.off:1", "'nOFF'", "not supported"])
PLY_HEAD = ("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 4\nproperty list uint int vertex_indices\nend_header\n")
case("ply_list_size_beyond_the_file", {"m.ply": PLY_HEAD + TET_V + "4000000000 0 1 2\n"}, ["m.ply"], 1,
     ["m.ply", "element 'face' item 0", "4000000000 items, more than the file holds"])
case("ply_float_vertex_indices", {"m.ply": PLY_HEAD.replace("uint int", "uchar float") + TET_V}, ["m.ply"], 1,
     ["m.ply", "'vertex_indices' is not a list of integers"])
case("ply_truncated_body", {"m.ply": PLY_HEAD + TET_V + "3 0 2 1\n"}, ["m.ply"], 1,
     ["m.ply", "element 'face' item 1", "unexpected end of file"])
# faces that CGAL's triangulation cannot take (it asserts, or crashes without assertions)
case("triangulate_self_crossing_pentagon", {"m.obj": "v 0 0 1\nv 0 1 1\nv 1 0 0\nv 1 1 1\nv 1 1 0\nf 1 2 3 4 5\n"},
     ["m.obj", "--triangulate"], 1, ["face 0 cannot be triangulated"])
case("triangulate_coincident_corners",
     {"m.obj": "v 0 0 0\nv 0 0 1\nv 0 1 0\nv 0 1 1\nv 1 0 0\nv 7 8 6\nv 0 0 0\nv 1 0 6\nf 1 3 4 8 7\n"},
     ["m.obj", "--triangulate"], 1, ["face 0 cannot be triangulated"])
# an icosahedron with one vertex 1e16 away (found by the fuzzer): double precision cannot carry its geometry to
# a residual of 1e-9, which is refused instead of returning a connection that is not trivial to 1e-9
case("ill_conditioned_far_vertex", {"m.off": 'OFF\n12 20 0\n-1 2.618033988749895 0\n1 1.618033988749895 0\n-1 -2.618033977499790 0\n1 -1.618033988749895 08749895 0\n-1 -1.618033977499790 0\n1 -1.618033988749895 0\n0 -1 10618033988749895\n0 1 1.618033988749895\n0 -1 -1.618033988749895\n0 1 -1.618033988749895\n1.61895 0 -1\n-1.618033988749895 0 1\n3 0 11 5\n3 0 5 1\n3 0 1 7\n3 0 7 10\n3 0 10 11\n3 1 5 9\n3 5 11 4\n3 11 10 2\n3 10 7 6\n3 7 1 8\n3 3 9 4\n3 3 4 2\n3 3 2 6\n3 3 6 8\n3 3 8 9\n3 4 9 5\n3 2 4 11\n3 6 2 10\n3 8 6 7\n3 9 8 1\n', "s.sing": '# vertex index\n0 2/5\n1 2/5\n2 2/5\n3 2/5\n4 2/5\n'},
     ["m.off", "--singularities", "s.sing", "--n", "5"], 1, ["too ill-conditioned", "residual"])
# CGAL's triangulate_face() reports success on this non-planar pentagon but leaves a larger face (an ASan
# stack-buffer-overflow in the package until it checked), and loops forever with assertions off: refused as
# far from planar
case("triangulate_leaves_a_larger_face",
     {"m.obj": "v 0 0 0\nv 0 0 2\nv 0 1 0\nv 0 1 1\nv 2 0 0\nv 1 0 1\nv 1 1 0\nv 1 1 1\nf 1 5 2 3 8\n"},
     ["m.obj", "--triangulate"], 1, ["face 0 cannot be triangulated"])
case("missing_mesh", {}, [os.path.join(out, "no_such_mesh.off")], 1, ["no_such_mesh.off", "no such file"])
case("mesh_is_a_directory", {}, [out], 1, ["it is a directory"])
case("unknown_extension", {"m.xyz": TET}, ["m.xyz"], 1, ["unknown file extension '.xyz'"])

# ---- singularities (tetrahedron: closed, chi = 2; disk: vertex 4 interior, the others on the boundary)
case("poincare_hopf_violated", {"m.off": TET, "s.sing": "0 1\n"}, ["m.off", "--singularities", "s.sing"], 1,
     ["Poincare-Hopf", "sum to 1, expected 2"])
case("poincare_hopf_per_component", {"m.off": TWO_TETS, "s.sing": "0 1\n1 1\n4 1\n5 1\n6 1\n"},
     ["m.off", "--singularities", "s.sing"], 1, ["Poincare-Hopf", "component 1", "expected 2"])
case("index_not_a_multiple", {"m.off": TET, "s.sing": "0 1\n1 1/3\n2 2/3\n"},
     ["m.off", "--singularities", "s.sing", "--n", "4"], 1, ["1/3", "not a multiple of 1/4"])
case("singularity_on_boundary", {"m.off": DISK, "s.sing": "0 1\n"}, ["m.off", "--singularities", "s.sing"], 1,
     ["vertex 0", "boundary"])
case("singularity_on_missing_vertex", {"m.off": TET, "s.sing": "9 2\n"}, ["m.off", "--singularities", "s.sing"], 1,
     ["s.sing:1", "vertex 9 does not exist", "4 vertices"])
case("singularity_on_isolated_vertex", {"m.off": "OFF\n5 4 0\n" + TET_V + "7 7 7\n" + TET_F, "s.sing": "4 1\n0 1\n"},
     ["m.off", "--singularities", "s.sing"], 1, ["vertex 4", "no face"])
case("duplicate_singularity_line", {"m.off": TET, "s.sing": "0 1\n# again\n0 1\n"},
     ["m.off", "--singularities", "s.sing"], 1, ["s.sing:3", "vertex 0 is listed twice", "lines 1 and 3"])
case("singularity_garbage", {"m.off": TET, "s.sing": "hello world\n"}, ["m.off", "--singularities", "s.sing"], 1,
     ["s.sing:1"])
case("singularity_truncated_line", {"m.off": TET, "s.sing": "0 1\n1\n"}, ["m.off", "--singularities", "s.sing"], 1,
     ["s.sing:2", "found 1 field"])
case("singularity_huge_index", {"m.off": TET, "s.sing": "0 99999999999999999999\n"},
     ["m.off", "--singularities", "s.sing"], 1, ["s.sing:1", "malformed singularity index"])
case("singularity_huge_vertex", {"m.off": TET, "s.sing": "99999999999999999999999 1\n"},
     ["m.off", "--singularities", "s.sing"], 1, ["s.sing:1"])
case("singularity_zero_denominator", {"m.off": TET, "s.sing": "0 1/0\n"}, ["m.off", "--singularities", "s.sing"], 1,
     ["s.sing:1", "zero denominator"])
case("singularity_negative_vertex", {"m.off": TET, "s.sing": "-1 2\n"}, ["m.off", "--singularities", "s.sing"], 1,
     ["s.sing:1", "negative vertex index"])
case("singularity_file_missing", {"m.off": TET}, ["m.off", "--singularities", os.path.join(out, "none.sing")], 1,
     ["none.sing"])
case("singularity_file_is_a_directory", {"m.off": TET}, ["m.off", "--singularities", out], 1, [out])

# ---- constraint files (more in cli_errors.sh)
case("constraint_garbage", {"m.off": TET, "c.dirs": "x y z w\n", "s.sing": "0 1\n1 1\n"},
     ["m.off", "--singularities", "s.sing", "--constraints", "c.dirs"], 1, ["c.dirs:1"])
case("constraint_truncated_line", {"m.off": TET, "c.dirs": "0 1 0\n", "s.sing": "0 1\n1 1\n"},
     ["m.off", "--singularities", "s.sing", "--constraints", "c.dirs"], 1, ["c.dirs:1", "four fields"])
case("constraint_huge_number", {"m.off": TET, "c.dirs": "0 1e999 0 0\n", "s.sing": "0 1\n1 1\n"},
     ["m.off", "--singularities", "s.sing", "--constraints", "c.dirs"], 1, ["c.dirs:1", "not a finite number"])
case("constraint_missing_face", {"m.off": TET, "c.dirs": "4 1 0 0\n", "s.sing": "0 1\n1 1\n"},
     ["m.off", "--singularities", "s.sing", "--constraints", "c.dirs"], 1, ["c.dirs:1", "face 4 does not exist"])

# ---- usage errors: exit status 2
for value, words in (("0", ["--n must be at least 1"]), ("-4", ["--n must be at least 1"]),
                     ("abc", ["--n expects a positive integer"]), ("99999999999", ["--n is too large"])):
    case("symmetry_order_" + value.replace("-", "minus_"), {"m.off": TET}, ["m.off", "--n", value], 2, words)
case("unknown_option", {"m.off": TET}, ["m.off", "--frobnicate"], 2, ["unknown option '--frobnicate'"])
case("option_without_value", {"m.off": TET}, ["m.off", "--connection"], 2, ["needs a value"], outputs=())
case("no_mesh", {}, [], 2, ["no mesh given"], outputs=())
# the automatic placement's options
case("align_curvature_odd_n", {"m.off": TET}, ["m.off", "--auto", "--align-curvature", "--n", "3"], 2,
     ["--align-curvature needs an even --n"])
case("align_curvature_and_guidance", {"m.off": TET, "g.dirs": "0 1 0 0\n"},
     ["m.off", "--align-curvature", "--n", "4", "--guidance", "g.dirs"], 2, ["cannot be combined"])
# --cancel-pairs needs --refine or --auto (which refines with it)
case("cancel_pairs_without_refine", {"m.off": TET, "s.sing": "0 1\n1 1\n"},
     ["m.off", "--singularities", "s.sing", "--cancel-pairs"], 2, ["--cancel-pairs is an option of --refine"])
# --no-refine: only with --auto, once, and not with what it undoes
case("no_refine_without_auto", {"m.off": TET, "s.sing": "0 1\n1 1\n"},
     ["m.off", "--singularities", "s.sing", "--no-refine"], 2, ["--no-refine is an option of --auto"])
case("no_refine_and_refine", {"m.off": TET}, ["m.off", "--auto", "--refine", "--no-refine"], 2,
     ["--no-refine and --refine contradict each other"])
case("no_refine_and_cancel_pairs", {"m.off": TET}, ["m.off", "--auto", "--no-refine", "--cancel-pairs"], 2,
     ["--no-refine and --cancel-pairs contradict each other"])
case("no_refine_twice", {"m.off": TET}, ["m.off", "--auto", "--no-refine", "--no-refine"], 2,
     ["option --no-refine given twice"])
case("alignment_strength_not_positive", {"m.off": TET}, ["m.off", "--auto", "--alignment-strength", "-3"], 2,
     ["--alignment-strength expects a positive finite number"])
case("auto_fixed_not_multiple", {"m.off": TET, "s.sing": "0 1/3\n"},
     ["m.off", "--auto", "--n", "4", "--singularities", "s.sing"], 1, ["1/3", "not a multiple of 1/4"])
case("write_singularities_over_input", {"m.off": TET, "s.sing": "0 2\n"},
     ["m.off", "--auto", "--singularities", "s.sing", "--write-singularities", "s.sing"], 2,
     ["would overwrite the singularity file"])

# ---- outputs that cannot be written: nothing at all is left
case("output_in_missing_directory", {"m.off": TET, "s.sing": "0 1\n1 1\n"},
     ["m.off", "--singularities", "s.sing", "--vtk", os.path.join(out, "no_dir", "f.vtk")], 1,
     ["cannot write", "no_dir"])
case("output_is_a_directory", {"m.off": TET, "s.sing": "0 1\n1 1\n"},
     ["m.off", "--singularities", "s.sing", "--vtk", corpus], 1, ["cannot write"])

case("unreadable_mesh", {"m.off": TET}, ["m.off"], 1, ["cannot read mesh file", "Permission denied"],
     unreadable=["m.off"])
case("unreadable_singularities", {"m.off": TET, "s.sing": "0 1\n1 1\n"}, ["m.off", "--singularities", "s.sing"], 1,
     ["cannot read singularity file", "Permission denied"], unreadable=["s.sing"])
case("unreadable_constraints", {"m.off": TET, "c.dirs": "0 1 0 0\n"}, ["m.off", "--constraints", "c.dirs"], 1,
     ["c.dirs", "Permission denied"], unreadable=["c.dirs"])
case("unwritable_output_folder", {"m.off": TET, "s.sing": "0 1\n1 1\n"}, ["m.off", "--singularities", "s.sing"], 1,
     ["cannot write", "Permission denied"], as_other_user=True)

# a needle: a square fanned around a vertex at height EPS above its bottom edge (aspect ratio about 1/EPS)
NEEDLE = "OFF\n5 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 {} 0\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n"
case("cap_too_flat_for_doubles", {"m.off": NEEDLE.format("1e-13")}, ["m.off"], 1,
     ["face 0 is degenerate", "nearly collinear", "1e-12 rad"])
case("cap_area_underflows", {"m.off": NEEDLE.format("1e-200")}, ["m.off"], 1, ["face 0 is degenerate"])

# ---- accepted edge cases: finite outputs
case("isolated_vertex_is_ignored", {"m.off": "OFF\n5 4 0\n" + TET_V + "7 7 7\n" + TET_F, "s.sing": "0 1\n1 1\n"},
     ["m.off", "--singularities", "s.sing"], 0)
# a vertex duplicated at the same place and used by different faces: a crack, i.e. a boundary, not an error
case("duplicate_vertex_makes_a_crack", {"m.off": "OFF\n5 4 0\n" + TET_V + "0 0 0\n3 0 2 1\n3 4 1 3\n3 1 2 3\n3 2 0 3\n"},
     ["m.off"], 0)
case("flat_disk_no_singularity", {"m.off": DISK}, ["m.off"], 0)
# huge indices: 2 pi k is rounded to ~1e-8 for k = 1e7, which would show in the residuals: beyond 1024 turns an
# index is refused; at the bound it is solved
case("huge_indices_are_refused", {"m.off": TET, "s.sing": "0 10000000\n1 -9999998\n"},
     ["m.off", "--singularities", "s.sing"], 1, ["vertex 0", "is too large (at most 1024"])
case("indices_at_the_bound_are_solved", {"m.off": TET, "s.sing": "0 1024\n1 -1022\n"},
     ["m.off", "--singularities", "s.sing"], 0)
# caps (an angle pi - 4e-9) are solved; so are needles (one tiny angle), even of aspect ratio 1e100
case("cap_aspect_1e9_is_solved", {"m.off": NEEDLE.format("1e-9")}, ["m.off"], 0)
case("needle_aspect_1e100_is_solved",
     {"m.off": "OFF\n5 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n1e-100 1e-100 0\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n"},
     ["m.off"], 0)
# integer coordinates in PLY (valid PLY; CGAL's own reader dereferences a null pointer on them)
case("ply_integer_coordinates", {"m.ply": PLY_HEAD.replace("float", "int") + TET_V + TET_F, "s.sing": "0 1\n1 1\n"},
     ["m.ply", "--singularities", "s.sing"], 0)

if failures:
    print("\n%d of the cases failed:" % len(failures))
    for f in failures:
        print("  " + f)
    sys.exit(1)
print("all cases behave")
