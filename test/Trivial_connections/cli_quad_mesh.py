#!/usr/bin/env python3
# The program's --quad-mesh (issue 43), from its files alone:
#  - a unit cube (each face 4 x 4 squares, two triangles each) with its eight corners +1/4, --n 4 --align-features
#    (the field along the cube's edges): with --quad-size 1/k the OBJ holds 6 k^2 quads, every edge in two quads
#    with opposite directions, V - E + F = 2, the eight corners of valence 3 and every other vertex 4, every quad
#    on one face of the cube facing out; the report line says the same (0 valence errors, 0 folds, 0 flipped,
#    Hausdorff distance <= H/2); --target-faces 54 gives H = 1/3 and 54 quads; with --quad-scale-smoothness the
#    same (the cube's field is a gradient already: the scale stays 1), and with --quad-cone-modes 30 (its map winds
#    right around every corner already);
#  - the usage errors (status 2): --quad-mesh without --n 4, without or with both of --quad-size and
#    --target-faces, a bad H, --quad-scale-smoothness or --quad-cone-modes without --quad-mesh, negative or (the
#    latter) infinite; the input errors (status 1): H so small that the mesh would exceed the bound, a
#    surface with border the field does not follow; no file written on any error;
#  - the open box with --align-boundary: 5 k^2 quads ending on its rim; the cube of 5 x 5 squares per face with
#    H = 0.4 and --align-features: its 12 edges are chains of quad edges.
# Usage: cli_quad_mesh.py PROGRAM OUT_DIR
import os, re, subprocess, sys
from collections import Counter

sys.path.append(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from cube_mesh import unit_cube as cube  # noqa: E402

program, out = sys.argv[1:3]
os.makedirs(out, exist_ok=True)
failures = []


def check(cond, what):
    print(("ok: " if cond else "FAIL: ") + what)
    if not cond:
        failures.append(what)


def write_off(path, P, F):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(P)} {len(F)} 0\n")
        f.writelines(" ".join(repr(x) for x in p) + "\n" for p in P)
        f.writelines("3 %d %d %d\n" % t for t in F)


def read_obj(path):
    V, Q = [], []
    for line in open(path):
        w = line.split()
        if w and w[0] == "v":
            V.append(tuple(float(x) for x in w[1:4]))
        elif w and w[0] == "f":
            Q.append([int(x.split("/")[0]) - 1 for x in w[1:]])
    return V, Q


def run(args, status):
    p = subprocess.run([program] + args + ["--error-codes"], capture_output=True, text=True)
    check(p.returncode == status, f"{' '.join(args)}: status {p.returncode} (expected {status}) {p.stderr.strip()}")
    return p


P, F, corners = cube(4)
mesh = os.path.join(out, "cube.off")
sing = os.path.join(out, "cube.sing")
write_off(mesh, P, F)
with open(sing, "w") as f:
    f.writelines(f"{v} 1/4\n" for v in corners)
base = [mesh, "--singularities", sing, "--n", "4", "--align-features",
        "--connection", os.path.join(out, "c.txt"), "--field", os.path.join(out, "f.txt")]


def check_cube(k, size_args):
    obj = os.path.join(out, f"quads_{k}.obj")
    if os.path.exists(obj):
        os.remove(obj)
    p = run(base + ["--quad-mesh", obj] + size_args, 0)
    if p.returncode != 0:
        return
    H = 1 / k
    V, Q = read_obj(obj)
    tag = f"k = {k} ({' '.join(size_args)})"
    check(len(Q) == 6 * k * k and all(len(q) == 4 for q in Q), f"{tag}: {len(Q)} quads, 6 k^2 = {6 * k * k}")
    directed = Counter((q[j], q[(j + 1) % 4]) for q in Q for j in range(4))
    check(all(c == 1 and directed.get((b, a)) == 1 for (a, b), c in directed.items()),
          f"{tag}: every edge in two quads with opposite directions")
    E = len(directed) // 2
    check(len(V) - E + len(Q) == 2, f"{tag}: V - E + F = {len(V) - E + len(Q)}")
    neighbours = [set() for _ in V]
    for a, b in directed:
        neighbours[a].add(b)
    valence = Counter(len(n) for n in neighbours)
    check(valence[3] == 8 and valence[4] == len(V) - 8, f"{tag}: valences {dict(valence)}")
    on_corner = all(all(abs(x) < 1e-9 or abs(x - 1) < 1e-9 for x in V[v])
                    for v in range(len(V)) if len(neighbours[v]) == 3)
    check(on_corner, f"{tag}: the valence-3 vertices are the cube's corners")
    # each quad on one face of the cube (its four vertices on one plane x_a = 0 or 1), its normal pointing out
    good = 0
    for q in Q:
        pts = [V[v] for v in q]
        n = [0.0, 0.0, 0.0]
        for j in range(4):
            a, b = pts[j], pts[(j + 1) % 4]
            n = [n[0] + a[1] * b[2] - a[2] * b[1], n[1] + a[2] * b[0] - a[0] * b[2], n[2] + a[0] * b[1] - a[1] * b[0]]
        for axis in range(3):
            for plane, side in ((0.0, -1), (1.0, 1)):
                if all(abs(p[axis] - plane) < 1e-9 for p in pts) and n[axis] * side > 0:
                    good += 1
    check(good == len(Q), f"{tag}: {good} of {len(Q)} quads on a face of the cube, facing out")
    line = [l for l in p.stdout.splitlines() if l.startswith("quad mesh:")]
    check(len(line) == 1, f"{tag}: one report line 'quad mesh: ...'")
    if line:
        m = re.search(r": (\d+) quads, (\d+) vertices, H = ([0-9.e+-]+); valence errors (\d+), folded triangles (\d+) "
                      r"\(degenerate (\d+)\), rejected polygons (\d+), open edges (\d+), flipped quads (\d+) \(concave (\d+)\); "
                      r"Hausdorff distance ([0-9.]+) H", line[0])
        check(m is not None, f"{tag}: the report line reads: {line[0]}")
        if m:
            g = m.groups()
            check(int(g[0]) == len(Q) and int(g[1]) == len(V), f"{tag}: the report counts the file's quads and vertices")
            check(abs(float(g[2]) - H) < 1e-5, f"{tag}: H = {g[2]}")
            check(all(int(x) == 0 for x in g[3:10]),
                  f"{tag}: no valence error, fold, rejected polygon, open edge, flipped or concave quad")
            check(float(g[10]) <= 0.5, f"{tag}: Hausdorff distance {g[10]} H <= H/2")


check_cube(1, ["--quad-size", "1"])
check_cube(2, ["--quad-size", "0.5"])
check_cube(4, ["--quad-size", "0.25"])
check_cube(3, ["--target-faces", "54"])
# the cube's field is a gradient already (flat faces, unit length): scaling it towards one leaves it alone
check_cube(2, ["--quad-size", "0.5", "--quad-scale-smoothness", "0.1"])
# the cone modes (the map made to wind around every singular vertex as its index asks): the cube's map does already
check_cube(2, ["--quad-size", "0.5", "--quad-cone-modes", "30"])

# errors: nothing written
obj = os.path.join(out, "refused.obj")
written = [obj, os.path.join(out, "e_c.txt"), os.path.join(out, "e_f.txt")]
for w in written:
    if os.path.exists(w):
        os.remove(w)
err = [mesh, "--singularities", sing, "--connection", written[1], "--field", written[2]]
for args, status, what in [
    (["--quad-mesh", obj, "--quad-size", "0.5"], 2, "without --n 4"),
    (["--n", "2", "--quad-mesh", obj, "--quad-size", "0.5"], 2, "with --n 2"),
    (["--n", "4", "--quad-mesh", obj], 2, "without a size"),
    (["--n", "4", "--quad-mesh", obj, "--quad-size", "0.5", "--target-faces", "24"], 2, "with both sizes"),
    (["--n", "4", "--quad-size", "0.5"], 2, "--quad-size without --quad-mesh"),
    (["--n", "4", "--quad-mesh", obj, "--quad-size", "-1"], 2, "a negative H"),
    (["--n", "4", "--quad-mesh", obj, "--quad-size", "nan"], 2, "H = nan"),
    (["--n", "4", "--quad-mesh", obj, "--target-faces", "0"], 2, "0 target faces"),
    (["--n", "4", "--quad-scale-smoothness", "0.1"], 2, "--quad-scale-smoothness without --quad-mesh"),
    (["--n", "4", "--quad-mesh", obj, "--quad-size", "0.5", "--quad-scale-smoothness", "-1"], 2,
     "a negative scale smoothness"),
    (["--n", "4", "--quad-cone-modes", "30"], 2, "--quad-cone-modes without --quad-mesh"),
    (["--n", "4", "--quad-mesh", obj, "--quad-size", "0.5", "--quad-cone-modes", "-1"], 2, "a negative cone weight"),
    (["--n", "4", "--quad-mesh", obj, "--quad-size", "0.5", "--quad-cone-modes", "inf"], 2, "an infinite cone weight"),
    (["--n", "4", "--quad-mesh", obj, "--quad-size", "1e-5"], 1, "H too small"),
]:
    p = run(err + args, status)
    check(not any(os.path.exists(w) for w in written), f"{what}: no file written")
    if what == "H too small":
        check("[invalid_argument]" in p.stderr and "too small" in p.stderr, f"{what}: says so: {p.stderr.strip()}")

# a surface with border (the cube without its top) whose field does not follow it: refused, nothing written
P, F, box_corners = cube(3, open_top=True)
open_mesh = os.path.join(out, "open_box.off")
write_off(open_mesh, P, F)
p = run([open_mesh, "--n", "4", "--quad-mesh", obj, "--quad-size", "0.5", "--connection", written[1], "--field",
         written[2]], 1)
check("border" in p.stderr, f"a border the field does not follow: the error says so: {p.stderr.strip()}")
check(not any(os.path.exists(w) for w in written), "a border: no file written")

# the same box with --align-boundary and its four bottom corners +1/4: the quads end on the border (the rim)
box_sing = os.path.join(out, "box.sing")
with open(box_sing, "w") as f:
    f.writelines(f"{v} 1/4\n" for v in box_corners if P[v][2] == 0)
box_obj = os.path.join(out, "box_quads.obj")
p = run([open_mesh, "--n", "4", "--singularities", box_sing, "--align-boundary", "--quad-mesh", box_obj,
         "--quad-size", "0.5", "--connection", os.path.join(out, "ok_c.txt"), "--field", os.path.join(out, "ok_f.txt")], 0)
if p.returncode == 0:
    V, Q = read_obj(box_obj)
    check(len(Q) == 20 and all(len(q) == 4 for q in Q), f"open box, H = 1/2: {len(Q)} quads, 5 k^2 = 20")
    directed = Counter((q[j], q[(j + 1) % 4]) for q in Q for j in range(4))
    border = [(a, b) for (a, b) in directed if (b, a) not in directed]
    check(len(border) == 8 and all(abs(V[a][2] - 1) < 1e-9 and abs(V[b][2] - 1) < 1e-9 for a, b in border),
          f"open box: the {len(border)} edges in one quad are the rim's 8 (4 k), at z = 1")
    neighbours = [set() for _ in V]
    for a, b in directed:
        neighbours[a].add(b)
        neighbours[b].add(a)
    valence = Counter(len(n) for n in neighbours)
    check(valence[3] == 4 + 8 and valence[4] == len(V) - 12,
          f"open box: valence 3 at the 4 bottom corners and the 8 rim vertices, 4 elsewhere: {dict(valence)}")

# sharp edges on iso-lines: the cube of 5 x 5 squares per face with H = 0.4 (the side is not a multiple of H, and
# no iso-line would run along the cube's edges by itself): with --align-features every cube edge is a chain of quad
# edges, and the report counts its 60 mesh edges as feature edges
P5, F5, corners5 = cube(5)
mesh5, sing5, obj5 = os.path.join(out, "cube5.off"), os.path.join(out, "cube5.sing"), os.path.join(out, "cube5.obj")
write_off(mesh5, P5, F5)
with open(sing5, "w") as f:
    f.writelines(f"{v} 1/4\n" for v in corners5)
p = run([mesh5, "--singularities", sing5, "--n", "4", "--align-features", "--quad-mesh", obj5, "--quad-size", "0.4",
         "--connection", os.path.join(out, "ok_c.txt"), "--field", os.path.join(out, "ok_f.txt")], 0)
if p.returncode == 0:
    V, Q = read_obj(obj5)
    quad_edges = {tuple(sorted((q[j], q[(j + 1) % 4]))) for q in Q for j in range(4)}
    covered = 0
    for axis in range(3):
        for c1 in (0.0, 1.0):
            for c2 in (0.0, 1.0):
                fixed = [a for a in range(3) if a != axis]
                on = lambda v: abs(V[v][fixed[0]] - c1) < 1e-9 and abs(V[v][fixed[1]] - c2) < 1e-9
                spans = sorted(sorted((V[a][axis], V[b][axis])) for a, b in quad_edges if on(a) and on(b))
                reach = 0.0
                for lo, hi in spans:
                    if lo <= reach + 1e-9:
                        reach = max(reach, hi)
                covered += reach >= 1 - 1e-9
    check(covered == 12, f"cube 5 x 5, H = 0.4, --align-features: {covered} of the 12 cube edges are chains of quad edges")
    line = [l for l in p.stdout.splitlines() if l.startswith("quad mesh:")]
    m = re.search(r"valence errors (\d+), folded triangles (\d+).*on iso-lines: (\d+) feature edges", line[0]) if line else None
    check(m is not None and m.group(1) == "0" and m.group(2) == "0" and m.group(3) == "60",
          f"cube 5 x 5: no valence error or fold, 60 feature edges: {line}")

if failures:
    sys.exit(f"cli_quad_mesh.py: {len(failures)} failures")
print("cli_quad_mesh.py: all checks passed")
