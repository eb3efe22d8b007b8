#!/usr/bin/python3
"""Regenerates the default example: examples/data/sphere.off (an icosphere, 3 subdivisions of the
icosahedron, 642 vertices and 1280 faces, counter-clockwise seen from outside) and examples/data/sphere.sing
(two +1 singularities at two antipodal vertices). Needs python3-numpy.
Usage: python3 scripts/make_example_mesh.py [OUTDIR] [SUBDIVISIONS]"""
import os, sys
import numpy as np

def icosphere(levels):
    t = (1.0 + 5 ** 0.5) / 2
    V = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    V = [np.array(p, float) / np.linalg.norm(p) for p in V]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
         (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        mid, G = {}, []
        def m(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                p = V[a] + V[b]
                V.append(p / np.linalg.norm(p)); mid[key] = len(V) - 1
            return mid[key]
        for (a, b, c) in F:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            G += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        F = G
    V = np.array(V)
    for (a, b, c) in F:   # counter-clockwise seen from outside: the normal points away from the centre
        assert np.dot(np.cross(V[b] - V[a], V[c] - V[a]), V[a] + V[b] + V[c]) > 0
    return V, F

def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..', 'examples', 'data')
    levels = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    V, F = icosphere(levels)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, 'sphere.off'), 'w') as fh:
        fh.write(f"OFF\n{len(V)} {len(F)} 0\n")
        for p in V:
            fh.write("%.17g %.17g %.17g\n" % tuple(p))
        for f in F:
            fh.write("3 %d %d %d\n" % f)
    assert np.allclose(V[0], -V[3])
    with open(os.path.join(out, 'sphere.sing'), 'w') as fh:
        fh.write("# Two +1 singularities at antipodal vertices of examples/data/sphere.off:\n"
                 "# vertex 0 and vertex 3 = -vertex 0. Their indices sum to the Euler characteristic 2.\n"
                 "# Format: one line 'v k' per singular vertex (0-based index, integer or p/q).\n"
                 "0 1\n3 1\n")
    print(f"wrote {out}/sphere.off ({len(V)} vertices, {len(F)} faces) and {out}/sphere.sing")

if __name__ == '__main__':
    main()
