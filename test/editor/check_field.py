#!/usr/bin/python3
"""The field a page of the editor holds against the library's answer for the same inputs (issue 22's browser test).

    python3 check_field.py MESH STATE.json DIRECTIONS.f32

STATE.json: the page's request, {"n": n, "singularities": [[vertex, "p/q"], ...], "constraints": [[face, [x, y, z]],
...], "align_boundary": bool}; DIRECTIONS.f32: the page's directions, float32, n per face (3 numbers each). Solves with
a solver of the module (PYTHONPATH) built for the same constrained faces and alignment, and compares to float32
rounding: the page's directions are the library's field, sent as an angle per face, turned by 2 pi k / n in the frame of
the page's float32 points (and the library's own directions to 1e-4). Checks too that on
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
    # The page receives per face the angle of the library's field from the face's first edge (float32) and turns
    # it by 2 pi k / n in the frame it makes from the float32 points it received, whose rounding grows on small
    # faces far from the origin. So: the page's directions against that construction made here from the library's
    # field (to float32 rounding), and against the library's own directions to a tolerance that allows for it.
    def frame(P):
        a, b, c = (P[F[:, k]] for k in range(3))
        e1 = (b - a) / np.linalg.norm(b - a, axis=1)[:, None]
        normal = np.cross(b - a, c - a)
        return e1, np.cross(normal / np.linalg.norm(normal, axis=1)[:, None], e1)
    e1, e2 = frame(V)
    angle = np.arctan2(np.einsum("ij,ij->i", result.field, e2), np.einsum("ij,ij->i", result.field, e1))
    angle = angle.astype(np.float32).astype(np.float64)
    p1, p2 = (e.astype(np.float32).astype(np.float64) for e in frame(V.astype(np.float32).astype(np.float64)))
    t = angle[:, None] + 2 * np.pi * np.arange(n)[None, :] / n
    built = np.cos(t)[:, :, None] * p1[:, None, :] + np.sin(t)[:, :, None] * p2[:, None, :]
    page_turn = np.abs(page - built).max()
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
          f"(the page's construction from the field's angles {page_turn:.2e}), "
          f"max |pinned - page| = {pin_error:.2e}")
    return 0 if page_turn <= 1e-6 and error <= 1e-4 and pin_error <= 1e-5 else 1


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
