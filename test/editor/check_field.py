#!/usr/bin/python3
"""The field a page of the editor holds against the library's answer for the same inputs (issue 22's browser test).

    python3 check_field.py MESH STATE.json DIRECTIONS.f32

STATE.json: {"n": n, "singularities": [[vertex, "p/q"], ...]}; DIRECTIONS.f32: the page's directions, float32,
n per face (3 numbers each). Solves with the module (PYTHONPATH) and compares to float32 rounding; exit 1 if not.
"""
import json
import sys

import numpy as np
import trivial_connections as tc


def main(mesh, state_path, directions_path):
    with open(state_path) as f:
        state = json.load(f)
    n = int(state["n"])
    solver = tc.Solver.from_file(mesh)
    result = solver.solve({int(v): str(k) for v, k in state["singularities"]}, n=n)
    expected = (result.directions if n > 1 else result.field[:, None, :]).astype(np.float64)
    page = np.fromfile(directions_path, dtype="<f4").astype(np.float64)
    if page.size != expected.size:
        print(f"check_field: the page holds {page.size} numbers, the library's answer has {expected.size}")
        return 1
    error = np.abs(page.reshape(expected.shape) - expected).max()
    print(f"check_field: n = {n}, {len(state['singularities'])} singularities, max |page - library| = {error:.2e}")
    # the page turns the field (float32) about normals it computes in float32 from float32 points
    return 0 if error <= 1e-5 else 1


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
