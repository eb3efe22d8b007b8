#!/usr/bin/python3
"""What the Python binding adds to the C++ calls it makes (issue 21's speed targets), on CGAL meshes.

    PYTHONPATH=build/python python3 benchmark/python/binding_overhead.py MESH.off [MESH.off ...] [--repetitions N]

Per mesh, medians over N repetitions (default 9):
  - solve: the wall time of Solver.solve() in Python against Result.timings["solve"] + ["field"] (the C++
    Trivial_connection_solver::solve() and compute_field() inside it): the ratio is the binding's overhead on a
    solve (target: at most 1.05 at 75k faces);
  - build: the wall time of Solver(V, F) in Python against Solver.build_timings["solver"] (the C++ constructor on
    the Surface_mesh the arrays were read into): the ratio is what building from arrays adds to building from a
    Surface_mesh (target: at most 1.0).
The singularities: two +1 at vertices 0 and n/2 on a closed genus-0 mesh, none otherwise unless Poincare-Hopf
needs them (then the automatic placement's).
"""
import argparse
import statistics
import time

import numpy as np
import trivial_connections as tc


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("meshes", nargs="+")
    ap.add_argument("--repetitions", type=int, default=9)
    a = ap.parse_args()
    print("| mesh | faces | solve (Python) | C++ solve + field | solve ratio | build (Python, arrays) | C++ solver | build ratio |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for path in a.meshes:
        reference = tc.Solver.from_file(path)
        V, F = reference.vertices, reference.faces
        singularities, _ = reference.place_singularities(n=1)
        builds, cpp_builds = [], []
        for _ in range(a.repetitions):
            t = time.perf_counter()
            solver = tc.Solver(V, F)
            builds.append(time.perf_counter() - t)
            cpp_builds.append(solver.build_timings["solver"])
        solves, cpp_solves = [], []
        for _ in range(a.repetitions):
            t = time.perf_counter()
            r = solver.solve(singularities)
            solves.append(time.perf_counter() - t)
            cpp_solves.append(r.timings["solve"] + r.timings["field"])
        m = statistics.median
        print(f"| {path.split('/')[-1]} | {len(F)} | {m(solves) * 1e3:.2f} ms | {m(cpp_solves) * 1e3:.2f} ms | "
              f"{m(solves) / m(cpp_solves):.3f} | {m(builds) * 1e3:.1f} ms | {m(cpp_builds) * 1e3:.1f} ms | "
              f"{m(builds) / m(cpp_builds):.3f} |")


if __name__ == "__main__":
    main()
