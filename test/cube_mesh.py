# Copyright (c) 2026 CGAL Trivial Connections contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# The unit cube of the quad-mesh tests, shared by test/python/test_module.py (the module) and
# test/Trivial_connections/cli_quad_mesh.py (the program): each imports it from this folder (sys.path).


def unit_cube(s, open_top=False):
    """The unit cube's surface, each face s x s squares cut into two triangles, outward (counter-clockwise seen
    from outside); open_top: without the face z = 1 (an open box, one border loop). Returns (points as tuples of
    floats, triangles as tuples of vertex numbers, the vertices at the cube's corners)."""
    index, P, F = {}, [], []

    def vertex(q):
        if q not in index:
            index[q] = len(P)
            P.append(q)
        return index[q]

    for a in range(3):
        for sign in (-1, 1):
            if open_top and a == 2 and sign > 0:
                continue
            u, w = (a + 1) % 3, (a + 2) % 3
            for p in range(s):
                for q in range(s):
                    def corner(dp, dq):
                        L = [0, 0, 0]
                        L[a], L[u], L[w] = (s if sign > 0 else 0), p + dp, q + dq
                        return vertex(tuple(L))

                    quad = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)]
                    if sign < 0:
                        quad[1], quad[3] = quad[3], quad[1]
                    F += [(quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3])]
    corners = [i for i, p in enumerate(P) if all(x in (0, s) for x in p)]
    return [tuple(x / s for x in p) for p in P], F, corners
