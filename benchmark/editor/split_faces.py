#!/usr/bin/python3
"""Splits every triangle of an OFF mesh into four at its edge midpoints (the surface is unchanged, the faces are
four times as many): the editor's latency benchmark uses it to reach the issue's 100k faces from a CGAL mesh.

    python3 split_faces.py IN.off OUT.off
"""
import os
import sys

import numpy as np


def read_off(path):
    with open(path) as f:
        words = [w for line in f for w in line.split("#")[0].split()]
    if words[0] != "OFF":
        raise ValueError(f"{path}: not an OFF file")
    nv, nf = int(words[1]), int(words[2])
    V = np.array(words[4:4 + 3 * nv], float).reshape(nv, 3)
    rest = np.array(words[4 + 3 * nv:], dtype=np.int64)
    F = rest.reshape(nf, -1) if rest.size == 4 * nf else None
    if F is None or (F[:, 0] != 3).any():
        raise ValueError(f"{path}: only triangle meshes")
    return V, F[:, 1:]


def split(V, F):
    edges = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    unique, inverse = np.unique(edges, axis=0, return_inverse=True)
    midpoint = len(V) + inverse.reshape(3, len(F)).T  # per face: the midpoints of its edges ab, bc, ca
    V2 = np.concatenate([V, (V[unique[:, 0]] + V[unique[:, 1]]) / 2])
    a, b, c = F.T
    ab, bc, ca = midpoint.T
    F2 = np.concatenate([np.stack([a, ab, ca], 1), np.stack([ab, b, bc], 1), np.stack([ca, bc, c], 1),
                         np.stack([ab, bc, ca], 1)])
    return V2, F2


def main(source, target):
    V, F = split(*read_off(source))
    temporary = target + ".tmp"
    with open(temporary, "w") as f:
        f.write(f"OFF\n{len(V)} {len(F)} 0\n")
        np.savetxt(f, V, fmt="%.17g")
        np.savetxt(f, np.column_stack([np.full(len(F), 3), F]), fmt="%d")
    os.replace(temporary, target)
    print(f"{target}: {len(V)} vertices, {len(F)} faces")


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:3]))
