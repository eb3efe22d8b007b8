#!/usr/bin/python3
"""The field a page of the editor holds against the library's answer for the same inputs (issue 22's browser test).

    python3 check_field.py MESH STATE.json DIRECTIONS.f32

STATE.json: the page's request, {"n": n, "singularities": [[vertex, "p/q"], ...], "constraints": [[face, [x, y, z]],
...], "align_boundary": bool}; DIRECTIONS.f32: the page's directions, float32, n per face (3 numbers each). Solves with
a solver of the module (PYTHONPATH) built for the same constrained faces and alignment, and compares to float32
rounding; checks too that on every pinned face one of the page's n directions is the pin's, projected on the face.
Exit 1 if not.
"""
import json
import sys

import numpy as np
import trivial_connections as tc


def main(mesh, state_path, directions_path):
    with open(state_path) as f:
        state = json.load(f)
    n = int(state["n"])
    pins = {int(f): np.array(d, float) for f, d in state.get("constraints", [])}
    solver = tc.Solver.from_file(mesh, constrained_faces=sorted(pins) or None,
                                 align_boundary=bool(state.get("align_boundary", False)))
    result = solver.solve({int(v): str(k) for v, k in state["singularities"]}, n=n, directions=pins or None)
    expected = (result.directions if n > 1 else result.field[:, None, :]).astype(np.float64)
    page = np.fromfile(directions_path, dtype="<f4").astype(np.float64)
    if page.size != expected.size:
        print(f"check_field: the page holds {page.size} numbers, the library's answer has {expected.size}")
        return 1
    page = page.reshape(expected.shape)
    error = np.abs(page - expected).max()
    # a pin holds: its direction projected on the face is one of the page's n there
    V, F = solver.vertices, solver.faces
    pin_error = 0.0
    for f, d in pins.items():
        a, b, c = V[F[f]]
        normal = np.cross(b - a, c - a)
        normal /= np.linalg.norm(normal)
        t = d - d.dot(normal) * normal
        t /= np.linalg.norm(t)
        pin_error = max(pin_error, np.linalg.norm(page[f] - t, axis=1).min())
    print(f"check_field: n = {n}, {len(state['singularities'])} singularities, {len(pins)} pins, "
          f"align_boundary {bool(state.get('align_boundary', False))}: max |page - library| = {error:.2e}, "
          f"max |pinned - page| = {pin_error:.2e}")
    # the page turns the field (float32) about normals it computes in float32 from float32 points
    return 0 if error <= 1e-5 and pin_error <= 1e-5 else 1


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
