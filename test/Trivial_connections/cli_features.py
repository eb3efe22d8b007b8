#!/usr/bin/env python3
# The program's --align-features (issue 37), from its files alone:
#  - fandisk (CGAL's data) with --align-features --n 4 --auto: the connection and field pass the independent checker
#    (../shared/tools/check_connection.py) with the singularities the program used, and every pin it used
#    (--write-constraints) is followed: check_constraints.py's angle residual <= 1e-9, and the weighted divergence
#    vanishes on every other face; every pinned face is beside an edge sharper than 30 degrees (recomputed here) but
#    the inner faces of its cusp's tongue (the sector rule, counted by the report), and every face beside one is
#    pinned but those of the dropped edges the report counts; the feature lines file holds the kept sharp edges;
#  - the user's constraint file wins on the faces it names; --refine and --singularities combine;
#  - a bad threshold is a usage error (status 2); a mesh without sharp edge gets a note and no pin.
# Exits 77 (skipped) when CGAL's data is absent.
# Usage: cli_features.py PROGRAM CHECKER CGAL_DATA_DIR SPHERE_OFF OUT_DIR
import os, re, subprocess, sys
import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from check_constraints import read_off  # noqa: E402

program, checker, data, sphere, out = sys.argv[1:6]
mesh = os.path.join(data, "fandisk.off")
if not os.path.exists(mesh):
    print(f"cli_features.py: {mesh} not found (bash scripts/fetch_cgal_data.sh): skipped")
    sys.exit(77)
os.makedirs(out, exist_ok=True)
python = sys.executable
failures = []


def check(cond, what):
    print(("ok: " if cond else "FAIL: ") + what)
    if not cond:
        failures.append(what)


def run(args, status=0):
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != status:
        print(p.stdout, p.stderr)
        sys.exit(f"cli_features.py: {' '.join(args)}: status {p.returncode}, expected {status}")
    return p


def sharp_faces(path, degrees):
    V, F = read_off(path)
    F = np.array(F)
    N = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    N /= np.linalg.norm(N, axis=1)[:, None]
    side = {}
    for f, t in enumerate(F):
        for k in range(3):
            side[(t[k], t[(k + 1) % 3])] = f
    beside, sharp = set(), 0
    for (i, j), f in side.items():
        g = side.get((j, i))
        if g is None or i > j:
            continue
        if np.degrees(np.arctan2(np.linalg.norm(np.cross(N[f], N[g])), N[f] @ N[g])) > degrees:
            beside |= {f, g}
            sharp += 1
    return beside, sharp


def read_pins(path):
    pins = {}
    for line in open(path):
        w = line.split("#", 1)[0].split()
        if w:
            pins[int(w[0])] = np.array([float(x) for x in w[1:4]])
    return pins


def check_outputs(tag, extra_constraints=None):
    d = os.path.join(out, tag)
    used_sing, pins, conn, field = (os.path.join(d, x) for x in ("used.sing", "pins.dirs", "c.txt", "f.txt"))
    r = run([python, checker, mesh, "--connection", conn, "--field", field, "--singularities", used_sing,
             "--n", "4", "--no-optimality"])
    check("PASS" in r.stdout or r.returncode == 0, f"{tag}: check_connection.py passes")
    r = run([python, os.path.join(here, "check_constraints.py"), mesh, "--connection", conn, "--field", field,
             "--constraints", pins, "--n", "4"])
    m = re.search(r"target_err=(\S+)", r.stdout)
    check(m is not None and float(m.group(1)) <= 1e-9, f"{tag}: every pin followed (angle residual {m and m.group(1)})")
    check("PASS" in r.stdout, f"{tag}: check_constraints.py passes (optimality off the pins)")
    return read_pins(pins)


# 1. fandisk, --align-features --n 4 --auto
d = os.path.join(out, "auto")
os.makedirs(d, exist_ok=True)
r = run([program, mesh, "--align-features", "--n", "4", "--auto", "--write-singularities", f"{d}/used.sing",
         "--write-constraints", f"{d}/pins.dirs", "--feature-lines", f"{d}/lines.vtk", "--connection", f"{d}/c.txt",
         "--field", f"{d}/f.txt"])
print(r.stdout)
line = next((l for l in r.stdout.splitlines() if l.startswith("features:")), "")
m = re.search(r"(\d+) sharp edges, (\d+) curves.*?(\d+) faces beside them .*?, (\d+) pinned", line)
check(m is not None, "a features: line in the report")
dropped = re.search(r"(\d+) isolated short ones dropped, (\d+) edges", line)
dropped_edges = int(dropped.group(2)) if dropped else 0
pins = check_outputs("auto")
beside, sharp = sharp_faces(mesh, 30)
check(int(m.group(1)) == sharp, f"the report's sharp edges ({m.group(1)}) are those recomputed here ({sharp})")
sector = re.search(r"\((\d+) cusps?: (\d+) faces by the sector rule\)", line)
sector_faces = int(sector.group(2)) if sector else 0
check(sector is not None and sector.group(1) == "1", "fandisk's one cusp is reported (a crease turning back)")
check(0 < len(set(pins) - beside) <= sector_faces,
      f"every pinned face is beside a sharp edge but faces of the cusp's tongue ({len(set(pins) - beside)}, at most "
      f"the {sector_faces} faces of the sector rule)")
check(len(beside - set(pins)) <= 2 * dropped_edges,
      f"every face beside a sharp edge is pinned ({len(set(pins) & beside)} of {len(beside)}, {dropped_edges} edges dropped)")
check(len(pins) == int(m.group(4)), "--write-constraints holds the pinned faces of the report")
lines = open(f"{d}/lines.vtk").read()
check(re.search(rf"^LINES {sharp - dropped_edges} {3 * (sharp - dropped_edges)}$", lines, re.M) is not None,
      "--feature-lines holds the kept sharp edges")

# 2. the user's constraints win; --refine and a threshold
d = os.path.join(out, "user")
os.makedirs(d, exist_ok=True)
some = sorted(pins)[:3]
with open(f"{d}/user.dirs", "w") as f:
    for face in some:
        V, F = read_off(mesh)
        a, b, c = (V[i] for i in F[face])
        f.write(f"{face} {b[0] - c[0]} {b[1] - c[1]} {b[2] - c[2]}\n")   # another edge of the face
r = run([program, mesh, "--align-features", "35", "--n", "4", "--auto", "--refine", "--constraints", f"{d}/user.dirs",
         "--write-singularities", f"{d}/used.sing", "--write-constraints", f"{d}/pins.dirs",
         "--connection", f"{d}/c.txt", "--field", f"{d}/f.txt"])
check("threshold 35 degrees" in r.stdout and f"3 left to {d}/user.dirs" in r.stdout,
      "the threshold is read and the file's faces are left to it")
used = check_outputs("user")
user = read_pins(f"{d}/user.dirs")
check(all(np.allclose(used[f], user[f]) for f in some), "the file's targets are the ones used on its faces")

# 3. bad thresholds, and a mesh without sharp edge
for bad in (["--align-features", "200"], ["--align-features=-1"], ["--align-features=abc"], ["--align-features", "nan"]):
    p = run([program, mesh] + bad + ["--connection", f"{out}/x.txt", "--field", f"{out}/y.txt"], status=2)
    check("--align-features expects an angle" in p.stderr, f"{' '.join(bad)}: usage error ({p.stderr.strip()})")
p = run([program, sphere, "--align-features", "--n", "4", "--auto", "--connection", f"{out}/s.c.txt",
         "--field", f"{out}/s.f.txt"])
check("note: no edge is sharper than 30 degrees" in p.stderr and "no sharp edge, no face pinned" in p.stdout,
      "a smooth mesh: a note, no pin, status 0")

if failures:
    sys.exit(f"cli_features.py: {len(failures)} check(s) failed")
print("cli_features.py: all checks passed")
