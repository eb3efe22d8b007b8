#!/usr/bin/python3
"""The field a page of the editor holds against the library's answer for the same inputs (issue 22's browser test).

    python3 check_field.py MESH STATE.json DIRECTIONS.f32

STATE.json: the page's request, {"n": n, "singularities": [[vertex, "p/q"], ...], "constraints": [[face, [x, y, z]],
...], "align_boundary": bool}; DIRECTIONS.f32: the page's directions, float32, n per face (3 numbers each). Solves with
a solver of the module (PYTHONPATH) built for the same constrained faces and alignment, and compares to float32
rounding: the first direction of each face is the library's field; the others are that field turned about the
face's normal as the page's float32 points give it (and the library's own directions to 1e-4). Checks too that on
every pinned face one of the page's n directions is the pin's, projected on the face. Exit 1 if not.
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
    V, F = solver.vertices, solver.faces
    # the page's first direction of each face is the library's field, rounded to float32
    first = np.abs(page[:, 0] - result.field).max()
    # the others: the field turned by 2 pi k / n about the face's normal, which the page computes from the float32
    # points it received (its rounding grows on small faces far from the origin): compared with that turn made here
    # from the same float32 points, and with the library's own directions to a tolerance that allows for it
    P = V.astype(np.float32).astype(np.float64)
    normal = np.cross(P[F[:, 1]] - P[F[:, 0]], P[F[:, 2]] - P[F[:, 0]])
    normal = (normal / np.linalg.norm(normal, axis=1)[:, None]).astype(np.float32).astype(np.float64)
    quarter = np.cross(normal, result.field)
    t = 2 * np.pi * np.arange(n) / n
    turned = np.cos(t)[None, :, None] * result.field[:, None, :] + np.sin(t)[None, :, None] * quarter[:, None, :]
    page_turn = np.abs(page - turned).max()
    error = np.abs(page - expected).max()
    # a pin holds: its direction projected on the face is one of the page's n there
    pin_error = 0.0
    for f, d in pins.items():
        a, b, c = V[F[f]]
        normal_f = np.cross(b - a, c - a)
        normal_f /= np.linalg.norm(normal_f)
        t_f = d - d.dot(normal_f) * normal_f
        t_f /= np.linalg.norm(t_f)
        pin_error = max(pin_error, np.linalg.norm(page[f] - t_f, axis=1).min())
    print(f"check_field: n = {n}, {len(state['singularities'])} singularities, {len(pins)} pins, "
          f"align_boundary {bool(state.get('align_boundary', False))}: max |page - library| = {error:.2e} "
          f"(first direction {first:.2e}, the turn of the float32 points {page_turn:.2e}), "
          f"max |pinned - page| = {pin_error:.2e}")
    return 0 if first <= 1e-6 and page_turn <= 1e-6 and error <= 1e-4 and pin_error <= 1e-5 else 1


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
