"""The program's --triangulate on a mesh of quads it cannot read without it. Used by ctest.

A cube whose faces are split into 3 x 3 planar quads: every vertex but the eight corners is flat (angle
defect 0) and each corner has defect pi/2. With a +1/4 singularity at each corner (n = 4, sum 2 = chi),
Levi-Civita transport is itself trivial, so the closest trivial connection is x = 0 on every edge, whatever
the diagonals PMP chooses. Without --triangulate the program must refuse the file and name the option.
Usage: cli_triangulate.py PROGRAM OUT_DIR
"""
import itertools
import os
import subprocess
import sys

program, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)


def fail(message):
    print("cli_triangulate.py: " + message, file=sys.stderr)
    sys.exit(1)


# vertices of the 4 x 4 x 4 lattice on the cube's surface, faces as outward quads
m = 3
index = {}
points = []
for p in itertools.product(range(m + 1), repeat=3):
    if 0 in p or m in p:
        index[p] = len(points)
        points.append(p)
quads = []
for axis in range(3):
    u, v = (axis + 1) % 3, (axis + 2) % 3
    for side in (0, m):
        for a in range(m):
            for b in range(m):
                corners = []
                for da, db in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    p = [0, 0, 0]
                    p[axis], p[u], p[v] = side, a + da, b + db
                    corners.append(index[tuple(p)])
                if side == 0:  # (u, v, axis) is right-handed: reverse on the low side to face outwards
                    corners.reverse()
                quads.append(corners)
mesh = os.path.join(out, "cube_quads.off")
with open(mesh, "w") as f:
    f.write("OFF\n%d %d 0\n" % (len(points), len(quads)))
    f.writelines("%d %d %d\n" % p for p in points)
    f.writelines("4 %d %d %d %d\n" % tuple(q) for q in quads)
sing = os.path.join(out, "corners.sing")
with open(sing, "w") as f:
    for p in itertools.product((0, m), repeat=3):
        f.write("%d 1/4\n" % index[p])

refused = subprocess.run([program, mesh, "--singularities", sing, "--n", "4"], capture_output=True, text=True)
if refused.returncode != 1 or "4 vertices" not in refused.stderr or "--triangulate" not in refused.stderr:
    fail("quads without --triangulate: expected exit 1 naming the option, got %d: %s"
         % (refused.returncode, refused.stderr.strip()))
print("ok: refused without --triangulate: " + refused.stderr.strip())

connection, field = os.path.join(out, "c.txt"), os.path.join(out, "f.txt")
run = subprocess.run([program, mesh, "--triangulate", "--singularities", sing, "--n", "4",
                      "--connection", connection, "--field", field], capture_output=True, text=True)
if run.returncode != 0:
    fail("with --triangulate: exit %d: %s" % (run.returncode, run.stderr.strip()))
expected = "triangulated: %d of the file's %d faces" % (len(quads), len(quads))
if expected not in run.stdout:
    fail("report does not say '%s':\n%s" % (expected, run.stdout))
rows = [line.split() for line in open(connection) if line.strip() and not line.startswith("#")]
# 2 triangles per quad: E = 3F/2 on a closed mesh
if len(rows) != 3 * len(quads):
    fail("%d interior edges, expected %d" % (len(rows), 3 * len(quads)))
worst = max(abs(float(r[2])) for r in rows)
if worst > 1e-12:
    fail("max |x| = %g: Levi-Civita is trivial here, x must vanish" % worst)
faces = [line for line in open(field) if line.strip() and not line.startswith("#")]
if len(faces) != 2 * len(quads):
    fail("%d field vectors, expected one per triangle (%d)" % (len(faces), 2 * len(quads)))
print("ok: %d quads -> %d triangles, max |x| = %.1e" % (len(quads), len(faces), worst))
