"""The streamlines of a solve: seed faces spread over the mesh, rays cut to a budget of faces."""

import math
import time

import numpy as np

from .limits import DEFAULT_SEEDS, MAX_SEEDS, RAY_STEPS
from .wire import frame, shown


class Streamlines:
    """the streamline requests of a Session (a part of it: self.F, self.solver, self.seeds, self.problem(),
    self.solve())"""

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
