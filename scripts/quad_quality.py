#!/usr/bin/env python3
"""The quality of a quad mesh made from a triangle mesh (issue 43): topology, valences, flips, distortion, distance.

    quad_quality.py INPUT_MESH QUAD_MESH.obj [--singularities FILE] [--quad-size H] [--json]

INPUT_MESH: the triangle mesh the quads were made from (.off or .obj; polygons are split into fans).
QUAD_MESH: an OBJ of polygons ('v x y z', 'f a b c d', 1-based or negative indices, 'a/b/c' accepted).
--singularities: the field's singularities, lines 'v k' (input vertex index, index k = p or p/q), as written by
  trivial_connections --write-singularities. Each is matched to the quad vertex at the same position (within
  --match-tolerance times the input's bounding box diagonal); that vertex must have valence 4 - 4k.
--quad-size H: the target edge length; areas are reported relative to H^2 and distances relative to H
  (default: the square root of the mean quad area, said so in the output).

Reported (JSON with --json, else one line of text):
- counts: referenced vertices, faces, quads, non-quads (faces of other than 4 vertices), unreferenced vertices;
- valence (number of distinct edges at a vertex) histogram over the vertices not on an open edge; irregular
  vertices (valence != 4); with --singularities, valence errors: vertices of valence != 4 away from the
  singularities plus singular vertices of valence != 4 - 4k, and singularities with no quad vertex at their place;
- edges: open (one face), non-manifold (more than two faces), inconsistently oriented (the same directed edge in
  two faces), degenerate faces (repeated vertex or zero area);
- flipped quads: the quad's vector area (Newell) against the normal of the input face nearest to its centroid;
- distortion over the quads: each corner's |angle - 90 degrees| (mean, max) and area / H^2 (mean, std);
- Hausdorff distance, approximately, both ways: from the quad vertices and edge midpoints to the input triangles,
  and from the input vertices to the quads' triangles (fans), each exact from those sample points (a uniform grid
  narrows the triangles to test); the maximum of the two; all also divided by H.
Bad input (unreadable file, bad line, index out of range, fewer than 3 vertices in a face): exit status 2 and a
one-line reason. Needs numpy only.
"""
import argparse
import json
import math
import sys
from fractions import Fraction

import numpy as np


class BadInput(Exception):
    pass


def _index(token, count, path, lineno, one_based):
    try:
        i = int(token.split("/")[0])
    except ValueError:
        raise BadInput(f"{path}:{lineno}: bad vertex index '{token}'")
    if one_based:
        i = i - 1 if i > 0 else count + i if i < 0 else -1
    if not 0 <= i < count:
        raise BadInput(f"{path}:{lineno}: vertex index {token} out of range (1..{count})" if one_based
                       else f"{path}:{lineno}: vertex index {token} out of range (0..{count - 1})")
    return i


def read_obj(path):
    points, faces = [], []
    with open(path) as fh:
        for lineno, line in enumerate(fh, 1):
            parts = line.split()
            if not parts or parts[0].startswith("#"):
                continue
            if parts[0] == "v":
                try:
                    points.append([float(x) for x in parts[1:4]])
                except ValueError:
                    raise BadInput(f"{path}:{lineno}: bad vertex line")
                if len(points[-1]) != 3:
                    raise BadInput(f"{path}:{lineno}: a vertex needs 3 coordinates")
            elif parts[0] == "f":
                # indices may refer to vertices before this line only (OBJ), negative ones count back from here
                face = [_index(t, len(points), path, lineno, True) for t in parts[1:]]
                if len(face) < 3:
                    raise BadInput(f"{path}:{lineno}: a face needs at least 3 vertices")
                faces.append(face)
    return np.array(points, float).reshape(-1, 3), faces


def read_off(path):
    with open(path) as fh:
        tokens = []
        for line in fh:
            line = line.split("#", 1)[0]
            tokens.extend(line.split())
    if not tokens or not tokens[0].endswith("OFF"):
        raise BadInput(f"{path}: not an OFF file")
    try:
        nv, nf = int(tokens[1]), int(tokens[2])
        at = 4
        points = np.array(tokens[at:at + 3 * nv], float).reshape(nv, 3)
        at += 3 * nv
        faces = []
        for _ in range(nf):
            k = int(tokens[at])
            faces.append([int(t) for t in tokens[at + 1:at + 1 + k]])
            if len(faces[-1]) != k or k < 3:
                raise BadInput(f"{path}: face {len(faces) - 1} is short")
            at += 1 + k
    except (ValueError, IndexError):
        raise BadInput(f"{path}: truncated or malformed OFF")
    for f, face in enumerate(faces):
        if min(face) < 0 or max(face) >= nv:
            raise BadInput(f"{path}: face {f} has a vertex index out of range (0..{nv - 1})")
    return points, faces


def read_mesh(path):
    try:
        if path.lower().endswith(".off"):
            return read_off(path)
        if path.lower().endswith(".obj"):
            return read_obj(path)
    except OSError as e:
        raise BadInput(f"{path}: {e.strerror}")
    raise BadInput(f"{path}: unknown mesh format (.off or .obj)")


def read_singularities(path, nv):
    result = []
    try:
        with open(path) as fh:
            for lineno, line in enumerate(fh, 1):
                line = line.split("#", 1)[0].split()
                if not line:
                    continue
                try:
                    v, k = int(line[0]), Fraction(line[1])
                except (ValueError, IndexError, ZeroDivisionError):
                    raise BadInput(f"{path}:{lineno}: expected 'v k'")
                if not 0 <= v < nv:
                    raise BadInput(f"{path}:{lineno}: vertex {v} out of range (0..{nv - 1})")
                result.append((v, k))
    except OSError as e:
        raise BadInput(f"{path}: {e.strerror}")
    return result


def fans(faces):
    """Triangles (i, j, k) of the fans of the polygons, and the polygon of each."""
    tris, owner = [], []
    for f, face in enumerate(faces):
        for j in range(1, len(face) - 1):
            tris.append((face[0], face[j], face[j + 1]))
            owner.append(f)
    return np.array(tris, np.int64).reshape(-1, 3), np.array(owner, np.int64)


def closest_on_triangles(p, a, b, c):
    """Squared distances from points p to triangles (a, b, c), row by row (all arrays n x 3): the closest point
    by the triangle's Voronoi regions (vertices, edges, inside), in barycentric form."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    bp = p - b
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    cp = p - c
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        # inside: barycentric weights from the sub-areas; degenerate triangles fall to the edge cases below
        den = va + vb + vc
        v = np.where(den != 0, vb / den, 0.0)
        w = np.where(den != 0, vc / den, 0.0)
        q = a + ab * v[:, None] + ac * w[:, None]
        # the edges: bc, ac, ab (later assignments win where regions overlap at ties, all giving the same point)
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        on_bc = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
        q = np.where(on_bc[:, None], b + (c - b) * np.nan_to_num(t_bc)[:, None], q)
        t_ac = d2 / (d2 - d6)
        on_ac = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        q = np.where(on_ac[:, None], a + ac * np.nan_to_num(t_ac)[:, None], q)
        t_ab = d1 / (d1 - d3)
        on_ab = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        q = np.where(on_ab[:, None], a + ab * np.nan_to_num(t_ab)[:, None], q)
    # the vertices
    q = np.where(((d6 >= 0) & (d5 <= d6))[:, None], c, q)
    q = np.where(((d3 >= 0) & (d4 <= d3))[:, None], b, q)
    q = np.where(((d1 <= 0) & (d2 <= 0))[:, None], a, q)
    return np.einsum("ij,ij->i", p - q, p - q)


class NearestTriangle:
    """Nearest triangle queries: triangles binned into a uniform grid by their bounding boxes; a query tests the
    triangles of the cells within r of its own and is exact when the best distance is <= r cell sizes (any
    nearer triangle would touch one of those cells); the others are asked again with r doubled, at the end
    against all triangles."""

    def __init__(self, points, tris, chunk_pairs=1_000_000):
        self.a, self.b, self.c = points[tris[:, 0]], points[tris[:, 1]], points[tris[:, 2]]
        self.m = len(tris)
        self.chunk_pairs = chunk_pairs
        lo = np.minimum(np.minimum(self.a, self.b), self.c)
        hi = np.maximum(np.maximum(self.a, self.b), self.c)
        ext = hi - lo
        # cells about the size of a typical triangle: few triangles per cell, few cells per triangle
        self.s = max(float(np.median(ext.max(axis=1))), 1e-300)
        self.origin = lo.min(axis=0)
        glo = np.floor((lo - self.origin) / self.s).astype(np.int64)
        ghi = np.floor((hi - self.origin) / self.s).astype(np.int64)
        self.dims = ghi.max(axis=0) + 1
        span = ghi - glo + 1
        keys, ids = [], []
        # triangles spanning many cells (rare, long ones) are enumerated by offsets up to the largest span
        for dx in range(span[:, 0].max()):
            for dy in range(span[:, 1].max()):
                for dz in range(span[:, 2].max()):
                    sel = np.nonzero((dx < span[:, 0]) & (dy < span[:, 1]) & (dz < span[:, 2]))[0]
                    cell = glo[sel] + np.array([dx, dy, dz])
                    keys.append(self._key(cell))
                    ids.append(sel)
        keys, ids = np.concatenate(keys), np.concatenate(ids)
        order = np.argsort(keys, kind="stable")
        self.keys, self.ids = keys[order], ids[order]

    def _key(self, cell):
        return (cell[:, 0] * self.dims[1] + cell[:, 1]) * self.dims[2] + cell[:, 2]

    def query(self, p):
        """Distance from each point to the nearest triangle, and that triangle's index."""
        n = len(p)
        best = np.full(n, np.inf)
        arg = np.full(n, -1, np.int64)
        cell_all = np.floor((p - self.origin) / self.s).astype(np.int64)
        # the distance from each point to its own cell's walls: ring r covers at least r cells plus that
        lo_wall = p - (self.origin + cell_all * self.s)
        wall = np.minimum(lo_wall, self.s - lo_wall).min(axis=1)
        todo = np.arange(n)
        r = 0
        while len(todo):
            if (2 * r + 1) ** 3 > 8 * self.dims.prod() or r > 64:
                self._brute(p, todo, best, arg)
                break
            cell = cell_all[todo]
            offsets = np.arange(-r, r + 1)
            for dx in offsets:
                for dy in offsets:
                    for dz in offsets:
                        if max(abs(dx), abs(dy), abs(dz)) < r // 2 + (r > 0) and r > 1:
                            continue  # tested in the previous ring (r // 2), with the same triangles
                        c = cell + np.array([dx, dy, dz])
                        inside = np.all((c >= 0) & (c < self.dims), axis=1)
                        q, c = todo[inside], c[inside]
                        key = self._key(c)
                        start = np.searchsorted(self.keys, key, "left")
                        stop = np.searchsorted(self.keys, key, "right")
                        self._test(p, q, start, stop - start, best, arg)
            exact = np.sqrt(best[todo]) <= r * self.s + wall[todo]
            todo = todo[~exact]
            r = max(1, 2 * r)
        return np.sqrt(best), arg

    def _test(self, p, q, start, count, best, arg):
        keep = count > 0
        q, start, count = q[keep], start[keep], count[keep]
        if not len(q):
            return
        cum = np.cumsum(count)
        lo = 0
        while lo < len(q):  # in chunks of about chunk_pairs (query, triangle) pairs
            hi = int(np.searchsorted(cum, (cum[lo - 1] if lo else 0) + self.chunk_pairs, "right"))
            hi = max(hi, lo + 1)
            qq, ss, cc = q[lo:hi], start[lo:hi], count[lo:hi]
            rep = np.repeat(np.arange(len(qq)), cc)
            first = np.cumsum(cc) - cc
            t = self.ids[ss[rep] + np.arange(len(rep)) - first[rep]]
            pts = qq[rep]
            d = closest_on_triangles(p[pts], self.a[t], self.b[t], self.c[t])
            # the minimum per query: the pairs are grouped by query (rep is non-decreasing)
            mins = np.minimum.reduceat(d, first)
            hit = np.flatnonzero(d == mins[rep])
            hit = hit[np.unique(rep[hit], return_index=True)[1]]
            better = mins < best[qq]
            best[qq[better]] = mins[better]
            arg[qq[better]] = t[hit][better]
            lo = hi

    def _brute(self, p, todo, best, arg):
        step = max(1, self.chunk_pairs // max(self.m, 1))
        for lo in range(0, len(todo), step):
            qq = todo[lo:lo + step]
            rep = np.repeat(np.arange(len(qq)), self.m)
            t = np.tile(np.arange(self.m), len(qq))
            d = closest_on_triangles(p[qq[rep]], self.a[t], self.b[t], self.c[t]).reshape(len(qq), self.m)
            j = d.argmin(axis=1)
            best[qq] = d[np.arange(len(qq)), j]
            arg[qq] = j


def newell(points, faces):
    """The vector area of each polygon (half the Newell normal): its norm is the area of a planar polygon."""
    out = np.zeros((len(faces), 3))
    for k in sorted({len(f) for f in faces}):
        sel = [i for i, f in enumerate(faces) if len(f) == k]
        idx = np.array([faces[i] for i in sel])
        p = points[idx]
        out[sel] = 0.5 * np.cross(p, np.roll(p, -1, axis=1)).sum(axis=1)
    return out


def quality(input_path, quad_path, singularities_path=None, quad_size=None, match_tolerance=1e-6):
    ip, ifaces = read_mesh(input_path)
    qp, qfaces = read_mesh(quad_path)
    if not ifaces:
        raise BadInput(f"{input_path}: no face")
    if not qfaces:
        raise BadInput(f"{quad_path}: no face")
    itris, _ = fans(ifaces)
    sizes = np.array([len(f) for f in qfaces])
    quads = [f for f in qfaces if len(f) == 4]
    diag = float(np.linalg.norm(ip.max(axis=0) - ip.min(axis=0)))
    rep = {}

    used = np.unique(np.concatenate([np.array(f) for f in qfaces]))
    rep["counts"] = {"vertices": int(len(used)), "unreferenced_vertices": int(len(qp) - len(used)),
                     "faces": len(qfaces), "quads": len(quads), "non_quads": int((sizes != 4).sum()),
                     "face_sizes": {str(k): int(v) for k, v in zip(*np.unique(sizes, return_counts=True))}}

    # edges: undirected counts and directed repeats
    directed = np.array([(f[j], f[(j + 1) % len(f)]) for f in qfaces for j in range(len(f))], np.int64)
    degenerate_faces = sum(1 for f in qfaces if len(set(f)) != len(f))
    directed = directed[directed[:, 0] != directed[:, 1]]
    und, und_count = np.unique(np.sort(directed, axis=1), axis=0, return_counts=True)
    _, dir_count = np.unique(directed, axis=0, return_counts=True)
    open_edges = und[und_count == 1]
    vector_area = newell(qp, qfaces)
    area = np.linalg.norm(vector_area, axis=1)
    degenerate_faces += int(((area == 0) & np.array([len(set(f)) == len(f) for f in qfaces])).sum())
    rep["edges"] = {"edges": int(len(und)), "open": int(len(open_edges)),
                    "non_manifold": int((und_count > 2).sum()),
                    "inconsistently_oriented": int((dir_count > 1).sum()),
                    "degenerate_faces": int(degenerate_faces)}

    # valences over the vertices not on an open edge
    valence = np.bincount(und.ravel(), minlength=len(qp))
    on_border = np.zeros(len(qp), bool)
    on_border[open_edges.ravel()] = True
    interior = np.zeros(len(qp), bool)
    interior[used] = True
    interior &= ~on_border
    hist_v, hist_c = np.unique(valence[interior], return_counts=True)
    val = {"histogram": {str(k): int(c) for k, c in zip(hist_v, hist_c)},
           "irregular": int((valence[interior] != 4).sum()), "border_vertices": int(on_border.sum())}
    if singularities_path is not None:
        sings = read_singularities(singularities_path, len(ip))
        expected = np.full(len(qp), 4.0)
        unmatched, wrong_singular = [], 0
        if sings and len(used):
            # nearest used quad vertex of each singular input vertex, by brute force (few singularities)
            up = qp[used]
            for v, k in sings:
                d = np.linalg.norm(up - ip[v], axis=1)
                j = int(d.argmin())
                if d[j] > match_tolerance * diag:
                    unmatched.append(v)
                else:
                    expected[used[j]] = float(4 - 4 * k)
        mism = interior & (valence != expected)
        singular = expected != 4
        wrong_singular = int((mism & singular).sum())
        val.update({"singularities": len(sings), "singularities_unmatched": len(unmatched),
                    "errors_away_from_singularities": int((mism & ~singular).sum()),
                    "errors_at_singularities": wrong_singular,
                    "errors": int(mism.sum()) + len(unmatched)})
    rep["valence"] = val

    # orientation against the input: normal of the input face nearest to each quad's centroid
    centroid = np.array([qp[f].mean(axis=0) for f in qfaces])
    input_tris = NearestTriangle(ip, itris)
    d_centroid, nearest = input_tris.query(centroid)
    inormal = np.cross(ip[itris[:, 1]] - ip[itris[:, 0]], ip[itris[:, 2]] - ip[itris[:, 0]])
    flipped = (np.einsum("ij,ij->i", vector_area, inormal[nearest]) < 0)
    rep["flipped"] = {"quads": int(flipped[sizes == 4].sum()), "faces": int(flipped.sum())}

    # distortion over the quads
    h_given = quad_size is not None
    if quads:
        qi = np.array(quads)
        p = qp[qi]
        e_next = np.roll(p, -1, axis=1) - p
        e_prev = np.roll(p, 1, axis=1) - p
        ln = np.linalg.norm(e_next, axis=2) * np.linalg.norm(e_prev, axis=2)
        ok = ln > 0
        cosine = np.clip(np.einsum("ijk,ijk->ij", e_next, e_prev)[ok] / ln[ok], -1.0, 1.0)
        deviation = np.abs(np.degrees(np.arccos(cosine)) - 90.0)
        qarea = area[sizes == 4]
        if quad_size is None:
            quad_size = math.sqrt(float(qarea.mean())) if qarea.mean() > 0 else diag
        rel = qarea / quad_size ** 2
        rep["distortion"] = {"angle_deviation_degrees_mean": float(deviation.mean()) if len(deviation) else None,
                             "angle_deviation_degrees_max": float(deviation.max()) if len(deviation) else None,
                             "degenerate_corners": int((~ok).sum()),
                             "area_over_h2_mean": float(rel.mean()), "area_over_h2_std": float(rel.std())}
    else:
        rep["distortion"] = None
        if quad_size is None:
            quad_size = diag
    if not quad_size > 0:
        raise BadInput(f"--quad-size must be positive, got {quad_size}")
    rep["quad_size"] = {"h": float(quad_size), "given": h_given}

    # Hausdorff distance both ways, from sample points
    samples = np.concatenate([qp[used], 0.5 * (qp[und[:, 0]] + qp[und[:, 1]])])
    forward, _ = input_tris.query(samples)
    qtris, _ = fans(qfaces)
    iused = np.unique(itris.ravel())
    backward, _ = NearestTriangle(qp, qtris).query(ip[iused])
    fwd, bwd = float(forward.max()), float(backward.max())
    rep["hausdorff"] = {"quads_to_input": fwd, "input_to_quads": bwd, "max": max(fwd, bwd),
                        "quads_to_input_mean": float(forward.mean()), "input_to_quads_mean": float(backward.mean()),
                        "max_over_h": max(fwd, bwd) / quad_size, "input_bbox_diagonal": diag}
    return rep


def text_line(rep):
    c, e, v, d, h = rep["counts"], rep["edges"], rep["valence"], rep["distortion"], rep["hausdorff"]
    s = (f"{c['vertices']} vertices, {c['quads']} quads, {c['non_quads']} non-quads; "
         f"valence errors {v['errors'] if 'errors' in v else 'n/a'} ({v['irregular']} irregular); "
         f"open edges {e['open']}, non-manifold {e['non_manifold']}, flipped quads {rep['flipped']['quads']}; ")
    if d:
        s += (f"angle deviation {d['angle_deviation_degrees_mean']:.2f} mean, {d['angle_deviation_degrees_max']:.2f} max "
              f"degrees; area/H^2 {d['area_over_h2_mean']:.3f} +- {d['area_over_h2_std']:.3f}; ")
    s += f"Hausdorff {h['max']:.3g} = {h['max_over_h']:.3f} H (H = {rep['quad_size']['h']:.4g}" + \
         ("" if rep["quad_size"]["given"] else ", sqrt of the mean quad area") + ")"
    return s


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("input_mesh")
    ap.add_argument("quad_mesh")
    ap.add_argument("--singularities")
    ap.add_argument("--quad-size", type=float)
    ap.add_argument("--match-tolerance", type=float, default=1e-6,
                    help="singular vertex to quad vertex, relative to the input's bounding box diagonal")
    ap.add_argument("--json", action="store_true", help="print the report as JSON")
    a = ap.parse_args(argv)
    try:
        if a.quad_size is not None and not a.quad_size > 0:
            raise BadInput(f"--quad-size must be positive, got {a.quad_size}")
        rep = quality(a.input_mesh, a.quad_mesh, a.singularities, a.quad_size, a.match_tolerance)
    except BadInput as e:
        print(f"quad_quality.py: {e}", file=sys.stderr)
        return 2
    print(json.dumps(rep, indent=1) if a.json else text_line(rep))
    return 0


if __name__ == "__main__":
    sys.exit(main())
