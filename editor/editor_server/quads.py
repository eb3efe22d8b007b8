"""The quad mesh of a solve (issue 43): the module's Solver.quad_mesh() on the request's cross field."""

import math
import time

import numpy as np

from .limits import MAX_QUADS, QUAD_SIZE_EDGES
from .wire import Refusal, frame, json_safe, shown


class Quads:
    """the quad-mesh requests of a Session (a part of it: self.V, self.F, self.problem(), self.solve())"""

    def mean_edge(self):
        """the mean length of the mesh's edges (each edge once), computed once"""
        if getattr(self, "_mean_edge", None) is None:
            edges = np.unique(np.sort(np.concatenate([self.F[:, [0, 1]], self.F[:, [1, 2]], self.F[:, [2, 0]]]),
                                      axis=1), axis=0)
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

    def quads_frame(self, request):
        p = self.problem(request)
        if p.n != 4:  # before the solve: the library would refuse it after
            raise Refusal(422, f"invalid_symmetry_order: a quad mesh needs a cross field (n = 4), not n = {p.n}")
        sizes = self.quad_sizes(request)
        result, solver = self.solve(p)
        start = time.perf_counter()
        points, quads, report = solver.quad_mesh(result, p.singularities, max_quads=MAX_QUADS, **sizes)
        header = {"n": p.n, "energy": result.energy, "report": json_safe(report),
                  "timings": dict(result.timings, quads=time.perf_counter() - start)}
        return frame(header, [("points", points, "<f4"), ("quads", quads, "<u4")])
