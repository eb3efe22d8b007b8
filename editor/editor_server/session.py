"""The solve session: one mesh, its prefactored solvers, requests checked and solved into frames."""

import collections
import math
import os
import threading

import numpy as np
import trivial_connections as tc

from .files import Folder_files
from .limits import BODY_PER_FACE, MAX_BODY, MAX_N
from .quads import Quads
from .streamlines import Streamlines
from .topology import angle_defects, components_of, face_edges
from .wire import Refusal, frame, json_safe, shown


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


class Session(Streamlines, Quads, Folder_files):
    """one mesh, its solver factored once (and the aligned one, made on first use), the requests checked and
    solved; the streamlines, the quad meshes and the files of the folder in the parts it is made of"""

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
        edges = face_edges(self.F)
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

    @staticmethod
    def feature_angle(request, name):
        """the angle of the sharp features a request gives as `name` (degrees, default the library's), as a float;
        out of [0, 180] is the library's refusal (422)"""
        threshold = request.get(name, tc.DEFAULT_FEATURE_ANGLE)
        if type(threshold) not in (int, float):
            raise ValueError(f"{name} must be a number of degrees, got {shown(threshold)}")
        try:
            return float(threshold)
        except OverflowError:  # an integer of hundreds of digits: out of range, as the library says
            return math.inf if threshold > 0 else -math.inf

    def features_frame(self, request):
        """the pins of the sharp features (feature_aligned_faces() of the module), cached per threshold and n"""
        n = self.symmetry_order(request)
        align = self.align_boundary(request)
        threshold = self.feature_angle(request, "threshold")
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
                  "singularities": [[int(v), str(k)] for v, k in sorted(self.initial.items())],
                  "quad_size": self.quad_sizes({})["quad_size"]}
        edges = face_edges(self.F)
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
