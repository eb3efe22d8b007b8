"""Per vertex of the mesh: its angle defect, its component; per component its Euler characteristic; the faces'
edges."""

import numpy as np


def face_edges(F):
    """the edges of the faces as rows (i, j), i < j: every face's first edge (F[f, 0] to F[f, 1]), then every
    face's second, then every face's third ((3 m, 2): an interior edge twice)"""
    return np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)


def angle_defects(V, F):
    """per vertex, 2 pi minus the sum of its corner angles (2 pi for a vertex of no face); vectorised"""
    P = V[F]
    angles = np.empty(F.shape)
    for k in range(3):
        a, b = P[:, (k + 1) % 3] - P[:, k], P[:, (k + 2) % 3] - P[:, k]
        angles[:, k] = np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b))
    return 2 * np.pi - np.bincount(F.ravel(), weights=angles.ravel(), minlength=len(V))


def components_of(V, F):
    """per vertex, its component (of the faces' edge graph), and per component its Euler characteristic"""
    parent = np.arange(len(V))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b, c in F:
        ra, rb, rc = root(a), root(b), root(c)
        parent[rb] = ra
        parent[rc] = ra
    roots = np.array([root(i) for i in range(len(V))])
    used = np.zeros(len(V), bool)
    used[F.ravel()] = True
    labels = {r: k for k, r in enumerate(sorted(set(roots[used].tolist())))}
    component = np.array([labels.get(r, -1) if u else -1 for r, u in zip(roots, used)])
    edges = np.unique(face_edges(F), axis=0)
    chi = np.zeros(len(labels), int)
    np.add.at(chi, component[used], 1)
    np.add.at(chi, component[edges[:, 0]], -1)
    np.add.at(chi, component[F[:, 0]], 1)
    return component, chi
