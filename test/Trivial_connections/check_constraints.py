#!/usr/bin/env python3
# Checks what the program wrote with --constraints / --align-boundary, from the files alone (numpy only):
#  - every target of the constraint file is met by the field: the angle from the field to the target
#    projected onto the face is a multiple of 2 pi / n;
#  - with --align-boundary, on every boundary face the field is along its border edge (the longer one when
#    it has two), modulo 2 pi / n;
#  - with --guidance, on every guided face the mismatch d_g (angle from the guide to the field, reduced to
#    (-pi/n, pi/n]) is measured;
#  - optimality where it must hold: the weighted divergence sum_h w_e x(h) of the connection vanishes on
#    every face that is neither constrained nor guided (on constrained faces it does not: that is where the
#    paths end), and equals MU d_g on a guided face (the optimality condition of energy + MU sum d_g^2 with
#    optimal integers).
# The holonomy, the field's parallelism and everything else are checked by ../shared/tools/check_connection.py
# (run with --no-optimality on constrained outputs).
# Usage: check_constraints.py MESH.off --connection C --field F [--constraints FILE] [--align-boundary]
#                             [--guidance FILE] [--guidance-weight MU] [--n N]
import argparse, math, sys
import numpy as np


def read_off(path):
    words = []
    with open(path) as f:
        for line in f:
            line = line.split('#', 1)[0].split()
            words.extend(line)
    if not words[0].endswith('OFF'):
        sys.exit(f'{path}: not an OFF file')
    nv, nf = int(words[1]), int(words[2])
    p = 4
    V = np.array([[float(words[p + 3 * i + k]) for k in range(3)] for i in range(nv)])
    p += 3 * nv
    F = []
    for _ in range(nf):
        k = int(words[p])
        if k != 3:
            sys.exit(f'{path}: face with {k} vertices')
        F.append((int(words[p + 1]), int(words[p + 2]), int(words[p + 3])))
        p += 1 + k
    return V, F


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('mesh')
    ap.add_argument('--connection', required=True)
    ap.add_argument('--field', required=True)
    ap.add_argument('--constraints')
    ap.add_argument('--align-boundary', action='store_true')
    ap.add_argument('--guidance')
    ap.add_argument('--guidance-weight', type=float, default=1.0)
    ap.add_argument('--n', type=int, default=1)
    ap.add_argument('--no-optimality', action='store_true',
                    help='skip the optimality check: guides this script is not given (the program chose them, '
                         '--align-curvature)')
    a = ap.parse_args()
    V, F = read_off(a.mesh)
    period = 2 * math.pi / a.n
    U = np.loadtxt(a.field, comments='#').reshape(-1, 3)
    face_of = {}
    for f, (i, j, k) in enumerate(F):
        for (s, t) in ((i, j), (j, k), (k, i)):
            face_of[(s, t)] = f
    N = np.array([np.cross(V[j] - V[i], V[k] - V[i]) for (i, j, k) in F])
    N /= np.linalg.norm(N, axis=1)[:, None]

    def signed_mismatch(f, d):  # from the guide d to the field, reduced to (-period/2, period/2]
        d = d - np.dot(d, N[f]) * N[f]
        u = U[f]
        a_ = math.atan2(np.dot(np.cross(d, u), N[f]), np.dot(u, d))
        r = math.fmod(a_, period)
        if r > period / 2: r -= period
        if r <= -period / 2: r += period
        return r

    def mismatch(f, d):
        return abs(signed_mismatch(f, d))

    def read_directions(path):
        out = []
        with open(path) as c:
            for line in c:
                w = line.split('#', 1)[0].split()
                if w:
                    out.append((int(w[0]), np.array([float(w[1]), float(w[2]), float(w[3])])))
        return out

    constrained = set()
    rep, ok = {}, True
    if a.constraints:
        worst = 0.0
        count = 0
        with open(a.constraints) as c:
            for line in c:
                w = line.split('#', 1)[0].split()
                if not w:
                    continue
                f = int(w[0])
                constrained.add(f)
                worst = max(worst, mismatch(f, np.array([float(w[1]), float(w[2]), float(w[3])])))
                count += 1
        rep['targets'] = count
        rep['target_err'] = worst
        ok &= worst < 1e-7
    if a.align_boundary:
        worst = 0.0
        count = 0
        for f, (i, j, k) in enumerate(F):
            border = [(np.linalg.norm(V[t] - V[s]), V[t] - V[s]) for (s, t) in ((i, j), (j, k), (k, i))
                      if (t, s) not in face_of]
            if not border:
                continue
            border.sort(key=lambda b: -b[0])  # stable: the first of equally long edges
            constrained.add(f)
            worst = max(worst, mismatch(f, border[0][1]))
            count += 1
        rep['boundary_faces'] = count
        rep['alignment_err'] = worst
        ok &= count > 0 and worst < 1e-7
    div = np.zeros(len(F))
    scale = np.zeros(len(F))
    with open(a.connection) as c:
        for line in c:
            w = line.split('#', 1)[0].split()
            if not w:
                continue
            i, j, x, wt = int(w[0]), int(w[1]), float(w[2]), float(w[3])
            f, g = face_of[(i, j)], face_of[(j, i)]
            div[f] += wt * x
            div[g] -= wt * x
            scale[f] += abs(wt * x)
            scale[g] += abs(wt * x)
    expected = np.zeros(len(F))
    if a.guidance:
        guides = read_directions(a.guidance)
        worst = 0.0
        for f, d in guides:
            expected[f] = a.guidance_weight * signed_mismatch(f, d)
            worst = max(worst, abs(expected[f]) / a.guidance_weight)
        rep['guides'] = len(guides)
        rep['largest_guide_angle'] = worst
    free = [f for f in range(len(F)) if f not in constrained]
    rep['optimality_err'] = float(np.max(np.abs(div[free] - expected[free])) / max(1e-300, np.max(scale))) if free else 0.0
    if not a.no_optimality:
        ok &= rep['optimality_err'] < 1e-6
    print(' '.join(f"{k}={v:.3g}" if isinstance(v, float) else f"{k}={v}" for k, v in rep.items()))
    print('PASS' if ok else 'FAIL')
    sys.exit(0 if ok else 1)


if __name__ == '__main__':
    main()
