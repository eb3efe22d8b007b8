#!/usr/bin/python3
"""Renders a direction field computed by trivial_connections to a PNG picture (headless).

Input: the legacy VTK files the program writes with --vtk FIELD.vtk (mesh, per face the n directions
direction_0 ... direction_{n-1}, per vertex singularity_index) and optionally --streamlines S.vtk and
--features F.vtk (the sharp edges of --align-features, written by --feature-lines: drawn as orange lines)
and --quads Q.obj (a quad mesh of the surface, e.g. written by --quad-mesh: its edges drawn as dark lines;
the field's glyphs are then left out unless --glyphs is given).

What is drawn:
  * the mesh, shaded per face (two-sided Lambert lighting from the camera side plus ambient), with a
    darker line where the depth jumps (silhouettes, parts in front of others);
  * the field: the streamlines of S.vtk if given; otherwise glyphs on at most K visible faces spread
    evenly over the picture: the n directions of the face as short segments from its barycentre
    (for a vector field, n = 1, arrows);
  * the singular vertices as dots with a black edge, coloured by index (negative blue, positive red),
    and a legend listing every index present as a fraction, with how many of those are visible.

Occlusion: the camera is orthographic and a software z-buffer (numpy, vectorised) gives the nearest
face of every pixel: the pixel centres inside each projected triangle are found with a barycentric test
(a small tolerance so that shared edges leave no crack), faces being grouped by the size of their
projected bounding box so that each group is a dense array of candidate pixels, processed in chunks of
bounded memory; per pixel the nearest candidate wins. A face is visible iff it owns a pixel. A
streamline point or a singular vertex is visible iff its depth is within a few pixel sizes of the
nearest z-buffer depth around its pixel; streamlines are split where they become hidden.

Camera: with (a, b, up) the right-handed frame where up is the --up axis and a the next axis in cyclic
order (up = y: a = z, b = x; up = z: a = x, b = y, as in matplotlib), the eye direction (from the object
to the camera) is d = cos(el) cos(az) a + cos(el) sin(az) b + sin(el) up; the image right vector is
r = -sin(az) a + cos(az) b and the image up vector is d x r. The bounding box of the projected mesh is
fitted in the image with a margin (and room for the title).

Prints one summary line; --stats FILE also writes the numbers as JSON. Errors in an input file are
reported as 'render_field.py: FILE: reason' with exit status 1, and no output file is written.
Needs numpy and matplotlib (Debian: /usr/bin/python3 with python3-numpy, python3-matplotlib).
"""
import argparse, json, math, os, re, sys, tempfile
from fractions import Fraction

try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")     # headless: no display needed
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection
    from matplotlib.lines import Line2D
except ImportError as e:
    sys.exit(f"render_field.py: {e}: needs numpy and matplotlib (Debian: /usr/bin/python3)")

PROG = "render_field.py"
CHUNK = 1 << 22           # candidate pixels per rasterisation chunk: bounds its memory to ~200 MB
BASE = np.array([0.72, 0.80, 0.90])   # light blue-grey surface
AMBIENT = 0.35


class InputError(Exception):
    def __init__(self, path, reason):
        super().__init__(f"{path}: {reason}")


# ----------------------------------------------------------------------------------------------- input
def read_vtk(path):
    """Tokenises an ASCII legacy VTK POLYDATA file and returns its sections by keyword."""
    try:
        with open(path, encoding="ascii") as f:
            text = f.read()
    except OSError as e:
        raise InputError(path, e.strerror or str(e))
    except UnicodeDecodeError:
        raise InputError(path, "not an ASCII file")
    head = text.split("\n", 3)   # header line, free title line, ASCII, then the tokens
    if len(head) < 4 or not head[0].startswith("# vtk DataFile"):
        raise InputError(path, "not a legacy VTK file (no '# vtk DataFile' header)")
    if head[2].strip().upper() != "ASCII":
        raise InputError(path, "only ASCII legacy VTK files are supported")
    tok, p = head[3].split(), 0
    out = {"CELL_DATA": {}, "POINT_DATA": {}}
    attach = count = None

    def take(n, dtype, what):
        nonlocal p
        if n < 0 or p + n > len(tok):
            raise InputError(path, f"file ends inside {what} (expected {n} values)")
        try:
            a = np.array(tok[p:p + n], dtype=dtype)
        except ValueError:
            raise InputError(path, f"non-numeric value in {what}")
        p += n
        return a

    while p < len(tok):
        kw = tok[p].upper()
        p += 1
        if kw == "DATASET":
            if take(1, str, "DATASET")[0].upper() != "POLYDATA":
                raise InputError(path, "DATASET is not POLYDATA")
        elif kw == "POINTS":
            n = int(take(1, np.int64, "POINTS")[0]); p += 1          # skip the type
            out["POINTS"] = take(3 * n, float, "POINTS").reshape(n, 3)
        elif kw in ("POLYGONS", "LINES", "VERTICES", "TRIANGLE_STRIPS"):
            n, size = take(2, np.int64, kw)
            flat, cells, q = take(int(size), np.int64, kw), [], 0
            for _ in range(n):      # variable-length cells 'm i0 ... i(m-1)'
                if q >= len(flat) or flat[q] < 0 or q + 1 + flat[q] > len(flat):
                    raise InputError(path, f"{kw}: cell sizes do not match the declared size {size}")
                cells.append(flat[q + 1:q + 1 + flat[q]]); q += 1 + flat[q]
            out[kw] = cells
        elif kw in ("CELL_DATA", "POINT_DATA"):
            attach, count = kw, int(take(1, np.int64, kw)[0])
        elif kw in ("VECTORS", "NORMALS", "SCALARS"):
            if attach is None:
                raise InputError(path, f"{kw} before CELL_DATA or POINT_DATA")
            name = take(1, str, kw)[0]; p += 1                           # skip the type
            ncomp = 3
            if kw == "SCALARS":
                ncomp = int(take(1, np.int64, kw)[0]) if p < len(tok) and tok[p].isdigit() else 1
                if p < len(tok) and tok[p].upper() == "LOOKUP_TABLE":
                    p += 2
            out[attach][name] = take(count * ncomp, float, f"{kw} {name}").reshape(count, ncomp)
        else:
            raise InputError(path, f"unexpected token '{tok[p - 1]}'")
    if "POINTS" not in out:
        raise InputError(path, "no POINTS")
    if not np.isfinite(out["POINTS"]).all():
        raise InputError(path, "non-finite point coordinates")
    for kw in ("POLYGONS", "LINES"):
        if any(len(c) and (c.min() < 0 or c.max() >= len(out["POINTS"])) for c in out.get(kw, [])):
            raise InputError(path, f"{kw}: point index out of range")
    return out


def load_field(path):
    d = read_vtk(path)
    polys = d.get("POLYGONS")
    if not polys:
        raise InputError(path, "no POLYGONS")
    if any(len(c) != 3 for c in polys):
        raise InputError(path, "POLYGONS: only triangles are supported")
    tris = np.array(polys, dtype=np.int64).reshape(-1, 3)
    dirs = {int(m.group(1)): a for name, a in d["CELL_DATA"].items()
            if (m := re.fullmatch(r"direction_(\d+)", name))}
    if not dirs:
        raise InputError(path, "no CELL_DATA vectors direction_0 ...")
    if any(len(a) != len(tris) for a in dirs.values()):
        raise InputError(path, "CELL_DATA count differs from the number of POLYGONS")
    sing = d["POINT_DATA"].get("singularity_index", np.zeros((len(d["POINTS"]), 1)))
    if sing.shape != (len(d["POINTS"]), 1):
        raise InputError(path, "singularity_index: one value per point expected")
    return d["POINTS"], tris, [dirs[k] for k in sorted(dirs)], sing[:, 0]


def load_quads(path):
    """The vertices and the undirected edges of the polygons of an OBJ file ('v x y z', 'f i j k ...' with
    1-based or negative indices, 'i/t/n' tokens allowed), as (points, [[a, b], ...])."""
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise InputError(path, e.strerror or str(e))
    points, edges = [], set()
    for number, line in enumerate(lines, 1):
        tok = line.split("#", 1)[0].split()
        if not tok:
            continue
        try:
            if tok[0] == "v":
                points.append([float(t) for t in tok[1:4]])
                if len(tok) < 4:
                    raise ValueError
            elif tok[0] == "f":
                ids = [int(t.split("/")[0]) for t in tok[1:]]
                ids = [i - 1 if i > 0 else len(points) + i for i in ids]
                if len(ids) < 3 or min(ids) < 0 or max(ids) >= len(points):
                    raise InputError(path, f"line {number}: a face of fewer than 3 vertices or an index out of range")
                for a, b in zip(ids, ids[1:] + ids[:1]):
                    edges.add((min(a, b), max(a, b)))
        except ValueError:
            raise InputError(path, f"line {number}: not a number")
    P = np.array(points, dtype=float).reshape(-1, 3)
    if not len(edges):
        raise InputError(path, "no face")
    if not np.isfinite(P).all():
        raise InputError(path, "non-finite vertex coordinates")
    return P, [np.array(e) for e in sorted(edges)]


def load_streamlines(path):
    d = read_vtk(path)
    if "LINES" not in d:
        raise InputError(path, "no LINES")
    return d["POINTS"], [c for c in d["LINES"] if len(c) >= 2]


# --------------------------------------------------------------------------------------------- camera
class Camera:
    def __init__(self, V, az, el, up, W, H, top):
        i = "xyz".index(up[-1])
        u = np.eye(3)[i] * (-1 if up.startswith("-") else 1)
        a = np.eye(3)[(i + 1) % 3]
        b = np.cross(u, a)
        az, el = math.radians(az), math.radians(el)
        self.d = math.cos(el) * (math.cos(az) * a + math.sin(az) * b) + math.sin(el) * u
        self.r = -math.sin(az) * a + math.cos(az) * b
        self.c = np.cross(self.d, self.r)
        sx, sy = V @ self.r, V @ self.c
        margin = 0.05 * min(W, H)
        span_x, span_y = max(np.ptp(sx), 1e-12), max(np.ptp(sy), 1e-12)
        self.scale = min((W - 2 * margin) / span_x, (H - 2 * margin - top) / span_y)
        self.cx, self.cy = (sx.min() + sx.max()) / 2, (sy.min() + sy.max()) / 2
        self.ox, self.oy = W / 2, (H + top) / 2

    def project(self, P):
        """Pixel coordinates (x right, y down, pixel (i, j) covers [j, j+1) x [i, i+1)) and depth
        (world units, smaller is nearer)."""
        x = self.ox + (P @ self.r - self.cx) * self.scale
        y = self.oy - (P @ self.c - self.cy) * self.scale
        return x, y, -(P @ self.d)


def zbuffer(x, y, z, tris, W, H):
    """Per pixel, the depth and the id of the nearest face (-1: background); per face, the norm of
    the depth gradient in world units per pixel."""
    depth, owner = np.full(W * H, np.inf), np.full(W * H, -1, dtype=np.int64)
    X, Y, Z = x[tris], y[tris], z[tris]
    # pixels whose centre (j + 0.5, i + 0.5) lies in the face's bounding box
    j0 = np.maximum(np.ceil(X.min(1) - 0.5 - 1e-9), 0).astype(np.int64)
    j1 = np.minimum(np.floor(X.max(1) - 0.5 + 1e-9), W - 1).astype(np.int64)
    i0 = np.maximum(np.ceil(Y.min(1) - 0.5 - 1e-9), 0).astype(np.int64)
    i1 = np.minimum(np.floor(Y.max(1) - 0.5 + 1e-9), H - 1).astype(np.int64)
    ex1, ey1, ex2, ey2 = X[:, 1] - X[:, 0], Y[:, 1] - Y[:, 0], X[:, 2] - X[:, 0], Y[:, 2] - Y[:, 0]
    det = ex1 * ey2 - ex2 * ey1
    ok = (j1 >= j0) & (i1 >= i0) & (np.abs(det) > 1e-12)   # edge-on faces cover no area
    det = np.where(ok, det, 1.0)
    qbits = 62 - (W * H).bit_length()       # depth quantised to >= 2^34 levels, ties are harmless
    zlo, zq = Z.min(), (2 ** qbits - 1) / max(np.ptp(Z), 1e-300)
    # classes of 1, 2, 4, ... by 1, 2, 4, ... pixels: a class is a dense (faces x sw*sh) candidate array
    # with at least a quarter of the candidates in the face's bounding box
    lw = np.ceil(np.log2(np.maximum(j1 - j0, 0) + 1)).astype(np.int64)
    lh = np.ceil(np.log2(np.maximum(i1 - i0, 0) + 1)).astype(np.int64)
    cls = lw * 64 + lh
    for c in np.unique(cls[ok]):
        sw, sh = 1 << int(c // 64), 1 << int(c % 64)
        dj, di = np.tile(np.arange(sw), sh), np.repeat(np.arange(sh), sw)
        faces, step = np.flatnonzero(ok & (cls == c)), max(1, CHUNK // (sw * sh))
        for start in range(0, len(faces), step):
            f = faces[start:start + step]
            jj, ii = j0[f, None] + dj, i0[f, None] + di
            keep = (jj <= j1[f, None]) & (ii <= i1[f, None])
            ff = np.broadcast_to(f[:, None], keep.shape)[keep]
            jj, ii = jj[keep], ii[keep]
            px, py = jj + 0.5 - X[ff, 0], ii + 0.5 - Y[ff, 0]
            l1 = (px * ey2[ff] - ex2[ff] * py) / det[ff]
            l2 = (ex1[ff] * py - px * ey1[ff]) / det[ff]
            inside = (l1 >= -1e-7) & (l2 >= -1e-7) & (l1 + l2 <= 1 + 1e-7)
            ff, l1, l2 = ff[inside], l1[inside], l2[inside]
            pix = ii[inside] * W + jj[inside]
            if not len(pix):        # slivers between pixel centres
                continue
            zz = Z[ff, 0] + l1 * (Z[ff, 1] - Z[ff, 0]) + l2 * (Z[ff, 2] - Z[ff, 0])
            # sort by (pixel, depth) as one integer key (3x faster than lexsort): the first is the nearest
            order = np.argsort((pix << qbits) | ((zz - zlo) * zq).astype(np.int64))
            pix, zz, ff = pix[order], zz[order], ff[order]
            first = np.r_[True, pix[1:] != pix[:-1]]
            pix, zz, ff = pix[first], zz[first], ff[first]
            nearer = zz < depth[pix]
            depth[pix[nearer]], owner[pix[nearer]] = zz[nearer], ff[nearer]
    ez1, ez2 = Z[:, 1] - Z[:, 0], Z[:, 2] - Z[:, 0]
    grad = np.hypot(ez1 * ey2 - ez2 * ey1, ez2 * ex1 - ez1 * ex2) / np.abs(det)
    return depth.reshape(H, W), owner.reshape(H, W), grad


def visible(x, y, z, depth, owner, grad, tol):
    """Depth test of points lying on the surface. The z-buffer holds the depth at pixel centres, up to
    0.7 pixel away from the point, possibly on a neighbouring face: the tolerance grows with the depth
    slope of the pixel's face, or grazing faces near silhouettes would hide what lies on them. A point
    on a background pixel (on a silhouette) is tested against the covered pixels around it."""
    H, W = depth.shape
    limit = np.where(owner >= 0, depth + tol + 1.5 * grad[owner], np.inf)
    j, i = np.floor(x).astype(np.int64), np.floor(y).astype(np.int64)
    inside = (j >= 0) & (j < W) & (i >= 0) & (i < H)
    j, i = j[inside], i[inside]
    own = limit[i, j]
    around = np.min([limit[np.clip(i + a, 0, H - 1), np.clip(j + b, 0, W - 1)]
                     for a in (-1, 0, 1) for b in (-1, 0, 1)], axis=0)
    out = np.zeros(len(x), dtype=bool)
    out[inside] = z[inside] <= np.where(np.isfinite(own), own, around)
    return out


def shade(V, tris, cam, depth, owner, jump):
    n = np.cross(V[tris[:, 1]] - V[tris[:, 0]], V[tris[:, 2]] - V[tris[:, 0]])
    n /= np.maximum(np.linalg.norm(n, axis=1), 1e-300)[:, None]
    light = cam.d + 0.3 * cam.c - 0.2 * cam.r          # from the camera side, slightly up-left
    light /= np.linalg.norm(light)
    lum = AMBIENT + (1 - AMBIENT) * np.abs(n @ light)   # two-sided: open meshes show their back
    img = np.ones(owner.shape + (3,))
    hit = owner >= 0
    img[hit] = BASE * lum[owner[hit]][:, None]
    # darken the nearer side of depth jumps (silhouettes and overlaps) so that shapes read well
    d, edge = depth, np.zeros(owner.shape, dtype=bool)
    with np.errstate(invalid="ignore"):                 # inf - inf between background pixels
        h, v = np.abs(d[:, 1:] - d[:, :-1]) > jump, np.abs(d[1:] - d[:-1]) > jump
    edge[:, 1:] |= h & (d[:, 1:] <= d[:, :-1]); edge[:, :-1] |= h & (d[:, :-1] < d[:, 1:])
    edge[1:] |= v & (d[1:] <= d[:-1]); edge[:-1] |= v & (d[:-1] < d[1:])
    img[edge & hit] *= 0.45
    return img


def fraction(k):
    q = Fraction(k).limit_denominator(1000)
    return ("+" if q > 0 else "") + str(q)


# ----------------------------------------------------------------------------------------------- main
def write_atomically(path, write, mode):
    """Writes through a temporary file in the same directory: PATH is complete or untouched."""
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)), prefix=".render_field.")
    try:
        with os.fdopen(fd, mode) as fh:
            write(fh)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)      # mkstemp creates it private
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def render(a):
    V, tris, dirs, sing = load_field(a.field)
    stream = load_streamlines(a.streamlines) if a.streamlines else None
    if a.glyphs is None:
        a.glyphs = 0 if a.quads else 1500
    W, H = a.size
    top = 0.06 * H if a.title else 0
    cam = Camera(V, a.view[0], a.view[1], a.up, W, H, top)
    x, y, z = cam.project(V)
    depth, owner, grad = zbuffer(x, y, z, tris, W, H)
    tol = 3.0 / cam.scale                               # a few pixel sizes, in world units
    img = shade(V, tris, cam, depth, owner, 10 * tol)
    vis_faces = np.unique(owner[owner >= 0])

    dpi = 100
    fig = plt.figure(figsize=(W / dpi, H / dpi), dpi=dpi)
    ax = fig.add_axes([0, 0, 1, 1])
    ax.imshow(img, extent=(0, W, H, 0), interpolation="nearest")   # row 0 at the top: y points down
    ax.set_xlim(0, W); ax.set_ylim(H, 0); ax.axis("off")
    lw = 0.7 * max(min(W, H) / 900, 0.5)
    st = {"faces": len(tris), "visible_faces": len(vis_faces), "streamline_segments": 0,
          "visible_streamline_segments": 0, "glyphs": 0}

    def draw_lines(Q, lines, colour, width):
        """Draws the visible parts of polylines; returns (segments, visible segments)."""
        if not lines:
            return 0, 0
        cat = np.concatenate(lines)
        line_id = np.repeat(np.arange(len(lines)), [len(c) for c in lines])
        qx, qy, qz = cam.project(Q[cat])
        vis = visible(qx, qy, qz, depth, owner, grad, tol)
        seg = line_id[1:] == line_id[:-1]           # consecutive points of the same polyline
        seg_vis = np.flatnonzero(seg & vis[1:] & vis[:-1])
        runs = np.split(seg_vis, np.flatnonzero(np.diff(seg_vis) != 1) + 1) if len(seg_vis) else []
        xy = np.column_stack([qx, qy])
        ax.add_collection(LineCollection([xy[r[0]:r[-1] + 2] for r in runs], colors=colour,
                                         linewidths=width, capstyle="round", joinstyle="round", zorder=2))
        return int(seg.sum()), len(seg_vis)

    if stream is not None:
        st["streamline_segments"], st["visible_streamline_segments"] = draw_lines(*stream, "#1c1c28", lw)
    else:
        # one glyph per cell of a screen grid sized for K glyphs: even density, visible faces only
        cover = max(int((owner >= 0).sum()), 1)
        step = max(math.sqrt(cover / max(a.glyphs, 1)), 1.0)
        gi = np.arange(step / 2, H, step).astype(np.int64)
        gj = np.arange(step / 2, W, step).astype(np.int64)
        f = np.unique(owner[np.ix_(gi, gj)])
        f = f[f >= 0]
        if len(f) > a.glyphs:
            f = f[np.linspace(0, len(f) - 1, a.glyphs).astype(np.int64)]
        edges = V[tris[:, [1, 2, 0]]] - V[tris]
        # barycentres of neighbouring faces are ~0.6 mean edge apart: keep glyphs from touching
        # (an arrow, n = 1, has no opposite arm and may be longer)
        mean_edge = np.linalg.norm(edges, axis=2).mean() * cam.scale
        length = (0.6 if len(dirs) == 1 else 0.4) * max(0.6 * mean_edge, step)
        bx, by, _ = cam.project(V[tris[f]].mean(axis=1))
        # screen vectors of the n directions (foreshortened like the surface); image y points down
        vec = [length * np.column_stack([D[f] @ cam.r, -(D[f] @ cam.c)]) for D in dirs]
        if len(f) and len(dirs) == 1:      # a vector field: arrows, so that the orientation shows
            ax.quiver(bx, by, vec[0][:, 0], vec[0][:, 1], angles="xy", scale_units="xy", scale=1,
                      units="xy", width=np.clip(length / 14, 0.8, 2.0), color="#1c1c28",
                      headwidth=4, headlength=4.5, headaxislength=4)
        elif len(f):
            base = np.column_stack([bx, by])
            segs = np.concatenate([np.stack([base, base + v], axis=1) for v in vec])
            ax.add_collection(LineCollection(segs, colors="#1c1c28", linewidths=lw))
        st["glyphs"] = len(f)

    if a.quads:      # the quad mesh's edges, over the field
        st["quad_edges"], st["visible_quad_edges"] = draw_lines(*load_quads(a.quads), "#1c1c28", lw)
    if a.features:   # the feature curves (trivial_connections --feature-lines), over the field
        st["feature_segments"], st["visible_feature_segments"] = draw_lines(*load_streamlines(a.features),
                                                                            "#e8770e", 2.2 * lw)
    si = np.flatnonzero(np.abs(sing) > 1e-9)
    sx, sy, sz = cam.project(V[si])
    svis = visible(sx, sy, sz, depth, owner, grad, tol)
    st["singularities"], st["visible_singularities"] = len(si), int(svis.sum())
    if len(si):
        kmax = np.abs(sing[si]).max()
        # saturated by sign even for small indices, darker for larger ones
        colour = lambda k: plt.cm.coolwarm(0.5 + 0.5 * np.sign(k) * (0.45 + 0.55 * abs(k) / kmax))
        size = 110 * (min(W, H) / 900) ** 2
        if svis.any():    # an empty scatter would still draw a stray marker at the origin
            ax.scatter(sx[svis], sy[svis], s=size, c=[colour(k) for k in sing[si][svis]],
                       edgecolors="black", linewidths=1.2 * lw, zorder=3)
        handles = []
        for k in sorted(set(np.round(sing[si], 9)), reverse=True):
            m = np.abs(sing[si] - k) < 1e-6
            label = f"{fraction(k)}   ({int((m & svis).sum())} of {int(m.sum())} visible)"
            handles.append(Line2D([], [], ls="", marker="o", ms=math.sqrt(size), mfc=colour(k),
                                  mec="black", label=label))
        font = 10 * max(min(W, H) / 900, 0.6)
        ax.legend(handles=handles, title="singularity index", loc="upper right", framealpha=0.85,
                  fontsize=font, title_fontsize=font)
    if a.title:
        ax.text(W / 2, 0.02 * H, a.title, ha="center", va="top", fontsize=14 * max(min(W, H) / 900, 0.6))

    try:
        write_atomically(a.output, lambda fh: fig.savefig(fh, dpi=dpi, format="png"), "wb")
    finally:
        plt.close(fig)
    st.update(width=W, height=H, n=len(dirs))
    return st


def main():
    ap = argparse.ArgumentParser(prog=PROG, description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("field", help="field file written by trivial_connections --vtk")
    ap.add_argument("--streamlines", metavar="S.vtk",
                    help="streamlines written by --streamlines (else glyphs are drawn)")
    ap.add_argument("--features", metavar="F.vtk",
                    help="feature curves written by --feature-lines, drawn as orange lines")
    ap.add_argument("--quads", metavar="Q.obj",
                    help="a quad mesh of the surface (OBJ, e.g. written by --quad-mesh): its edges are drawn")
    ap.add_argument("-o", "--output", required=True, metavar="OUT.png", help="the picture to write")
    ap.add_argument("--view", nargs=2, type=float, default=(35.0, 25.0), metavar=("AZIMUTH", "ELEVATION"),
                    help="camera angles in degrees (default 35 25)")
    ap.add_argument("--up", default="y", choices=["x", "y", "z", "-x", "-y", "-z"],
                    help="world axis pointing up in the picture (default y)")
    ap.add_argument("--size", nargs=2, type=int, default=(1200, 900), metavar=("W", "H"),
                    help="picture size in pixels (default 1200 900)")
    ap.add_argument("--title", help="title drawn at the top")
    ap.add_argument("--glyphs", type=int, default=None, metavar="K",
                    help="at most K glyphs when no streamlines are given (default 1500; 0 with --quads)")
    ap.add_argument("--stats", metavar="FILE", help="also write the summary numbers as JSON")
    a = ap.parse_args()
    if min(a.size) < 16 or max(a.size) > 16384:
        ap.error("--size: each side must be between 16 and 16384 pixels")
    if a.glyphs is not None and a.glyphs < 0:
        ap.error("--glyphs must be >= 0")
    try:
        st = render(a)
    except InputError as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return 1
    except OSError as e:      # writing the picture (input files raise InputError)
        print(f"{PROG}: {a.output}: {e.strerror or e}", file=sys.stderr)
        return 1
    print(f"{st['faces']} faces ({st['visible_faces']} visible), singularities {st['singularities']} "
          f"({st['visible_singularities']} visible), streamline segments {st['streamline_segments']} "
          f"({st['visible_streamline_segments']} drawn), glyphs {st['glyphs']}, "
          + (f"quad edges {st['quad_edges']} ({st['visible_quad_edges']} drawn), " if a.quads else "")
          + f"{a.size[0]}x{a.size[1]} -> {a.output}")
    if a.stats:
        try:
            write_atomically(a.stats, lambda fh: json.dump(st, fh, indent=1), "w")
        except OSError as e:
            print(f"{PROG}: {a.stats}: {e.strerror or e}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
