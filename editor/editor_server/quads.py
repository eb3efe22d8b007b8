"""The quad mesh of a solve (issue 43): the module's Solver.quad_mesh() on the request's cross field."""

import math
import time

import numpy as np
import trivial_connections as tc

from .limits import MAX_QUADS, QUAD_SIZE_EDGES
from .topology import face_edges
from .wire import Refusal, frame, json_safe, shown


class Quads:
    """the quad-mesh requests of a Session (a part of it: self.V, self.F, self.problem(), self.solve(),
    self.feature_angle())"""

    def mean_edge(self):
        """the mean length of the mesh's edges (each edge once), computed once"""
        if getattr(self, "_mean_edge", None) is None:
            edges = np.unique(face_edges(self.F), axis=0)
            self._mean_edge = float(np.linalg.norm(self.V[edges[:, 0]] - self.V[edges[:, 1]], axis=1).mean())
        return self._mean_edge

    def quad_sizes(self, request):
        """the quad_size= or target_faces= of the module's call: the request's quad_size (a positive number) or
        target_faces (a positive integer), at most one of them; neither: QUAD_SIZE_EDGES mean edge lengths"""
        size, target = request.get("quad_size"), request.get("target_faces")
        if size is not None and target is not None:
            raise ValueError("give quad_size or target_faces, not both")
        if target is not None:
            if not isinstance(target, int) or isinstance(target, bool) or not 1 <= target <= MAX_QUADS:
                raise ValueError(f"target_faces must be an integer from 1 to {MAX_QUADS}, got {shown(target)}")
            return {"target_faces": target}
        if size is None:
            return {"quad_size": QUAD_SIZE_EDGES * self.mean_edge()}
        if type(size) not in (int, float):
            raise ValueError(f"quad_size must be a number, got {shown(size)}")
        try:
            size = float(size)
        except OverflowError:  # an integer of hundreds of digits: too large a size, as the library says it
            size = math.inf
        return {"quad_size": size}  # not positive or finite: the library's invalid_argument (422)

    def feature_edges(self, request):
        """the sharp edges (the module's feature_curves() at the request's feature_threshold, in degrees) as vertex
        pairs, put on iso-lines; None without feature_threshold"""
        if "feature_threshold" not in request:
            return None
        curves, _ = tc.feature_curves(self.V, self.F, self.feature_angle(request, "feature_threshold"))
        return np.vstack(curves) if curves else np.zeros((0, 2), np.int64)

    def scale_smoothness(self, request):
        """the request's scale_smoothness S (a number, default 0: the field not scaled), the module's
        quad_mesh(..., scale_smoothness=S); negative: the library's invalid_argument (422)"""
        s = request.get("scale_smoothness", 0)
        if type(s) not in (int, float):
            raise ValueError(f"scale_smoothness must be a number, got {shown(s)}")
        try:
            return float(s)
        except OverflowError:  # an integer of hundreds of digits: not finite, as the library says it
            return math.inf

    @staticmethod
    def move_off_features(request, features):
        """the request's move_off_features (true or false, default false): the singularities closer than the quad
        size H to a sharp edge, but not on one, moved to the nearest vertex at least H from every sharp edge before
        the quads (the module's move_singularities_off_features(), the program's step before --quad-mesh with
        --auto --align-features); it needs feature_threshold, whose sharp edges it moves away from"""
        move = request.get("move_off_features", False)
        if type(move) is not bool:
            raise ValueError(f"move_off_features must be true or false, got {shown(move)}")
        if move and features is None:
            raise ValueError("move_off_features needs feature_threshold: the sharp edges to move away from")
        return move

    def quads_frame(self, request):
        p = self.problem(request)
        if p.n != 4:  # before the solve: the library would refuse it after
            raise Refusal(422, f"invalid_symmetry_order: a quad mesh needs a cross field (n = 4), not n = {p.n}")
        sizes = self.quad_sizes(request)
        scale = self.scale_smoothness(request)
        features = self.feature_edges(request)
        move = self.move_off_features(request, features)
        result, solver = self.solve(p)
        start = time.perf_counter()
        moved = None
        if move:
            # the quads of the moved set, solved again (the request's own singularities are not changed: the
            # header says where the quads' ones went)
            singularities, moved = solver.move_singularities_off_features(p.singularities, features, **sizes)
            if moved["moves"]:
                p = p._replace(singularities=singularities)
                result, solver = self.solve(p)
            moved["singularities"] = [[int(v), str(k)] for v, k in sorted(singularities.items())]
        points, quads, report = solver.quad_mesh(result, p.singularities, max_quads=MAX_QUADS,
                                                 feature_edges=features, scale_smoothness=scale, **sizes)
        header = {"n": p.n, "energy": result.energy, "report": json_safe(report),
                  "timings": dict(result.timings, quads=time.perf_counter() - start)}
        if moved is not None:
            header["moved_off_features"] = json_safe(moved)
        return frame(header, [("points", points, "<f4"), ("quads", quads, "<u4")])
