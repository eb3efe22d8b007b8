#!/usr/bin/python3
"""The program's automatic placement where it used to fail (issue 36), checked from its outputs:
  - several components: CGAL's knot and femur in one OFF file, in both orders, get what each gets alone (the same
    singularities at the same points, energies that add up), with --no-refine (the smoothest field's singularities);
  - small shapes (one triangle, two, a strip, a tetrahedron, and a triangle beside a large mesh) get a field, which
    the independent checker (check_connection.py) accepts against the singularities written;
  - --progress names the placement with its iterations, the curvature guide and the refinement;
  - --auto refines by default: its report says so (the `design:` line), its energy is at most that of
    --auto --no-refine, --auto --refine [--cancel-pairs] (old command lines) give the same, and the contradicting
    or misplaced --no-refine is a usage error (exit status 2).
Usage: cli_placement.py PROGRAM CHECKER DATA_DIR OUT_DIR (DATA_DIR: CGAL's data/meshes)."""
import os
import re
import subprocess
import sys

from check_constraints import read_off  # (V as floats, F), beside this script

program, checker, data, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
failures = []


def check(condition, what):
    print(("ok: " if condition else "FAIL: ") + what)
    if not condition:
        failures.append(what)


def write_off(path, parts):
    """the parts (V, F) as one OFF file; repr() of each coordinate reads back to the same float"""
    V, F = [], []
    for v, f in parts:
        offset = len(V)
        V += [tuple(float(c) for c in p) for p in v]
        F += [tuple(i + offset for i in t) for t in f]
    with open(path, "w") as out_file:
        out_file.write("OFF\n%d %d 0\n" % (len(V), len(F)))
        out_file.writelines(" ".join(map(repr, p)) + "\n" for p in V)
        out_file.writelines("3 %d %d %d\n" % t for t in F)


def run(mesh, name, *options):
    """runs the program with --auto on mesh; returns (report, stderr, the singularities as {point: index})"""
    prefix = os.path.join(out, name)
    args = [program, mesh, "--auto", "--connection", prefix + ".c.txt", "--field", prefix + ".f.txt",
            "--write-singularities", prefix + ".sing", *options]
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        check(False, "%s: exit status %d: %s" % (name, r.returncode, r.stderr.strip()))
        return None, r.stderr, {}
    V = [tuple(float(c) for c in p) for p in read_off(mesh)[0]]
    placed = {}
    with open(prefix + ".sing") as f:
        for line in f:
            t = line.split("#")[0].split()
            if t:
                placed[V[int(t[0])]] = t[1]
    return r.stdout, r.stderr, placed


def number(report, pattern):
    m = re.search(pattern, report)
    return float(m.group(1)) if m else float("nan")


def checked_by_the_checker(mesh, name, n, optimality=True):
    """the checker on the outputs; without optimality where constraints (an aligned boundary) take part"""
    prefix = os.path.join(out, name)
    r = subprocess.run([sys.executable, checker, mesh, "--connection", prefix + ".c.txt", "--field", prefix + ".f.txt",
                        "--singularities", prefix + ".sing", "--n", str(n)] + ([] if optimality else ["--no-optimality"]),
                       capture_output=True, text=True)
    said = " ".join((r.stdout + r.stderr).split())
    check(r.returncode == 0 and said.endswith("PASS"), "%s: the checker says %s" % (name, said[-300:]))


# ---- several components: the smoothest field's singularities (--no-refine); a refinement is not bound to give each
# component what it gets alone
knot, femur = read_off(os.path.join(data, "knot.off")), read_off(os.path.join(data, "femur.off"))
for n in (1, 4):
    alone, energy, field_energy = {}, 0.0, 0.0
    for name, part in (("knot", knot), ("femur", femur)):
        path = os.path.join(out, name + ".off")
        write_off(path, [part])
        report, _, placed = run(path, "%s_n%d" % (name, n), "--n", str(n), "--no-refine")
        if report is None:
            continue
        alone.update(placed)
        energy += number(report, r"\nenergy: ([0-9.e+-]+)")
        field_energy += number(report, r"its connection energy ([0-9.e+-]+)")
    for name, parts in (("knot_femur", [knot, femur]), ("femur_knot", [femur, knot])):
        path = os.path.join(out, name + ".off")
        write_off(path, parts)
        report, _, placed = run(path, "%s_n%d" % (name, n), "--n", str(n), "--no-refine")
        if report is None:
            continue
        check(placed == alone, "%s, n = %d: %d singularities, %d for the parts alone, %d differ" % (
            name, n, len(placed), len(alone), len(set(placed.items()) ^ set(alone.items()))))
        e, fe = number(report, r"\nenergy: ([0-9.e+-]+)"), number(report, r"its connection energy ([0-9.e+-]+)")
        check(abs(e - energy) <= 1e-8 * energy, "%s, n = %d: energy %.10g, the parts' sum %.10g" % (name, n, e, energy))
        check(abs(fe - field_energy) <= 1e-8 * field_energy,
              "%s, n = %d: the smooth field's energy %.10g, the parts' sum %.10g" % (name, n, fe, field_energy))

# ---- small shapes
triangle = ([(0, 0, 0), (1, 0, 0), (0.3, 0.8, 0)], [(0, 1, 2)])
two = ([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0.4)], [(0, 1, 2), (1, 3, 2)])
tetrahedron = ([(1, 1, 1), (-1, -1, 1), (-1, 1, -1), (1, -1, -1)], [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)])
strip = ([(i, 0.1 * (i % 3), z) for z in (0, 1) for i in range(9)],
         [t for i in range(8) for t in ((i, i + 1, i + 9), (i + 1, i + 10, i + 9))])
far_triangle = ([(x + 3, y, z) for x, y, z in triangle[0]], triangle[1])
shapes = {"triangle": [triangle], "two_triangles": [two], "strip": [strip], "tetrahedron": [tetrahedron],
          "knot_and_a_triangle": [knot, far_triangle]}
for name, parts in shapes.items():
    path = os.path.join(out, name + ".off")
    write_off(path, parts)
    for n in (1, 2, 4):
        # () refines (the default), ("--no-refine",) does not
        for options in ((), ("--align-boundary",), ("--align-curvature",), ("--no-refine",)):
            if "--align-curvature" in options and n % 2:
                continue
            case = "%s_n%d%s" % (name, n, "".join(o.replace("--", "_") for o in options))
            report, _, placed = run(path, case, "--n", str(n), *options)
            if report is None:
                continue
            check(True, "%s: %d singularities" % (case, len(placed)))
            # the checker needs an interior edge (it takes minima over them); guided: not the unguided optimum
            if name != "triangle" and "--align-curvature" not in options:
                checked_by_the_checker(path, case, n, optimality="--align-boundary" not in options)
    # a regular tetrahedron carries a parallel line and cross field with four 1/2 singularities
    if name == "tetrahedron":
        for n in (2, 4):
            _, _, placed = run(path, "tetrahedron_n%d_again" % n, "--n", str(n), "--no-refine")
            check(sorted(placed.values()) == ["1/2"] * 4, "tetrahedron, n = %d: %s" % (n, sorted(placed.values())))
# the knot beside a triangle: the knot's own singularities (those of the smoothest field)
_, _, with_triangle = run(os.path.join(out, "knot_and_a_triangle.off"), "knot_and_a_triangle_n4_again", "--n", "4",
                          "--no-refine")
_, _, knot_alone = run(os.path.join(out, "knot.off"), "knot_n4_again", "--n", "4", "--no-refine")
check(with_triangle == knot_alone, "the knot beside a triangle: %d singularities, %d alone" % (
    len(with_triangle), len(knot_alone)))

# ---- --progress names every phase of the design (--auto refines without being asked)
report, err, _ = run(os.path.join(data, "fandisk.off"), "fandisk_progress", "--n", "4", "--align-curvature",
                     "--progress")
for phase, detail in (("curvature guide", r"\d+ guided faces"),
                      ("placement", r"curvature-aligned field(, \d+ iterations)?, \d+ singularities"),
                      ("refinement", r"\d+ moves in \d+ trial solves")):
    check(re.search(r"\] %s \.\.\. done \( *[0-9.]+ s; %s" % (phase, detail), err) is not None,
          "--progress shows '%s' with what it did" % phase)
report, err, _ = run(os.path.join(data, "fandisk.off"), "fandisk_progress_smooth", "--n", "4", "--progress")
check(re.search(r"\] placement \.\.\. done \( *[0-9.]+ s; smoothest field, \d+ iterations, \d+ singularities", err)
      is not None, "--progress shows the smoothest field's iterations")

# ---- --auto refines by default
DESIGN_REFINED = "design: the singularities of the %s field, refined to a local minimum of the energy"
DESIGN_UNREFINED = "design: the singularities of the %s field, not refined (--no-refine)"


def design_line(report):
    m = re.search(r"^design: .*$", report or "", re.M)
    return m.group(0) if m else "no design line"


by_default = {}  # case -> (report, singularities) of --auto
for mesh, n in (("fandisk.off", 4), ("knot.off", 1), ("knot.off", 4), ("pig.off", 4)):
    path = os.path.join(data, mesh)
    case = "%s_n%d" % (mesh[:-4], n)
    refined, _, placed = run(path, case + "_default", "--n", str(n))
    unrefined, _, smoothest = run(path, case + "_no_refine", "--n", str(n), "--no-refine")
    if refined is None or unrefined is None:
        continue
    by_default[case] = refined, placed
    check(design_line(refined).startswith(DESIGN_REFINED % "smoothest"), "%s --auto: %s" % (case, design_line(refined)))
    check(design_line(unrefined) == DESIGN_UNREFINED % "smoothest",
          "%s --auto --no-refine: %s" % (case, design_line(unrefined)))
    check(re.search(r"^refinement: ", unrefined, re.M) is None, "%s --auto --no-refine: no refinement line" % case)
    # the scripts' reading of the count is unchanged: the singularities written
    check(number(refined, r"(?m)^singularities: ([0-9]+)") == len(placed) and
          number(unrefined, r"(?m)^singularities: ([0-9]+)") == len(smoothest),
          "%s: 'singularities: N' gives %d refined, %d with --no-refine" % (case, len(placed), len(smoothest)))
    e, e0 = number(refined, r"(?m)^energy: ([0-9.e+-]+)"), number(unrefined, r"(?m)^energy: ([0-9.e+-]+)")
    check(e <= e0 * (1 + 1e-12), "%s: energy %.10g refined, %.10g with --no-refine" % (case, e, e0))
    checked_by_the_checker(path, case + "_default", n)
# the old command lines mean the same as --auto (the same singularities, the same energy)
fandisk = os.path.join(data, "fandisk.off")
default, default_placed = by_default.get("fandisk_n4", ("", {}))
for options in (("--refine",), ("--refine", "--cancel-pairs"), ("--cancel-pairs",)):
    case = "fandisk_n4" + "".join(o.replace("--", "_") for o in options)
    report, _, placed = run(fandisk, case, "--n", "4", *options)
    check(report is not None and placed == default_placed and
          number(report, r"(?m)^energy: ([0-9.e+-]+)") == number(default, r"(?m)^energy: ([0-9.e+-]+)"),
          "--auto %s gives what --auto gives (%d singularities)" % (" ".join(options), len(placed)))
aligned, _, _ = run(fandisk, "fandisk_n4_curvature_no_refine", "--n", "4", "--align-curvature", "--no-refine")
check(design_line(aligned) == DESIGN_UNREFINED % "curvature-aligned",
      "--auto --align-curvature --no-refine: %s" % design_line(aligned))
# usage errors: one line, exit status 2, no output written
for args, words in ((["--no-refine"], "--no-refine is an option of --auto"),
                    (["--auto", "--no-refine", "--refine"], "--no-refine and --refine contradict each other"),
                    (["--auto", "--refine", "--no-refine"], "--no-refine and --refine contradict each other"),
                    (["--auto", "--no-refine", "--cancel-pairs"], "--no-refine and --cancel-pairs contradict"),
                    (["--auto", "--no-refine", "--no-refine"], "option --no-refine given twice"),
                    (["--cancel-pairs"], "--cancel-pairs is an option of --refine")):
    prefix = os.path.join(out, "usage_error")
    for f in (prefix + ".c.txt", prefix + ".f.txt"):
        if os.path.exists(f):
            os.remove(f)
    r = subprocess.run([program, fandisk, *args, "--connection", prefix + ".c.txt", "--field", prefix + ".f.txt"],
                       capture_output=True, text=True)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 2 and len(lines) == 1 and words in lines[0] and not os.path.exists(prefix + ".c.txt"),
          "%s: exit status %d, %s" % (" ".join(args), r.returncode, r.stderr.strip()))

if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("all checks passed")
