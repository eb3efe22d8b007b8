#!/usr/bin/python3
"""The field editor's server: one mesh, its prefactored solver, a page.

    PYTHONPATH=build/python python3 editor/serve.py MESH [--n N] [--port P] [--bundle DIR] [--folder DIR]

Binds 127.0.0.1 only. Serves its page (editor/web/index.html and the bundle the build made, DIR/editor.js with
its source map DIR/editor.js.map: these three files by name, never a path taken from the URL) and the mesh it was
given; every edit the page sends is a solve on the solver factored once at start. Arrays travel
as binary (see `frame`), never as JSON numbers. The only files it reads or writes for the page are in --folder
(default: the current directory at start).

API. Requests are JSON objects (UTF-8, sent with a Content-Length); replies are frames (`frame`: a JSON header,
then arrays), or, when refused, a text/plain line giving the reason: 400 malformed request (not JSON, not an object,
nested too deeply, an integer of more than {MAX_DIGITS} digits, NaN or Infinity, a field of the wrong type, a bad
Content-Length or a body shorter than it), 403 a path outside the folder or the mesh itself, 404 unknown URL or
missing file, 405 a method the URL does not take (with an Allow header), 408 the body did not arrive within
{BODY_TIMEOUT} seconds, 409 saving over an existing file without "overwrite": true, 411 a POST without Content-Length
(a chunked body is not read), 413 a body longer than max_body (see Size below), 422 refused by the library
("code: message", e.g. "poincare_hopf_violated: ..."). GET and HEAD (the headers of the GET) on the page, its
bundle and the mesh, POST on the rest.
  GET  /api/mesh         header {vertices, faces, n, chi, closed (per component), singularities (placed at start)};
                         arrays V <f4 (V, 3), F <u4 (F, 3), component <i4 (V,) (-1: no face), boundary <u4 (b, 2)
                         (boundary edges), angle_defect <f4 (V,) (2 pi minus the corner angles at the vertex)
  POST /api/place        {n?, align_boundary?, constraints?}: automatic placement -> header {n, singularities}: the
                         singularities of the smoothest n-direction field that follows the constrained faces'
                         directions (and the boundary, with align_boundary), as the module's place_singularities()
  POST /api/features     {threshold?, n?, align_boundary?}: the pins of the sharp features (the module's
                         feature_aligned_faces(): the faces beside the feature curves whose normals differ by more than
                         `threshold` degrees, default {DEFAULT_FEATURE_ANGLE}, each pinned to the curve's direction)
                         -> header {threshold, constraints: [[f, [x, y, z]]] (increasing f; with align_boundary,
                         none on the boundary: the field follows the boundary there), on_aligned_boundary (the
                         faces left out for it), report (the module's dict: number_of_sharp_edges, number_of_curves,
                         disagreeing_pairs, ...)}. A threshold that is not a number is a 400, one outside [0, 180]
                         a 422 (invalid_argument). The page adds them where the user has no pin of their own (the
                         user's pins win)
  POST /api/solve        {SOLVE} -> header {n, energy, max_residual, timings, constraints}; array angle <f4 (F,):
                         one direction per face, as its angle counter-clockwise from the face's first edge (F[f, 0]
                         to F[f, 1]) about its normal (the page turns it by 2 pi / n for the others). constraints: the
                         solve's report on the paths joining the request's constrained faces (to each other or to
                         the aligned boundary): [{component, from_face, to_face, length, period, residual,
                         decided (True: a link between touching pins, its integer by rounding)}]
  POST /api/streamlines  {SOLVE, seeds?} -> header {n, energy, lines, seeds, maximum_faces_per_ray, timings};
                         arrays points <f4 (k, 3), offsets <u4 (lines + 1,): line i is points[offsets[i]:offsets[i+1]].
                         seeds: the number of seed faces asked for (1 to {MAX_SEEDS}, default
                         min(faces, {DEFAULT_SEEDS})), spread over the mesh the same way every time; header seeds:
                         the number used. The rays are cut (to maximum_faces_per_ray faces, at least 8), then seeds
                         left out, so that all of them cross at most {RAY_STEPS} faces: about half a second at most
                         on 100k faces
  POST /api/save         {kind, path, overwrite?, SOLVE, seeds?}: solves, then writes (completely or not at all)
                         `path` in the folder -> header {saved: the path relative to the folder, bytes}. kind:
                         "singularities", "constraints" (lines "f x y z"), "field" (the program's field file, path
                         ending in .txt), "vtk" / "ply" (mesh and field for a viewer, path ending in .vtk / .ply),
                         "streamlines" (VTK lines, as /api/streamlines). An existing file is replaced only with
                         overwrite: true (default false: 409, the page asks first; the new file is linked into place,
                         which fails if one appeared meanwhile). The mesh being edited is never replaced, even with
                         overwrite (403): neither its path nor another name of it (symbolic or hard link)
  POST /api/load         {kind: "singularities" | "constraints", path} -> header {singularities: [[v, "p/q"]]} or
                         {constraints: [[f, [x, y, z]]]}, in file order, checked by the library's readers against the
                         mesh (vertex and face numbers in range, no repeat)
SOLVE: n (1 to {MAX_N}, default --n); singularities [[vertex, "p/q" or integer]] (default []: each vertex once, a
vertex listed twice is a 422 duplicate_singularity, never last-wins); constraints
[[face, [x, y, z]]] (default []: faces in range and each once, a face listed twice is a 422 invalid_constraint
(the library's code for it); directions three finite numbers, not all zero; the field points along the direction
projected onto the face); align_boundary (default false: true follows the boundary, with a second solver made on
first use; on a mesh without boundary it is the same solve).
Paths (save, load): a non-empty relative path; with symbolic links resolved it must lie in the folder (403
otherwise); to save, its directory must exist (404), it must not be the mesh (403) and, if it exists, it must be a
regular file (400) and overwrite must be true (409); to load, it must be a regular file (404 if missing, 400
otherwise, 413 above {MAX_LOAD}). Nothing is written when a request is refused.
Constraints and alignment: each solver (plain, aligned) keeps the constrained faces of its last request; a request
with another set of faces calls set_constraints() first (cheap: pins cost about what the faces they pin cost, and
thousands are fine), under a lock held until its solve is done, so concurrent requests each get their own answer.
Size: there is no limit on the number of pins other than one per face; the body of a request is limited to
max_body bytes ({MAX_BODY} plus {BODY_PER_FACE} per face of the mesh: every face pinned with 17-digit numbers fits),
because it is read whole into memory and parsed before anything is checked.
"""
import argparse
import collections
import errno
import http.server
import json
import math
import os
import struct
import sys
import tempfile
import threading
import time
import traceback

import numpy as np
import trivial_connections as tc

MAX_BODY = 1 << 20  # bytes of a request body, plus BODY_PER_FACE per face of the mesh (Session.max_body)
BODY_PER_FACE = 128  # a pin [f, [x, y, z]] with 17-digit numbers takes ~80 bytes: every face can be pinned
MAX_SEEDS = 100000
DEFAULT_SEEDS = 3000
RAY_STEPS = 500_000  # faces crossed by all the rays of a streamline request together, at most (~0.5 s at worst)
MAX_LOAD = 64 << 20  # bytes of a file to load
MAX_N = 64  # the largest symmetry order n a request may ask for
MAX_DIGITS = 1000  # digits of an integer in a request (Python refuses to convert more than 4300: a ValueError)
BODY_TIMEOUT = 30  # seconds for a request body to arrive once its headers have (408 after)
# save kinds: the ending their path must have ("" for any)
SAVE_KINDS = {"singularities": "", "constraints": "", "field": ".txt", "vtk": ".vtk", "ply": ".ply",
              "streamlines": ""}
HERE = os.path.dirname(os.path.abspath(__file__))


def megabytes(size):
    return f"{size / (1 << 20):g} MB"


# the limits the docstring states, as it states them: written into it from the constants (its {NAME}s), so that
# the text (and --help) says what the code does
DOCUMENTED = {"MAX_DIGITS": MAX_DIGITS, "BODY_TIMEOUT": BODY_TIMEOUT, "MAX_SEEDS": MAX_SEEDS,
              "DEFAULT_SEEDS": DEFAULT_SEEDS, "RAY_STEPS": RAY_STEPS, "MAX_N": MAX_N, "MAX_LOAD": megabytes(MAX_LOAD),
              "MAX_BODY": megabytes(MAX_BODY), "BODY_PER_FACE": f"{BODY_PER_FACE} bytes",
              "DEFAULT_FEATURE_ANGLE": f"{tc.DEFAULT_FEATURE_ANGLE:g}"}
for _name, _value in DOCUMENTED.items():
    __doc__ = __doc__.replace("{" + _name + "}", str(_value))


class Refusal(Exception):
    """a request refused with an HTTP status and a one-line reason"""

    def __init__(self, status, reason):
        super().__init__(reason)
        self.status = status


def shown(value, limit=80):
    """repr(value), cut to `limit` characters for a message"""
    r = repr(value)
    return r if len(r) <= limit else r[:limit - 3] + "..."


def json_safe(value):
    """value with numpy scalars as Python numbers and non-finite floats as None (JSON.parse has no NaN)"""
    if isinstance(value, dict):
        return {str(k): json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def frame(header, arrays):
    """b"TCB1", the JSON header's length (uint32, little endian), the header, then each array (little endian, each
    at a multiple of 8 bytes); the header lists them: {"arrays": [{"name", "dtype", "shape", "offset"}]}.
    `arrays`: pairs (name, array), or triples (name, array, dtype) to convert it to dtype as it is copied in.
    Returns one preallocated bytearray: each array is copied once, straight into place."""
    entries, sources, offset = [], [], 0
    for name, a, *dtype in arrays:
        a = np.asarray(a)
        dt = np.dtype(dtype[0]) if dtype else a.dtype
        entries.append({"name": name, "dtype": dt.str, "shape": list(a.shape), "offset": offset})
        sources.append((a, dt, offset))
        offset += -(-a.size * dt.itemsize // 8) * 8
    head = json.dumps(dict(header, arrays=entries)).encode()
    head += b" " * (-(8 + len(head)) % 8)
    start = 8 + len(head)
    out = bytearray(start + offset)  # zeros: the padding
    out[:4] = b"TCB1"
    struct.pack_into("<I", out, 4, len(head))
    out[8:start] = head
    for a, dt, at in sources:
        if a.size:
            np.copyto(np.frombuffer(out, dt, a.size, start + at).reshape(a.shape), a, casting="unsafe")
    return out


def angle_defects(V, F):
    """per vertex, 2 pi minus the sum of its corner angles (2 pi for a vertex of no face); vectorised"""
    P = V[F]
    angles = np.empty(F.shape)
    for k in range(3):
        a, b = P[:, (k + 1) % 3] - P[:, k], P[:, (k + 2) % 3] - P[:, k]
        angles[:, k] = np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b))
    return 2 * np.pi - np.bincount(F.ravel(), weights=angles.ravel(), minlength=len(V))


def components_of(V, F):
    """per vertex, its component (of the faces' edge graph), and per component its Euler characteristic"""
    parent = np.arange(len(V))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b, c in F:
        ra, rb, rc = root(a), root(b), root(c)
        parent[rb] = ra
        parent[rc] = ra
    roots = np.array([root(i) for i in range(len(V))])
    used = np.zeros(len(V), bool)
    used[F.ravel()] = True
    labels = {r: k for k, r in enumerate(sorted(set(roots[used].tolist())))}
    component = np.array([labels.get(r, -1) if u else -1 for r, u in zip(roots, used)])
    edges = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    edges = np.unique(edges, axis=0)
    chi = np.zeros(len(labels), int)
    np.add.at(chi, component[used], 1)
    np.add.at(chi, component[edges[:, 0]], -1)
    np.add.at(chi, component[F[:, 0]], 1)
    return component, chi


Problem = collections.namedtuple("Problem", "n singularities faces directions align_boundary")
Problem.__doc__ = """a solve request, checked: n, {vertex: "p/q"}, the constrained faces (int64 (k,)) and their
directions (float64 (k, 3)) in request order, align_boundary"""


class Solver_state:
    """a solver and the constrained faces it has (sorted; None: unknown after a failure); its lock is held from
    set_constraints() to the end of the solve, so that each request gets the answer of its own constraints"""

    def __init__(self, solver):
        self.solver = solver
        self.faces = ()
        self.lock = threading.Lock()


class Session:
    def __init__(self, path, n, folder=None):
        self.path = os.path.abspath(path)
        self.solver = tc.Solver.from_file(path)
        # the mesh, never replaced by a save: its real path and its file (device, inode) at start
        self.mesh_real = os.path.realpath(path)
        stat = os.stat(path)
        self.mesh_file = (stat.st_dev, stat.st_ino)
        self.V, self.F = self.solver.vertices, self.solver.faces
        self.n = n
        self.folder = os.path.realpath(os.getcwd() if folder is None else folder)
        self.component, self.chi = components_of(self.V, self.F)
        # each face's frame: e1 along its first edge F[f, 0] -> F[f, 1], e2 = normal x e1 (counter-clockwise)
        a, b, c = (self.V[self.F[:, k]] for k in range(3))
        self.e1 = (b - a) / np.linalg.norm(b - a, axis=1)[:, None]
        normal = np.cross(b - a, c - a)
        self.e2 = np.cross(normal / np.linalg.norm(normal, axis=1)[:, None], self.e1)
        self.closed = [True] * len(self.chi)
        for loop in self.solver.loops:
            if loop["kind"] == "boundary":
                self.closed[loop["component"]] = False
        self.has_boundary = not all(self.closed)
        self.initial, _ = self.solver.place_singularities(n=n)
        self.plain = Solver_state(self.solver)
        self.aligned = None  # the solver with align_boundary=True, made on first use (on a mesh with boundary)
        self.aligned_lock = threading.Lock()
        self.seeds = {}  # number of seeds asked -> the seed faces
        self.seeds_lock = threading.Lock()
        self.mesh_bytes = None
        self.max_body = MAX_BODY + BODY_PER_FACE * len(self.F)
        # the faces with an edge on the boundary (feature pins are left off them when the field follows it)
        edges = np.sort(np.concatenate([self.F[:, [0, 1]], self.F[:, [1, 2]], self.F[:, [2, 0]]]), axis=1)
        _, inverse, count = np.unique(edges, axis=0, return_inverse=True, return_counts=True)
        self.boundary_face = (count[inverse.ravel()] == 1).reshape(3, -1).any(axis=0)
        self.features = {}  # (threshold, n) -> (faces, directions, report) of feature_aligned_faces()
        self.features_lock = threading.Lock()

    def symmetry_order(self, request):
        """n of a request (a JSON object), checked"""
        if not isinstance(request, dict):
            raise ValueError("the body must be a JSON object")
        n = request.get("n", self.n)
        if not isinstance(n, int) or isinstance(n, bool) or not 1 <= n <= MAX_N:
            raise ValueError(f"n must be an integer from 1 to {MAX_N}, got {shown(n)}")
        return n

    def align_boundary(self, request):
        align = request.get("align_boundary", False)
        if not isinstance(align, bool):
            raise ValueError(f"align_boundary must be true or false, got {shown(align)}")
        return align

    def constraints(self, items):
        """the constrained faces (int64 (k,)) and their directions (float64 (k, 3)) of a request's list
        [[face, [x, y, z]]], checked: 400 for a malformed list, 422 for values the solver cannot take"""
        if not isinstance(items, list):
            raise ValueError(f"constraints must be a list of [face, [x, y, z]], got {shown(items)}")
        nf = len(self.F)
        faces = np.empty(len(items), np.int64)
        directions = np.empty((len(items), 3))
        for i, item in enumerate(items):
            if not (isinstance(item, list) and len(item) == 2 and type(item[0]) is int
                    and isinstance(item[1], list) and len(item[1]) == 3
                    and all(type(c) in (int, float) for c in item[1])):
                raise ValueError(f"a constraint must be [face, [x, y, z]], got {shown(item)}")
            if not 0 <= item[0] < nf:
                raise Refusal(422, f"invalid_constraint: face {item[0]} does not exist (the mesh has {nf} faces)")
            faces[i] = item[0]
            try:
                directions[i] = item[1]
            except OverflowError:
                directions[i] = math.inf
        bad = np.flatnonzero(~np.isfinite(directions).all(axis=1))
        if bad.size:
            raise Refusal(422, f"invalid_constraint: face {faces[bad[0]]}: the direction is not three finite numbers")
        bad = np.flatnonzero((directions == 0).all(axis=1))
        if bad.size:
            raise Refusal(422, f"invalid_constraint: face {faces[bad[0]]}: the direction is the zero vector")
        ordered = np.sort(faces)
        twice = np.flatnonzero(ordered[1:] == ordered[:-1])
        if twice.size:
            raise Refusal(422, f"invalid_constraint: face {ordered[twice[0]]} is constrained twice")
        return faces, directions

    def problem(self, request):
        """the fields common to the solve-like requests, checked"""
        n = self.symmetry_order(request)
        singularities = {}
        items = request.get("singularities", [])
        if not isinstance(items, list):
            raise ValueError(f"singularities must be a list of [vertex, index], got {shown(items)}")
        for item in items:
            if not (isinstance(item, list) and len(item) == 2 and type(item[0]) is int
                    and type(item[1]) in (int, str)):
                raise ValueError(f"a singularity must be [vertex, index], got {shown(item)}")
            if item[0] in singularities:  # not last-wins: the library's code for a vertex listed twice
                raise Refusal(422, f"duplicate_singularity: vertex {shown(item[0])} is listed twice")
            singularities[item[0]] = str(item[1])
        faces, directions = self.constraints(request.get("constraints", []))
        return Problem(n, singularities, faces, directions, self.align_boundary(request))

    def state(self, align_boundary):
        """the solver state for a request: the aligned solver (made now if it is the first use) when asked for on a
        mesh with boundary; otherwise the plain one (with no boundary, alignment changes nothing)"""
        if not align_boundary or not self.has_boundary:
            return self.plain
        with self.aligned_lock:
            if self.aligned is None:
                self.aligned = Solver_state(tc.Solver.from_file(self.path, align_boundary=True))
            return self.aligned

    def targets(self, faces, directions):
        """the sorted constrained faces (a tuple) and the (F, 3) directions of a request's faces (None: no face)"""
        key = tuple(np.sort(faces).tolist())
        if not key:
            return key, None
        targets = np.zeros((len(self.F), 3))
        targets[faces] = directions
        return key, targets

    @staticmethod
    def use_constraints(state, key):
        """gives the solver of `state` the constrained faces `key` if it has others (state.lock held)"""
        if state.faces != key:
            before, state.faces = state.faces, None
            try:
                state.solver.set_constraints(constrained_faces=list(key))
            except tc.InvalidInput as e:
                # a refusal leaves the solver as it was; a solver failure leaves it without constrained faces
                state.faces = () if e.code == "solver_failure" else before
                raise
            state.faces = key

    def solve(self, p):
        """the Result of a Problem, and the solver that gave it"""
        state = self.state(p.align_boundary)
        key, directions = self.targets(p.faces, p.directions)
        with state.lock:
            self.use_constraints(state, key)
            # the page turns the field itself: not the n directions per face (3 n numbers each)
            result = state.solver.solve(p.singularities, n=p.n, directions=directions, all_directions=False)
            return result, state.solver

    def place_frame(self, request):
        """the placement under the request's pins (its constraints held in the smooth field, as the program's
        --auto with --constraints or --align-features), on the solver the request's solves use"""
        n = self.symmetry_order(request)
        align = self.align_boundary(request)
        faces, directions = self.constraints(request.get("constraints", []))
        key, targets = self.targets(faces, directions)
        state = self.state(align) if key else self.plain
        with state.lock:
            self.use_constraints(state, key)
            placed, _ = state.solver.place_singularities(n=n, align_boundary=align, directions=targets)
        return frame({"n": n, "singularities": [[int(v), str(k)] for v, k in sorted(placed.items())]}, [])

    def features_frame(self, request):
        """the pins of the sharp features (feature_aligned_faces() of the module), cached per threshold and n"""
        n = self.symmetry_order(request)
        align = self.align_boundary(request)
        threshold = request.get("threshold", tc.DEFAULT_FEATURE_ANGLE)
        if type(threshold) not in (int, float):
            raise ValueError(f"threshold must be a number of degrees, got {shown(threshold)}")
        try:
            threshold = float(threshold)
        except OverflowError:  # an integer of hundreds of digits: out of range, as the library says
            threshold = math.inf if threshold > 0 else -math.inf
        with self.features_lock:
            if (threshold, n) not in self.features:
                if len(self.features) >= 8:
                    self.features.clear()
                self.features[threshold, n] = tc.feature_aligned_faces(self.V, self.F, threshold, n=n)
            faces, directions, report = self.features[threshold, n]
        keep = np.ones(len(faces), bool)
        if align and self.has_boundary:
            keep = ~self.boundary_face[faces]
        header = {"threshold": threshold, "n": n, "on_aligned_boundary": int((~keep).sum()),
                  "report": json_safe(report),
                  "constraints": [[f, d] for f, d in zip(faces[keep].tolist(), directions[keep].tolist())]}
        return frame(header, [])

    def mesh_frame(self):
        if self.mesh_bytes is not None:
            return self.mesh_bytes
        header = {"vertices": len(self.V), "faces": len(self.F), "n": self.n, "chi": self.chi.tolist(),
                  "closed": self.closed,
                  "singularities": [[int(v), str(k)] for v, k in sorted(self.initial.items())]}
        edges = np.sort(np.concatenate([self.F[:, [0, 1]], self.F[:, [1, 2]], self.F[:, [2, 0]]]), axis=1)
        unique, count = np.unique(edges, axis=0, return_counts=True)
        self.mesh_bytes = bytes(frame(header, [("V", self.V, "<f4"), ("F", self.F, "<u4"),
                                               ("component", self.component, "<i4"),
                                               ("boundary", unique[count == 1], "<u4"),
                                               ("angle_defect", angle_defects(self.V, self.F), "<f4")]))
        return self.mesh_bytes

    def solve_frame(self, request):
        p = self.problem(request)
        result, _ = self.solve(p)
        # the report's paths that join the request's constrained faces (to each other, or to the aligned boundary);
        # not the many that only link boundary faces to one another
        pinned = set(p.faces.tolist())
        report = [c for c in result.constraints if c["from_face"] in pinned or c["to_face"] in pinned]
        header = {"n": p.n, "energy": result.energy, "max_residual": result.max_residual,
                  "timings": result.timings, "constraints": json_safe(report)}
        # one direction per face, as its angle in the face's frame (a third of the bytes of a vector: the transfer
        # into the browser is dearer than the solve); the page turns it by 2 pi / n for the others
        angle = np.arctan2(np.einsum("ij,ij->i", result.field, self.e2), np.einsum("ij,ij->i", result.field, self.e1))
        return frame(header, [("angle", angle, "<f4")])

    def seed_count(self, request):
        seeds = request.get("seeds", min(len(self.F), DEFAULT_SEEDS))
        if not isinstance(seeds, int) or isinstance(seeds, bool) or not 1 <= seeds <= MAX_SEEDS:
            raise ValueError(f"seeds must be an integer from 1 to {MAX_SEEDS}, got {shown(seeds)}")
        return min(seeds, len(self.F))

    def seed_faces(self, count):
        """`count` faces spread over the mesh (fewer if they cannot be kept apart), the same for every request:
        the library's spread_guided_faces() over faces taken in a fixed random order (kept in that order)"""
        with self.seeds_lock:
            if count not in self.seeds:
                if len(self.seeds) >= 8:
                    self.seeds.clear()
                guide = np.zeros((len(self.F), 3))
                guide[:, 0] = np.random.default_rng(22).uniform(1, 2, len(self.F))
                self.seeds[count] = self.solver.spread_guided_faces(guide, count)
            return self.seeds[count]

    def streamlines(self, p, result, solver, count):
        """the streamlines of a solve from up to `count` seed faces, the number of seeds used and the limit of faces
        per ray. A ray crosses about 4 times the seeds' spacing (in faces); all the rays together cross at most
        RAY_STEPS faces: the rays are shortened to 8 faces, then seeds are left out (the seeds come in an order whose
        every beginning is spread over the mesh)"""
        seeds = self.seed_faces(count)
        rays = p.n if p.n % 2 == 0 else 2 * p.n  # per seed: both ways along n/2 lines, or along n lines
        per_ray = min(400, max(8, round(4 * math.sqrt(len(self.F) / max(1, len(seeds))))))
        per_ray = max(8, min(per_ray, RAY_STEPS // max(1, len(seeds) * rays)))
        seeds = seeds[:max(1, RAY_STEPS // (rays * per_ray))]
        lines = solver.trace_streamlines(result, p.singularities, seed_faces=seeds, maximum_faces_per_ray=per_ray)
        return lines, len(seeds), per_ray

    def streamlines_frame(self, request):
        p = self.problem(request)
        count = self.seed_count(request)
        result, solver = self.solve(p)
        start = time.perf_counter()
        lines, seeds, per_ray = self.streamlines(p, result, solver, count)
        offsets = np.zeros(len(lines) + 1, np.int64)
        np.cumsum([len(line) for line in lines], out=offsets[1:])
        points = np.concatenate(lines) if lines else np.zeros((0, 3))
        header = {"n": p.n, "energy": result.energy, "lines": len(lines), "seeds": seeds,
                  "maximum_faces_per_ray": per_ray,
                  "timings": dict(result.timings, streamlines=time.perf_counter() - start)}
        return frame(header, [("points", points, "<f4"), ("offsets", offsets, "<u4")])

    def user_path(self, path, saving):
        """the real path of a file of the folder named by a request (relative to the folder), checked"""
        if not isinstance(path, str) or not path:
            raise Refusal(400, f"path must be a non-empty string (relative to the folder), got {shown(path)}")
        if "\0" in path:
            raise Refusal(400, f"path {shown(path)} contains a NUL character")
        if os.path.isabs(path):
            raise Refusal(400, f"path {shown(path)} must be relative to the folder")
        real = os.path.realpath(os.path.join(self.folder, path))
        if os.path.commonpath([self.folder, real]) != self.folder:
            raise Refusal(403, f"path {shown(path)} is outside the folder")
        if saving:
            if os.path.isdir(real):
                raise Refusal(400, f"path {shown(path)} is a directory")
            if not os.path.isdir(os.path.dirname(real)):
                raise Refusal(404, f"path {shown(path)}: its directory does not exist")
            self.not_the_mesh(real, path)
            if os.path.lexists(real) and not os.path.isfile(real):
                raise Refusal(400, f"path {shown(path)} exists and is not a regular file")
        else:
            if not os.path.lexists(real):
                raise Refusal(404, f"no file {shown(path)} in the folder")
            if not os.path.isfile(real):
                raise Refusal(400, f"path {shown(path)} is not a regular file")
            if os.path.getsize(real) > MAX_LOAD:
                raise Refusal(413, f"file {shown(path)} is larger than {MAX_LOAD} bytes")
        return real

    def not_the_mesh(self, real, path):
        """refuses (403) a path to save to that is the mesh being edited: its real path, or another name of its
        file (a hard link; a symbolic link resolves to its real path) as it was at start or as it is now"""
        if real == self.mesh_real:
            raise Refusal(403, f"path {shown(path)} is the mesh being edited: it is never replaced")
        try:
            stat = os.stat(real)
        except (OSError, ValueError):
            return  # no such file (yet): link_into_place() will not replace one that appears
        files = {self.mesh_file}
        try:
            now = os.stat(self.path)
            files.add((now.st_dev, now.st_ino))
        except OSError:
            pass
        if (stat.st_dev, stat.st_ino) in files:
            raise Refusal(403, f"path {shown(path)} is another name of the mesh being edited: it is never replaced")

    def write(self, target, path, overwrite, writer):
        """writes a file completely or not at all: writer(temporary) writes a temporary file beside `target` (the
        library writes atomically: its own temporary, renamed), which then takes the target's name. Without
        overwrite, an existing file is a 409 (checked after the solve: the page asks to replace a file only when
        the save would succeed) and the new file is linked to the name, which fails if a file has it (one that
        appeared meanwhile: 409 too), so it never replaces one; with overwrite it is renamed over it, the mesh
        checked again just before"""
        if not overwrite and os.path.lexists(target):
            raise exists_refusal(path)
        directory, name = os.path.split(target)
        temporary = None
        try:
            # the temporary keeps the name's ending: the library picks the field's format from it
            fd, temporary = tempfile.mkstemp(prefix=".tc-save-", suffix="-" + name, dir=directory)
            os.close(fd)
            writer(temporary)
            self.not_the_mesh(target, path)
            if overwrite:
                os.replace(temporary, target)
            else:
                self.link_into_place(temporary, target, path)
        except OSError as e:  # e.g. a folder one may not write in: the library's code for it
            raise Refusal(422, f"io_error: cannot write {shown(path)}: {e.strerror or e}") from None
        finally:
            if temporary is not None and os.path.lexists(temporary):
                os.unlink(temporary)

    @staticmethod
    def link_into_place(temporary, target, path):
        """gives the temporary file the target's name if no file has it, else 409 (the temporary stays, and the
        caller removes it)"""
        exists = exists_refusal(path)
        try:
            os.link(temporary, target)
            return
        except FileExistsError:
            raise exists from None
        except OSError as e:
            if e.errno not in (errno.EPERM, errno.ENOTSUP, errno.EOPNOTSUPP, errno.EMLINK, errno.EACCES):
                raise
        # a file system without hard links: the name is taken (O_EXCL, empty until the rename fills it)
        try:
            os.close(os.open(target, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644))
        except FileExistsError:
            raise exists from None
        os.replace(temporary, target)

    def save_frame(self, request):
        """solves (and traces), checks everything, then writes the file completely or not at all; an existing file
        is replaced only with overwrite: true, the mesh never"""
        if not isinstance(request, dict):
            raise ValueError("the body must be a JSON object")
        kind = request.get("kind")
        if not isinstance(kind, str) or kind not in SAVE_KINDS:
            raise ValueError(f"kind must be one of {', '.join(SAVE_KINDS)}, got {shown(kind)}")
        overwrite = request.get("overwrite", False)
        if not isinstance(overwrite, bool):
            raise ValueError(f"overwrite must be true or false, got {shown(overwrite)}")
        path = request.get("path")
        target = self.user_path(path, saving=True)
        if not target.endswith(SAVE_KINDS[kind]):
            raise ValueError(f"a {kind} file must end in {SAVE_KINDS[kind]}, got {shown(path)}")
        p = self.problem(request)
        count = self.seed_count(request) if kind == "streamlines" else 0
        result, solver = self.solve(p)
        if kind == "singularities":
            writer = lambda temporary: tc.write_singularities(temporary, p.singularities)
        elif kind == "constraints":
            writer = lambda temporary: tc.write_face_directions(temporary, p.faces, p.directions)
        elif kind == "streamlines":
            lines = self.streamlines(p, result, solver, count)[0]
            writer = lambda temporary: tc.write_streamlines(temporary, lines)
        else:
            writer = lambda temporary: solver.write_field(temporary, result, p.singularities)
        self.write(target, path, overwrite, writer)
        return frame({"saved": os.path.relpath(target, self.folder), "bytes": os.path.getsize(target)}, [])

    def load_frame(self, request):
        if not isinstance(request, dict):
            raise ValueError("the body must be a JSON object")
        kind = request.get("kind")
        if not isinstance(kind, str) or kind not in ("singularities", "constraints"):
            raise ValueError(f"kind must be singularities or constraints, got {shown(kind)}")
        real = self.user_path(request.get("path"), saving=False)
        if kind == "singularities":
            s = tc.read_singularities(real, len(self.V))
            return frame({"singularities": [[int(v), str(k)] for v, k in s.items()]}, [])
        faces, directions = tc.read_face_directions(real, len(self.F))
        return frame({"constraints": [[f, d] for f, d in zip(faces.tolist(), directions.tolist())]}, [])


def exists_refusal(path):
    """the 409 of a save to an existing file without "overwrite": true"""
    return Refusal(409, f"file {shown(path)} already exists in the folder: it is replaced only with "
                        f'"overwrite": true')


def json_integer(text):
    """an integer of a request: refused (ValueError) above MAX_DIGITS digits, before Python's own limit (4300
    digits, whose ValueError would come from deep inside the parser) and its quadratic-time conversion"""
    digits = len(text) - text.startswith("-")
    if digits > MAX_DIGITS:
        raise ValueError(f"an integer of {digits} digits (at most {MAX_DIGITS})")
    return int(text)


def json_constant(name):
    """NaN, Infinity, -Infinity: Python's json reads them, JSON has no such numbers"""
    raise ValueError(f"{name} is not a JSON number")


class Handler(http.server.BaseHTTPRequestHandler):
    """GET (and HEAD) on the page and the mesh, POST on the API; other methods 405 with an Allow header, methods
    nobody knows 501. Every refusal, the base class's own (a malformed request line or header) included, is a
    text/plain line; a refusal that leaves a body unread (or half read) closes the connection after it"""
    session = None
    bundle = None
    protocol_version = "HTTP/1.1"
    disable_nagle_algorithm = True  # no 40 ms wait for the client's delayed ACK between packets of a reply
    GETS = ("/", "/editor.js", "/editor.js.map", "/api/mesh")
    # the static files: URL -> (the file, from the page's folder or the bundle's, never a path from the request; type)
    FILES = {"/": ("web", "index.html", "text/html; charset=utf-8"),
             "/editor.js": ("bundle", "editor.js", "text/javascript"),
             "/editor.js.map": ("bundle", "editor.js.map", "application/json")}
    POSTS = {"/api/solve": "solve_frame", "/api/place": "place_frame", "/api/streamlines": "streamlines_frame",
             "/api/save": "save_frame", "/api/load": "load_frame", "/api/features": "features_frame"}

    def log_message(self, *args):
        pass

    def reply(self, code, body, kind, headers=()):
        """the status line, the headers and the body (not for HEAD) in one write; a client gone is not an error"""
        head = (f"{self.protocol_version} {code} {self.responses.get(code, ('',))[0]}\r\n"
                f"Content-Type: {kind}\r\nContent-Length: {len(body)}\r\nCache-Control: no-store\r\n"
                + "".join(f"{name}: {value}\r\n" for name, value in headers)
                + ("Connection: close\r\n" if self.close_connection else "") + "\r\n")
        try:
            self.wfile.write(head.encode("latin-1") + (b"" if self.command == "HEAD" else body))
        except (BrokenPipeError, ConnectionResetError):
            self.close_connection = True

    def refuse(self, code, reason, headers=()):
        """a 4xx (or 500) with a one-line reason; the folder's own path is left out of it"""
        folder = self.session.folder if self.session is not None else None
        if folder and folder != os.sep:
            reason = reason.replace(folder + os.sep, "")
        self.reply(code, (" ".join(reason.split()) + "\n").encode("utf-8", "backslashreplace"),
                   "text/plain; charset=utf-8", headers)

    def send_error(self, code, message=None, explain=None):
        """the base class's refusals (a malformed request line or header, 414, 431, 501, 505) as one line too"""
        self.close_connection = True
        self.refuse(code, message or self.responses.get(code, ("refused",))[0])

    def not_allowed(self, body_read=False):
        """405 for a method the URL does not take (404 for an unknown URL); unless the body was read, the
        connection closes after it"""
        self.close_connection = self.close_connection or not body_read
        if self.path in self.GETS:
            return self.refuse(405, f"{self.command} {self.path}: this URL takes GET and HEAD",
                               [("Allow", "GET, HEAD")])
        if self.path in self.POSTS:
            return self.refuse(405, f"{self.command} {self.path}: this URL takes POST", [("Allow", "POST")])
        return self.refuse(404, f"not found: {self.path}")

    do_PUT = do_DELETE = do_PATCH = do_OPTIONS = do_TRACE = do_CONNECT = not_allowed

    def do_GET(self):
        if self.headers.get("Transfer-Encoding") or self.headers.get("Content-Length", "0").strip() != "0":
            self.close_connection = True  # a body with a GET: not read, so nothing more can be on this connection
        if self.path not in self.GETS:
            return self.not_allowed(body_read=True)  # (or the connection closes, as just said)
        if self.path == "/api/mesh":
            return self.reply(200, self.session.mesh_frame(), "application/octet-stream")
        where, name, kind = self.FILES[self.path]
        path = os.path.join(os.path.join(HERE, "web") if where == "web" else self.bundle, name)
        try:
            with open(path, "rb") as f:
                body = f.read()
        except OSError as e:
            return self.refuse(404, f"not found: {self.path} ({e.strerror}; the page's bundle is built by the "
                                    f"target trivial_connections_editor)")
        self.reply(200, body, kind)

    do_HEAD = do_GET  # the headers of the GET (reply() leaves the body out)

    def request_object(self):
        """the body, read whole (Content-Length) and parsed: a JSON object, or None once refused"""
        if "Transfer-Encoding" in self.headers:
            self.close_connection = True
            return self.refuse(411, "a body in chunks (Transfer-Encoding) is not read: send it with a "
                                    "Content-Length")
        lengths = {value.strip() for value in self.headers.get_all("Content-Length", [])}
        if not lengths:
            self.close_connection = True  # a body could follow (read to the end of the connection): not read
            return self.refuse(411, "a POST needs a Content-Length")
        length = lengths.pop()
        if lengths or not length.isascii() or not length.isdigit():
            self.close_connection = True
            return self.refuse(400, f"bad Content-Length: {shown(self.headers.get_all('Content-Length'))}")
        length = int(length)
        limit = self.session.max_body
        if length > limit:
            self.close_connection = True  # the body is not read: nothing more can be on this connection
            return self.refuse(413, f"request body of {length} bytes (at most {limit})")
        self.connection.settimeout(BODY_TIMEOUT)
        try:
            data = self.rfile.read(length)
        except TimeoutError:
            self.close_connection = True
            return self.refuse(408, f"the body ({length} bytes) did not arrive within {BODY_TIMEOUT} s")
        except (ConnectionResetError, BrokenPipeError):
            self.close_connection = True  # nobody to answer
            return None
        finally:
            self.connection.settimeout(self.timeout)
        if len(data) < length:
            self.close_connection = True
            return self.refuse(400, f"the body ended after {len(data)} of its {length} bytes (Content-Length)")
        try:
            request = json.loads(data.decode("utf-8") or "{}", parse_int=json_integer, parse_constant=json_constant)
        except UnicodeDecodeError as e:
            return self.refuse(400, f"the body is not UTF-8: {e}")
        except RecursionError:
            return self.refuse(400, "malformed JSON: nested too deeply")
        except ValueError as e:  # json.JSONDecodeError, json_integer(), json_constant()
            return self.refuse(400, f"malformed JSON: {e}")
        if not isinstance(request, dict):
            names = {list: "an array", str: "a string", bool: "true or false", type(None): "null"}
            return self.refuse(400, f"the body must be a JSON object, got {names.get(type(request), 'a number')}")
        return request

    def do_POST(self):
        request = self.request_object()  # read first, so that the connection stays usable after a 404 or 405
        if request is None:
            return
        if self.path not in self.POSTS:
            return self.not_allowed(body_read=True)
        try:
            body = getattr(self.session, self.POSTS[self.path])(request)
        except Refusal as e:
            return self.refuse(e.status, str(e))
        except tc.InvalidInput as e:
            return self.refuse(422, f"{e.code}: {e}")
        except (TypeError, ValueError, KeyError, OverflowError) as e:
            return self.refuse(400, f"bad request: {e}")
        except RecursionError:
            return self.refuse(400, "bad request: nested too deeply")
        except Exception as e:  # noqa: BLE001 (a reply rather than a dropped connection; the trace on stderr)
            traceback.print_exc()
            return self.refuse(500, f"internal error: {type(e).__name__}: {e}")
        return self.reply(200, body, "application/octet-stream")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh")
    ap.add_argument("--n", type=int, default=4)
    ap.add_argument("--port", type=int, default=8000)
    ap.add_argument("--bundle", default=os.path.join(HERE, "..", "build", "editor"))
    ap.add_argument("--folder", default=os.getcwd(),
                    help="the only folder whose files the page may save and load (default: the current directory)")
    a = ap.parse_args()
    if not os.path.isdir(a.folder):
        ap.error(f"--folder {a.folder}: not a directory")
    Handler.session = Session(a.mesh, a.n, a.folder)
    Handler.bundle = a.bundle
    server = http.server.ThreadingHTTPServer(("127.0.0.1", a.port), Handler)
    print(f"http://127.0.0.1:{server.server_address[1]}/ (files in {Handler.session.folder})", flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    sys.exit(main())
