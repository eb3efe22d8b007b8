#!/usr/bin/env python3
# The program's --quad-mesh on fandisk (CGAL's data) with --auto --n 4 --align-features (issue 43), from its files
# alone, H = the bounding box's diagonal / 40:
#  - the sharp edges (faces' normals more than 30 degrees apart, recomputed here) are the report's feature edges;
#  - the singularities used (--write-singularities) are those of the same run without --quad-mesh, but the ones
#    closer than H to a sharp edge (distance along mesh edges to the nearest vertex of one) and not on one: each of
#    those moved to a vertex at least H from every sharp edge; the report line counts them;
#  - the quads against the run of main before this step (fandisk, same H: 55 folded triangles, 22 valence errors,
#    683 of the 722 sharp edges followed by quad edges, Hausdorff input -> quads 1.123 H), strictly better: the
#    report's folded triangles and valence errors, the sharp edges followed (counted here: a sharp edge is followed
#    when the quad edges whose two ends lie on its curve cover it), the quads' valences (counted here: a vertex
#    inside the quads of valence other than 4 that is not on a singular vertex: none); no flipped quad.
#  - the cusp (a crease turning back, two sharp edges less than 45 degrees apart) is a -1/4 singularity (the sector
#    rule), and the counts beat main's before it (40 folded + 1 degenerate, 12 valence errors, Hausdorff 1.064 H).
#  - the rounded map untangled (its 18 folded triangles at this H): the report says how many the rounded map had,
#    and the quads' counts beat those of the rounded map (the program with --no-untangle: 18 folded, 6 valence
#    errors, Hausdorff 0.974 H).
#  - the singular vertices the map winds around the wrong number of times (reported) are among the valence errors.
#  - at H = the diagonal / 45, the quads made again with the cone modes (the first ones have singular vertices
#    wound wrongly) are kept: fewer flaws, valence 4 - 4k exactly at the singularities of index k, and the
#    Hausdorff distance within H/2.
# What is left (issue 43): valence errors at singular vertices around which the map winds the wrong way (already
# before rounding) at some sizes (at the diagonal / 40 the cone modes tie and are not kept); the counts are
# measured, not zero.
# Exits 77 (skipped) when CGAL's data is absent.
# Usage: cli_quad_fandisk.py PROGRAM CGAL_DATA_DIR OUT_DIR
import collections, fractions, heapq, os, re, subprocess, sys
import numpy as np

program, data, out = sys.argv[1:4]
mesh = os.path.join(data, "fandisk.off")
if not os.path.exists(mesh):
    print(f"cli_quad_fandisk.py: {mesh} not found (bash scripts/fetch_cgal_data.sh): skipped")
    sys.exit(77)
os.makedirs(out, exist_ok=True)
failures = []


def check(cond, what):
    print(("ok: " if cond else "FAIL: ") + what)
    if not cond:
        failures.append(what)


def read_off(path):
    words = [w for line in open(path) for w in line.split("#")[0].split()]
    start = 1 if words[0] == "OFF" else 0
    nv, nf = int(words[start]), int(words[start + 1])
    P = np.array(words[start + 3:start + 3 + 3 * nv], float).reshape(-1, 3)
    F, at = [], start + 3 + 3 * nv
    for _ in range(nf):
        k = int(words[at])
        F.append([int(x) for x in words[at + 1:at + 1 + k]])
        at += 1 + k
    return P, np.array(F)


def read_obj(path):
    V, Q = [], []
    for line in open(path):
        w = line.split()
        if w and w[0] == "v":
            V.append([float(x) for x in w[1:4]])
        elif w and w[0] == "f":
            Q.append([int(x.split("/")[0]) - 1 for x in w[1:]])
    return np.array(V), Q


def read_sing(path):
    return {int(l.split()[0]): l.split()[1] for l in open(path) if l.strip() and not l.startswith("#")}


P, F = read_off(mesh)
H = np.linalg.norm(P.max(0) - P.min(0)) / 40
N = np.cross(P[F[:, 1]] - P[F[:, 0]], P[F[:, 2]] - P[F[:, 0]])
N /= np.linalg.norm(N, axis=1)[:, None]
faces_of = collections.defaultdict(list)
for f, t in enumerate(F):
    for k in range(3):
        faces_of[tuple(sorted((t[k], t[(k + 1) % 3])))].append(f)
sharp = [e for e, fs in faces_of.items() if len(fs) == 2 and N[fs[0]] @ N[fs[1]] < np.cos(np.radians(30))]
on_sharp = {v for e in sharp for v in e}
neighbours = collections.defaultdict(set)
for a, b in faces_of:
    neighbours[a].add(b)
    neighbours[b].add(a)

# distance along mesh edges to the nearest vertex of a sharp edge
to_sharp = {v: 0.0 for v in on_sharp}
queue = [(0.0, v) for v in on_sharp]
heapq.heapify(queue)
while queue:
    d, v = heapq.heappop(queue)
    if d > to_sharp[v]:
        continue
    for w in neighbours[v]:
        dw = d + np.linalg.norm(P[v] - P[w])
        if dw < to_sharp.get(w, np.inf):
            to_sharp[w] = dw
            heapq.heappush(queue, (dw, w))


def run(args):
    p = subprocess.run([program, mesh, "--auto", "--n", "4", "--align-features"] + args, capture_output=True, text=True)
    check(p.returncode == 0, f"{' '.join(args)}: status {p.returncode} {p.stderr.strip()}")
    if p.returncode != 0:
        sys.exit("cli_quad_fandisk.py: the program failed")
    return p.stdout


files = {k: os.path.join(out, k) for k in ("placed.sing", "used.sing", "quads.obj", "c.txt", "f.txt")}
for path in files.values():
    if os.path.exists(path):
        os.remove(path)
common = ["--connection", files["c.txt"], "--field", files["f.txt"]]
run(common + ["--write-singularities", files["placed.sing"]])
report = run(common + ["--write-singularities", files["used.sing"], "--quad-mesh", files["quads.obj"],
                       "--quad-size", repr(H)])
placed, used = read_sing(files["placed.sing"]), read_sing(files["used.sing"])

# the singularities: the placed ones kept where on a sharp edge or at least H away, the others moved that far
near = {v for v in placed if v not in on_sharp and to_sharp[v] < H}
kept = {v: k for v, k in placed.items() if v not in near}
check(all(used.get(v) == k for v, k in kept.items()), f"the {len(kept)} singularities not closer than H to a sharp edge kept")
new = {v: k for v, k in used.items() if v not in kept}
check(len(new) == len(near) and collections.Counter(new.values()) == collections.Counter(placed[v] for v in near),
      f"the {len(near)} closer than H moved, with their indices: {sorted(new)}")
check(all(to_sharp[v] >= H for v in new), "each moved to a vertex at least H from every sharp edge")
check(len(near) > 0, f"fandisk has singularities placed closer than H to a sharp edge: {len(near)}")
m = re.search(r"^singularities moved off feature lines: (\d+)", report, re.M)
check(m is not None and int(m.group(1)) == len(near), f"the report counts them: {m.group(0) if m else report}")

line = re.search(r"^quad mesh: .*", report, re.M)
check(line is not None, "a report line 'quad mesh: ...'")
r = re.search(r"valence errors (\d+), folded triangles (\d+) \(degenerate (\d+)\), rejected polygons (\d+), open edges "
              r"(\d+), flipped quads (\d+).*input to quads ([0-9.]+) H\); on iso-lines: (\d+) feature edges", line.group(0))
check(r is not None, f"the report line reads: {line.group(0)}")
valence_errors, folded, degenerate, rejected, open_edges, flipped = (int(x) for x in r.groups()[:6])
check(int(r.group(8)) == len(sharp), f"the {len(sharp)} sharp edges (30 degrees) are the report's {r.group(8)} feature edges")
check(folded + degenerate < 41, f"folded triangles {folded} (degenerate {degenerate}) < 40 + 1, main's before the sector rule")
check(valence_errors < 12, f"valence errors {valence_errors} < 12")
check(flipped == 0, f"no flipped quad ({flipped})")
check(float(r.group(7)) < 1.064, f"Hausdorff input -> quads {r.group(7)} H < 1.064 H")
u = re.search(r"untangling: (\d+) folded and degenerate triangles in the rounded map, (\d+) after it", line.group(0))
check(u is not None and int(u.group(2)) == folded + degenerate and int(u.group(1)) > folded + degenerate,
      f"the untangling is reported and removed folds: {u.group(0) if u else line.group(0)}")
w = re.search(r"wound the wrong number of times: (\d+) singular vertices, (\d+) branch points", line.group(0))
wound = int(w.group(1)) if w else 0
check(wound <= valence_errors,
      f"each singular vertex the map winds around the wrong number of times ({wound}) is a valence error ({valence_errors})")
check(folded + degenerate < 18, f"folded triangles {folded} (degenerate {degenerate}) < 18, the rounded map's")
check(valence_errors < 6, f"valence errors {valence_errors} < 6, the rounded map's")
check(float(r.group(7)) < 0.974, f"Hausdorff input -> quads {r.group(7)} H < 0.974 H, the rounded map's")

# the cusp: a vertex of two sharp edges that leave it less than 45 degrees apart (the crease turns back). The
# sector between them gets one quad corner and the outside four (the sector rule), so its index is 1 - 5/4.
sharp_at = collections.defaultdict(list)
for a, b in sharp:
    sharp_at[a].append(b)
    sharp_at[b].append(a)
cusps = []
for v, ends in sharp_at.items():
    if len(ends) == 2:
        d = [(P[w] - P[v]) / np.linalg.norm(P[w] - P[v]) for w in ends]
        if d[0] @ d[1] > np.cos(np.radians(45)):
            cusps.append(v)
check(len(cusps) == 1, f"fandisk has one cusp: {cusps}")
check(all(used.get(v) == "-1/4" for v in cusps), f"the cusp's index is -1/4: {[used.get(v) for v in cusps]}")

V, Q = read_obj(files["quads.obj"])
check(len(Q) > 1000 and all(len(q) == 4 for q in Q), f"{len(Q)} quads")


def sharp_curves():
    """The sharp edges as curves: chains between vertices of sharp degree other than 2, and closed loops."""
    adjacent = collections.defaultdict(list)
    for a, b in sharp:
        adjacent[a].append(b)
        adjacent[b].append(a)
    used_edges, curves = set(), []
    for s in [v for v in adjacent if len(adjacent[v]) != 2] + list(adjacent):
        for w in adjacent[s]:
            if (min(s, w), max(s, w)) in used_edges:
                continue
            chain = [s, w]
            used_edges.add((min(s, w), max(s, w)))
            while len(adjacent[chain[-1]]) == 2:
                nxt = [y for y in adjacent[chain[-1]] if (min(y, chain[-1]), max(y, chain[-1])) not in used_edges]
                if not nxt:
                    break
                used_edges.add((min(nxt[0], chain[-1]), max(nxt[0], chain[-1])))
                chain.append(nxt[0])
            curves.append(chain)
    return curves


# a sharp edge is followed when the quad edges with both ends on its curve cover it (arc length along the curve)
eps = 1e-6 * H
followed = 0
curves = sharp_curves()
check(sum(len(c) - 1 for c in curves) == len(sharp), f"the {len(sharp)} sharp edges in {len(curves)} curves")
for chain in curves:
    X = P[chain]
    seg = X[1:] - X[:-1]
    L = np.linalg.norm(seg, axis=1)
    s0 = np.concatenate([[0], np.cumsum(L)])
    at = {}  # quad vertex -> arc length on this curve
    for k in range(len(chain) - 1):
        t = ((V - X[k]) @ seg[k]) / L[k] ** 2
        off = np.linalg.norm(V - X[k] - np.outer(t, seg[k]), axis=1)
        for v in np.nonzero((off < eps) & (t > -eps / L[k]) & (t < 1 + eps / L[k]))[0]:
            at[int(v)] = s0[k] + np.clip(t[v], 0, 1) * L[k]
    spans = sorted(tuple(sorted((at[q[j]], at[q[(j + 1) % 4]]))) for q in Q for j in range(4)
                   if q[j] in at and q[(j + 1) % 4] in at)
    merged = []
    for lo, hi in spans:
        if merged and lo <= merged[-1][1] + eps:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    followed += sum(any(lo <= s0[k] + eps and hi >= s0[k + 1] - eps for lo, hi in merged) for k in range(len(chain) - 1))
check(followed > 683, f"{followed} of {len(sharp)} sharp edges followed by quad edges (> 683)")

# the quads' own valences: inside the quads (an edge in two quads all around), 4 but at the singular vertices
directed = collections.Counter((q[j], q[(j + 1) % 4]) for q in Q for j in range(4))
border = {a for (a, b) in directed if (b, a) not in directed} | {b for (a, b) in directed if (b, a) not in directed}
valence = collections.Counter()
for a, b in directed:
    valence[a] += 1
singular_points = P[sorted(used)]
off_singular = [v for v in valence if v not in border and valence[v] != 4 and
                np.min(np.linalg.norm(singular_points - V[v], axis=1)) > eps]
check(not off_singular, f"inside the quads, valence 4 but at the singular vertices ({len(off_singular)} others): the "
      "valence errors are at the holes the folds leave")
print(f"measured: {len(Q)} quads, {valence_errors} valence errors, {folded} folded ({degenerate} degenerate), "
      f"{rejected} rejected polygons, {open_edges} open edges, {followed} of {len(sharp)} sharp edges followed, "
      f"{len(off_singular)} quad vertices inside the quads of valence other than 4 off the singular vertices")

# The cone modes, tried by the program when the quads have singular vertices wound wrongly (manual, Cone modes):
# at H = the diagonal / 45 the first quads have such vertices, and those with the cone modes are kept and valid:
# a closed mesh of quads whose valence is 4 - 4k at each singularity of index k and 4 everywhere else.
H45 = np.linalg.norm(P.max(0) - P.min(0)) / 45
for k in ("used45.sing", "quads45.obj"):
    files[k] = os.path.join(out, k)
    if os.path.exists(files[k]):
        os.remove(files[k])
report45 = run(common + ["--write-singularities", files["used45.sing"], "--quad-mesh", files["quads45.obj"],
                         "--quad-size", repr(H45)])
line45 = re.search(r"^quad mesh: .*", report45, re.M).group(0)
c = re.search(r"cone modes \(weight 30\): the continuous map untangled first; without them (\d+) folded", line45)
r45 = re.search(r"valence errors (\d+), folded triangles (\d+) \(degenerate (\d+)\)", line45)
check(c is not None and r45 is not None, f"H = diagonal / 45: the cone modes tried and kept: {line45}")
if c is not None and r45 is not None:
    flaws45 = sum(int(x) for x in r45.groups())
    check(flaws45 < int(c.group(1)), f"with fewer flaws ({flaws45}) than without them ({c.group(1)})")
check("wound the wrong number of times" not in line45, "no singular vertex wound wrongly")
h45 = re.search(r"Hausdorff distance ([0-9.]+) H", line45)
check(h45 is not None and float(h45.group(1)) <= 0.5, f"Hausdorff distance {h45.group(1) if h45 else '?'} H <= H/2")
V45, Q45 = read_obj(files["quads45.obj"])
directed45 = collections.Counter((q[j], q[(j + 1) % 4]) for q in Q45 for j in range(4))
check(all(len(q) == 4 for q in Q45) and all(n == 1 and directed45[(b, a)] == 1 for (a, b), n in directed45.items()),
      f"{len(Q45)} quads, closed and manifold: every edge in two quads, once each way")
valence45 = collections.Counter(a for a, b in directed45)
used45 = read_sing(files["used45.sing"])
expected = {}
for v, k in used45.items():
    at = np.nonzero(np.linalg.norm(V45 - P[v], axis=1) < 1e-6 * H45)[0]
    check(len(at) == 1, f"singular vertex {v} ({k}) is a quad vertex")
    if len(at) == 1:
        expected[int(at[0])] = 4 - 4 * fractions.Fraction(k)
wrong45 = [v for v in valence45 if valence45[v] != expected.get(v, 4)]
check(not wrong45, f"valence 4 - 4k at the {len(expected)} singularities, 4 at the other "
      f"{len(valence45) - len(expected)} quad vertices (wrong: {wrong45[:10]})")

if failures:
    sys.exit(f"cli_quad_fandisk.py: {len(failures)} failures")
print("cli_quad_fandisk.py: all checks passed")
