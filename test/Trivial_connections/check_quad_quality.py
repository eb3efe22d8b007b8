"""scripts/quad_quality.py on quad meshes built here by hand, against what their construction implies. Used by ctest.

The input is the cube [-1, 1]^3 with each face split into 2 x 2 squares and each square into two triangles
(vertices: corners, edge midpoints, face centres). The quad mesh is the same cube's faces split into k x k squares
(k = 3), oriented outwards, so that:
- it has F = 6 k^2 quads, E = 2F edges (each quad has 4, each edge 2 quads) and V = 2 - F + E = 6 k^2 + 2 vertices;
- the eight corners have valence 3 and all other vertices 4; with a +1/4 singularity at each corner (4 - 4k = 3)
  there is no valence error; a corner given -1/4 (expects 5) is one error; a face centre of the input, not a
  vertex of the 3 x 3 grid, is an unmatched singularity;
- each quad is a square of side H = 2 / k: corner angles 90 degrees, area / H^2 = 1;
- both surfaces are the cube's surface: Hausdorff distance 0.
Broken copies change what their edits imply and nothing else:
- one quad reversed: one flipped quad, its 4 edges each used twice in the same direction;
- another quad (a, b, c, d) replaced by the triangle (a, b, c): one non-quad, open edges a-c, c-d, d-a;
- the centre quad of a face removed: a square hole of side H whose centre is an input vertex (the face centre) at
  distance H / 2 from the nearest quad (the hole's sides): input-to-quads distance H / 2, 4 open edges;
- one grid vertex inside a face moved outwards by delta: quads-to-input distance delta (its nearest input point
  is its projection on the face), input-to-quads at most delta.
Bad inputs: exit status 2 and a reason.
Usage: check_quad_quality.py QUAD_QUALITY_SCRIPT PYTHON OUT_DIR
"""
import itertools
import json
import os
import subprocess
import sys

script, python, out = sys.argv[1], sys.argv[2], sys.argv[3]
os.makedirs(out, exist_ok=True)
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def cube_grid(m):
    """Vertices (coordinates in [-1, 1]) and outward quads of the cube's faces split into m x m squares."""
    index, points, quads = {}, [], []
    for p in itertools.product(range(m + 1), repeat=3):
        if 0 in p or m in p:
            index[p] = len(points)
            points.append([2.0 * c / m - 1.0 for c in p])
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
                    # (u, v, axis) is right-handed: counter-clockwise seen from +axis; reversed on the low side
                    quads.append(corners if side == m else corners[::-1])
    return points, quads, index


def write_obj(path, points, faces):
    with open(path, "w") as fh:
        for p in points:
            fh.write("v %.17g %.17g %.17g\n" % tuple(p))
        for f in faces:
            fh.write("f " + " ".join(str(i + 1) for i in f) + "\n")


def write_off(path, points, faces):
    with open(path, "w") as fh:
        fh.write("OFF\n%d %d 0\n" % (len(points), len(faces)))
        for p in points:
            fh.write("%.17g %.17g %.17g\n" % tuple(p))
        for f in faces:
            fh.write("%d %s\n" % (len(f), " ".join(map(str, f))))


def run(*args, expect=0):
    r = subprocess.run([python, script, *args], capture_output=True, text=True)
    if r.returncode != expect:
        failures.append(f"{' '.join(args)}: exit {r.returncode}, expected {expect}: {r.stderr.strip()}")
        return None
    return r


def report(quads_path, *extra):
    r = run(input_path, quads_path, "--quad-size", str(H), "--json", *extra)
    return json.loads(r.stdout) if r else None


# the input: 2 x 2 squares per face, each split into two triangles
in_points, in_quads, in_index = cube_grid(2)
input_path = os.path.join(out, "cube_input.off")
write_off(input_path, in_points, [t for q in in_quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))])
corners = [in_index[p] for p in itertools.product((0, 2), repeat=3)]
face_centre = in_index[(1, 1, 2)]  # the centre of the face z = +1

k = 3
H = 2.0 / k
points, quads, index = cube_grid(k)
F = 6 * k * k
eps = 1e-12

# the clean cube
good = os.path.join(out, "cube_quads.obj")
write_obj(good, points, quads)
sing = os.path.join(out, "corners.sing")
with open(sing, "w") as fh:
    fh.write("# the eight corners, +1/4 each\n" + "".join(f"{v} 1/4\n" for v in corners))
rep = report(good, "--singularities", sing)
if rep:
    c, e, v, d, h = rep["counts"], rep["edges"], rep["valence"], rep["distortion"], rep["hausdorff"]
    check(c["quads"] == F and c["faces"] == F and c["non_quads"] == 0, f"counts {c}")
    check(c["vertices"] == 6 * k * k + 2, f"vertices {c['vertices']} != 6 k^2 + 2")
    check(e["edges"] == 2 * F and e["open"] == 0 and e["non_manifold"] == 0 and e["inconsistently_oriented"] == 0,
          f"edges {e}")
    check(v["histogram"] == {"3": 8, "4": 6 * k * k + 2 - 8}, f"valence histogram {v['histogram']}")
    check(v["irregular"] == 8 and v["errors"] == 0 and v["singularities_unmatched"] == 0, f"valence {v}")
    check(rep["flipped"]["quads"] == 0, f"flipped {rep['flipped']}")
    check(d["angle_deviation_degrees_max"] < 1e-9 and abs(d["area_over_h2_mean"] - 1) < eps
          and d["area_over_h2_std"] < eps, f"distortion {d}")
    check(h["max"] < eps, f"Hausdorff {h}")

# without singularities: irregular vertices counted, no valence error claimed
rep = report(good)
if rep:
    check(rep["valence"]["irregular"] == 8 and "errors" not in rep["valence"], f"no singularities: {rep['valence']}")

# wrong singularities: a corner said to be -1/4 (valence 5 expected), and one at the input face's centre
wrong = os.path.join(out, "wrong.sing")
with open(wrong, "w") as fh:
    fh.write(f"{corners[0]} -1/4\n" + "".join(f"{v} 1/4\n" for v in corners[1:]) + f"{face_centre} 1/4\n")
rep = report(good, "--singularities", wrong)
if rep:
    v = rep["valence"]
    check(v["errors_at_singularities"] == 1 and v["singularities_unmatched"] == 1
          and v["errors_away_from_singularities"] == 0 and v["errors"] == 2, f"wrong singularities: {v}")

# broken: a quad reversed on face x = -1, a quad made a triangle in the middle of face z = +1
centre_quad = next(i for i, q in enumerate(quads) if sorted(q) == sorted(
    index[(a, b, k)] for a in (1, 2) for b in (1, 2)))
broken = [list(q) for q in quads]
broken[0] = broken[0][::-1]
a_, b_, c_, d_ = broken[centre_quad]
broken[centre_quad] = [a_, b_, c_]
broken_path = os.path.join(out, "cube_broken.obj")
write_obj(broken_path, points, broken)
rep = report(broken_path, "--singularities", sing)
if rep:
    c, e, v = rep["counts"], rep["edges"], rep["valence"]
    check(c["quads"] == F - 1 and c["non_quads"] == 1 and c["face_sizes"] == {"3": 1, "4": F - 1}, f"broken counts {c}")
    check(rep["flipped"]["quads"] == 1 and rep["flipped"]["faces"] == 1, f"broken flipped {rep['flipped']}")
    check(e["inconsistently_oriented"] == 4 and e["open"] == 3 and e["non_manifold"] == 0, f"broken edges {e}")
    check(v["border_vertices"] == 3 and v["errors"] == 0, f"broken valence {v}")
    check(rep["hausdorff"]["max"] < eps, f"broken Hausdorff {rep['hausdorff']}")

# a hole: the centre quad of face z = +1 removed
holed = [q for i, q in enumerate(quads) if i != centre_quad]
holed_path = os.path.join(out, "cube_hole.obj")
write_obj(holed_path, points, holed)
rep = report(holed_path)
if rep:
    h = rep["hausdorff"]
    check(rep["edges"]["open"] == 4 and rep["valence"]["border_vertices"] == 4, f"hole edges {rep['edges']}")
    check(abs(h["input_to_quads"] - H / 2) < eps and h["quads_to_input"] < eps
          and abs(h["max_over_h"] - 0.5) < eps, f"hole Hausdorff {h}")

# a grid vertex inside face z = +1 moved outwards by delta
delta = 0.05
moved = [list(p) for p in points]
moved[index[(1, 1, k)]][2] += delta
moved_path = os.path.join(out, "cube_moved.obj")
write_obj(moved_path, moved, quads)
rep = report(moved_path)
if rep:
    h, d = rep["hausdorff"], rep["distortion"]
    check(abs(h["quads_to_input"] - delta) < eps and h["input_to_quads"] <= delta + eps, f"moved Hausdorff {h}")
    check(d["angle_deviation_degrees_max"] > 0.1 and rep["flipped"]["quads"] == 0, f"moved distortion {d}")

# the text line
r = run(input_path, good, "--quad-size", str(H), "--singularities", sing)
if r:
    check(f"{F} quads, 0 non-quads; valence errors 0 (8 irregular)" in r.stdout, f"text line: {r.stdout}")

# bad inputs: a reason and exit status 2, no report
bad_face = os.path.join(out, "bad_face.obj")
with open(bad_face, "w") as fh:
    fh.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")
for args, words in (((input_path, os.path.join(out, "missing.obj")), "No such file"),
                    ((input_path, bad_face), "out of range"),
                    ((input_path, good, "--quad-size", "0"), "positive"),
                    ((input_path, good, "--singularities", os.path.join(out, "missing.sing")), "No such file")):
    r = run(*args, expect=2)
    if r:
        check(words in r.stderr and not r.stdout, f"{args}: stderr {r.stderr!r}, stdout {r.stdout!r}")

if failures:
    print("check_quad_quality.py: " + "\n  ".join(failures), file=sys.stderr)
    sys.exit(1)
print("check_quad_quality.py: all checks passed")
