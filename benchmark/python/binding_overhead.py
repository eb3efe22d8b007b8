#!/usr/bin/python3
"""What the Python binding adds to the C++ calls it makes (issue 21's speed targets), on mesh files.

    PYTHONPATH=build/python python3 benchmark/python/binding_overhead.py MESH [MESH ...] [--repetitions N]
                                                   [--backend auto|ldlt|cholmod] [--json FILE] [--commit C]

(bash scripts/run_benchmarks.sh --python runs it on CGAL's meshes and writes the section "The Python binding" of
benchmark/RESULTS.md from FILE.)

Per mesh, medians over N repetitions (default 9), everything measured in this one process:
  - build: Solver(V, F) timed in Python (arrays -> validated connectivity -> Surface_mesh and the solver), against
    trivial_connections._reference_build(V, F), the C++ path from the same arrays: triangle_soup_to_mesh() into a
    Surface_mesh, then the Trivial_connection_solver constructor on it, timed in C++. Two ratios:
      "arrays": Python / (triangle_soup_to_mesh + constructor), the target (at most 1: building from arrays costs
                no more than building from a Surface_mesh made of them);
      "mesh":   Python / constructor alone, for a program that holds a Surface_mesh already (the arrays'
                adjacency, which such a mesh stores, is then not counted on the C++ side).
    The two builds alternate, each solver is freed before the next and every timed build starts with the freed
    heap given back to the system (malloc_trim, as in the C++ suite), so that both pay for the memory they touch.
  - solve: Solver.solve() timed in Python against Result.timings["solve"] + ["field"] (the C++ solve() and
    compute_field() inside it): the binding's overhead on a solve (target: at most 1.05 at 75k faces).
The singularities: the automatic placement's for n = 1.
Output: one Markdown table row per mesh (the header first); with --json, the medians as JSON too.
"""
import argparse
import ctypes
import datetime
import json
import os
import statistics
import time

import numpy as np  # noqa: F401  (the module's arrays)
import trivial_connections as tc


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("meshes", nargs="+")
    ap.add_argument("--repetitions", type=int, default=9)
    ap.add_argument("--backend", default="auto")
    ap.add_argument("--json", help="write the medians to this file")
    ap.add_argument("--commit", default="", help="the commit measured, for the JSON file")
    a = ap.parse_args()
    libc = ctypes.CDLL("libc.so.6")
    rows = []
    print("| mesh | faces | Solver(V, F), Python | C++: soup to mesh | C++: constructor | ratio arrays "
          "| ratio mesh | solve, Python | C++ solve + field | ratio solve |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    m = statistics.median
    for path in a.meshes:
        reference = tc.Solver.from_file(path, backend=a.backend)
        V, F = reference.vertices, reference.faces
        singularities, _ = reference.place_singularities(n=1)
        del reference
        python_builds, to_mesh, constructor = [], [], []
        for _ in range(a.repetitions):
            libc.malloc_trim(0)
            t = time.perf_counter()
            solver = tc.Solver(V, F, backend=a.backend)
            python_builds.append(time.perf_counter() - t)
            del solver
            libc.malloc_trim(0)
            cpp = tc._reference_build(V, F, backend=a.backend)
            to_mesh.append(cpp["soup_to_mesh"])
            constructor.append(cpp["solver"])
        solver = tc.Solver(V, F, backend=a.backend)
        solves, cpp_solves = [], []
        for _ in range(a.repetitions):
            t = time.perf_counter()
            r = solver.solve(singularities)
            solves.append(time.perf_counter() - t)
            cpp_solves.append(r.timings["solve"] + r.timings["field"])
            del r
        py, sm, ctor = m(python_builds), m(to_mesh), m(constructor)
        print(f"| {os.path.basename(path)} | {len(F)} | {py * 1e3:.1f} ms | {sm * 1e3:.1f} ms | {ctor * 1e3:.1f} ms | "
              f"{py / (sm + ctor):.3f} | {py / ctor:.3f} | {m(solves) * 1e3:.2f} ms | {m(cpp_solves) * 1e3:.2f} ms | "
              f"{m(solves) / m(cpp_solves):.3f} |", flush=True)
        rows.append({"mesh": os.path.basename(path), "faces": len(F), "python_build": py, "soup_to_mesh": sm,
                     "constructor": ctor, "python_solve": m(solves), "cpp_solve": m(cpp_solves),
                     "repetitions": a.repetitions})
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"python_binding": rows, "backend": a.backend, "commit": a.commit,
                       "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")}, f, indent=1)


if __name__ == "__main__":
    main()
