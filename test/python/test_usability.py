# Copyright (c) 2026 CGAL Trivial Connections contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# The module as a new Python user meets it (issue 40): clear errors for a bad n, an ignored directions=, a huge
# index in a uint64 F and a missing numpy; path-like arguments; __version__, repr() and docstrings; read_mesh() in
# every format the program reads; Solver.topology checked against V - E + F counted in numpy; progress callbacks,
# logging and Ctrl-C in long calls. Run by ctest (test python_module) with PYTHONPATH=build/python.

import _thread
import fractions
import logging
import os
import pathlib
import re
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import trivial_connections as tc
from test_module import bumpy_disk, concatenated, icosphere, torus

ROOT = pathlib.Path(__file__).resolve().parents[2]


def cgal_mesh(name):
    meshes = os.environ.get("TC_CGAL_MESHES")
    if not meshes or not os.path.isfile(os.path.join(meshes, name)):
        pytest.skip(f"CGAL's data set (TC_CGAL_MESHES) has no {name}")
    return os.path.join(meshes, name)


# ---- n ---------------------------------------------------------------------------------------------------------


def test_symmetry_order_range():
    V, F = icosphere(1)
    solver = tc.Solver(V, F)
    s = {0: 1, 1: 1}
    assert tc.MAX_SYMMETRY_ORDER == 999999999  # the program's --n takes at most nine digits
    for bad in [0, -1, -4, 10**9, 2**40, 2**80]:
        with pytest.raises(tc.InvalidInput, match=r"n must be an integer from 1 to 999999999.*got " + str(bad)) as e:
            solver.solve(s, n=bad)
        assert e.value.code == "invalid_symmetry_order"
        with pytest.raises(ValueError, match="from 1 to 999999999"):
            solver.place_singularities(n=bad)
        with pytest.raises(ValueError, match="from 1 to 999999999"):
            solver.refine_singularities(s, n=bad)
    for bad in [True, 4.0, "4", None]:
        with pytest.raises(TypeError, match="n must be an integer"):
            solver.solve(s, n=bad)
    with pytest.raises(ValueError, match="feature_n must be an integer from 1"):
        tc.Solver(V, F, align_features=True, feature_n=0)
    with pytest.raises(ValueError, match="n must be an integer from 1"):
        tc.feature_aligned_faces(V, F, n=-2)
    # a numpy integer is an integer; a large n works without the n directions per face
    assert solver.solve(s, n=np.int64(4)).n == 4
    big = solver.solve(s, n=10**6, all_directions=False)
    assert big.n == 10**6 and big.directions is None and big.max_residual < 1e-9
    # with them, 3 n numbers per face that cannot fit: a MemoryError that says what to do, before the solve
    with pytest.raises(MemoryError, match="all_directions=False"):
        solver.solve(s, n=tc.MAX_SYMMETRY_ORDER)
    assert solver.solve(s, n=tc.MAX_SYMMETRY_ORDER, all_directions=False).max_residual < 1e-9


# ---- directions= that would be ignored ---------------------------------------------------------------------------


def test_directions_without_constrained_or_guided_faces_is_an_error():
    V, F = icosphere(1)
    solver = tc.Solver(V, F)
    D = np.tile([1.0, 0.0, 0.0], (len(F), 1))
    s = {0: 1, 1: 1}
    with pytest.raises(ValueError, match=r"solve\(\): directions= is given but this solver has no constrained or "
                                         r"guided face, so it would be ignored"):
        solver.solve(s, directions=D)
    with pytest.raises(ValueError, match="would be ignored"):
        solver.solve(s, directions={3: (1, 0, 0)})
    with pytest.raises(ValueError, match=r"place_singularities\(\): directions= .* would be ignored"):
        solver.place_singularities(directions=D)
    with pytest.raises(ValueError, match=r"refine_singularities\(\): directions= .* would be ignored"):
        solver.refine_singularities(s, directions=D)
    # nothing to ignore: an empty dict, None
    assert solver.solve(s, directions={}).max_residual < 1e-9
    # with constrained faces they are read; after set_constraints() took them all away they would not be again
    solver.set_constraints(constrained_faces=[0])
    assert solver.solve({0: 1, 1: 1}, directions=D).max_residual < 1e-9
    solver.set_constraints(constrained_faces=[])
    with pytest.raises(ValueError, match="would be ignored"):
        solver.solve(s, directions=D)
    guided = tc.Solver(V, F, guided_faces=[5])
    assert guided.solve(s, directions={5: (0, 1, 0)}).max_residual < 1e-9


# ---- huge indices in F ------------------------------------------------------------------------------------------


def test_uint64_index_over_int64_is_said_as_it_is():
    V, F = icosphere(1)
    for value in [2**64 - 1, 2**63, 2**63 + 5]:
        G = F.astype(np.uint64)
        G[7, 2] = value
        before = G.copy()
        with pytest.raises(tc.InvalidInput) as e:
            tc.Solver(V, G)
        assert e.value.code == "invalid_vertex" and e.value.where == 7
        assert f"face 7 uses vertex {value} but the mesh has only {len(V)} vertices" in str(e.value)
        assert "-" not in str(e.value).split("uses vertex")[1].split()[0]
        assert np.array_equal(G, before)  # the input is not modified
    # an index just past the vertices, in any dtype, says the same
    for dtype in [np.uint64, np.int64, np.uint32, np.int16]:
        G = F.astype(dtype)
        G[3, 0] = len(V)
        with pytest.raises(tc.InvalidInput, match=f"face 3 uses vertex {len(V)} but"):
            tc.Solver(V, G)


# ---- numpy missing at import -------------------------------------------------------------------------------------


def test_import_without_numpy_is_an_import_error():
    code = ("import sys\nsys.modules['numpy'] = None  # as if numpy were not installed\n"
            "try:\n    import trivial_connections\nexcept ImportError as e:\n    print('ImportError:', e)\n"
            "else:\n    print('imported')\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=os.environ, check=True)
    assert out.stdout.startswith("ImportError: trivial_connections needs numpy"), out.stdout + out.stderr
    assert "python3-numpy" in out.stdout


# ---- paths ---------------------------------------------------------------------------------------------------------


def write_off(path, V, F):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(V)} {len(F)} 0\n")
        f.writelines(f"{a!r} {b!r} {c!r}\n" for a, b, c in np.asarray(V).tolist())
        f.writelines(" ".join(str(int(i)) for i in [len(t)] + list(t)) + "\n" for t in F)


def test_path_like_arguments(tmp_path):
    V, F = icosphere(1)
    mesh = tmp_path / "sphere.off"
    write_off(mesh, V, F)
    for path in [mesh, str(mesh), os.fsencode(mesh)]:
        W, G = tc.read_mesh(path)
        assert np.array_equal(W, V) and np.array_equal(G, F)
        assert tc.Solver.from_file(path).number_of_faces == len(F)
    solver = tc.Solver.from_file(mesh)
    s = {0: 1, 1: 1}
    result = solver.solve(s, n=4)
    tc.write_singularities(tmp_path / "s.sing", s)
    assert tc.read_singularities(tmp_path / "s.sing") == {0: 1, 1: 1}
    for name in ["f.txt", "f.vtk", "f.ply"]:
        solver.write_field(tmp_path / name, result, s)
        assert (tmp_path / name).stat().st_size > 0
    tc.write_face_directions(tmp_path / "d.txt", {2: (1, 0, 0)})
    faces, directions = tc.read_face_directions(tmp_path / "d.txt")
    assert faces.tolist() == [2] and directions.tolist() == [[1, 0, 0]]
    tc.write_streamlines(tmp_path / "l.vtk", solver.trace_streamlines(result, s, seed_faces=[0, 1]))
    assert (tmp_path / "l.vtk").stat().st_size > 0
    for bad in [3, None, ["a"]]:
        with pytest.raises(TypeError, match="os.PathLike"):
            tc.read_mesh(bad)
        with pytest.raises(TypeError, match="os.PathLike"):
            tc.read_singularities(bad)


# ---- version, repr, docstrings ------------------------------------------------------------------------------------


def test_version_is_the_projects():
    version = re.search(r"project\(TrivialConnections VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())
    assert tc.__version__ == version.group(1)


def test_repr_says_what_the_solver_holds():
    V, F = concatenated(icosphere(1), torus(8, 6))
    solver = tc.Solver(V, F, backend="ldlt")
    text = repr(solver)
    assert text.startswith("<trivial_connections.Solver: ") and text.endswith(">")
    assert f"{len(V)} vertices, {len(F)} faces, 2 components (chi 2, 0), 2 loops, backend \"ldlt\"" in text
    assert "last solve" not in text
    solver.solve({0: 1, 1: 1}, n=4)
    assert repr(solver).endswith(", last solve n=4>")
    assert "3 constrained or guided faces" in repr(tc.Solver(V, F, constrained_faces=[0, 1], guided_faces=[9]))


def public_names():
    for name in dir(tc):
        if name.startswith("_"):
            continue
        value = getattr(tc, name)
        if isinstance(value, (int, float, str)):
            continue  # constants: documented in the module's docstring and the manual
        yield f"trivial_connections.{name}", value
        if isinstance(value, type):
            for member in vars(value):
                if not member.startswith("_"):
                    yield f"trivial_connections.{name}.{member}", vars(value)[member]


def test_every_public_name_has_a_docstring():
    missing = [name for name, value in public_names() if not (getattr(value, "__doc__", None) or "").strip()]
    assert not missing, missing
    names = dict(public_names())
    assert "trivial_connections.Solver.number_of_faces" in names and "trivial_connections.read_mesh" in names
    assert (tc.__doc__ or "").strip()


# ---- read_mesh ------------------------------------------------------------------------------------------------------


def write_obj(path, V, F):
    with open(path, "w") as f:
        f.writelines(f"v {a!r} {b!r} {c!r}\n" for a, b, c in V.tolist())
        f.writelines("f " + " ".join(str(int(i) + 1) for i in t) + "\n" for t in F)


def write_ply(path, V, F):
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {len(V)}\nproperty double x\nproperty double y\n"
                f"property double z\nelement face {len(F)}\nproperty list uchar int vertex_indices\nend_header\n")
        f.writelines(f"{a!r} {b!r} {c!r}\n" for a, b, c in V.tolist())
        f.writelines(f"{len(t)} " + " ".join(str(int(i)) for i in t) + "\n" for t in F)


def write_stl(path, V, F):
    with open(path, "w") as f:
        f.write("solid s\n")
        for t in F:
            f.write(" facet normal 0 0 0\n  outer loop\n")
            f.writelines(f"   vertex {V[i][0]!r} {V[i][1]!r} {V[i][2]!r}\n" for i in t)
            f.write("  endloop\n endfacet\n")
        f.write("endsolid s\n")


def triangles_as_points(V, F):
    """the triangles as triples of points, each from its smallest point (orientation kept), sorted"""
    out = []
    for t in F.tolist():
        corners = [tuple(V[i].tolist()) for i in t]
        k = corners.index(min(corners))
        out.append(tuple(corners[k:] + corners[:k]))
    return sorted(out)


@pytest.mark.parametrize("extension, writer", [(".off", write_off), (".obj", write_obj), (".ply", write_ply),
                                               (".stl", write_stl)])
def test_read_mesh_formats(tmp_path, extension, writer):
    V, F = torus(7, 5)
    path = tmp_path / ("torus" + extension)
    writer(path, V, F)
    W, G = tc.read_mesh(path)
    assert W.dtype == np.float64 and G.dtype == np.int64 and W.shape[1] == 3 and G.shape == F.shape
    if extension == ".stl":  # STL lists every corner's point: its vertices are the distinct points, in some order
        assert len(W) == len(V)
        assert triangles_as_points(W, G) == triangles_as_points(V, F)
    else:  # vertex i and face f of the file are row i and row f
        assert np.array_equal(W, V) and np.array_equal(G, F)
    solver = tc.Solver.from_file(path)
    assert np.array_equal(solver.vertices, W) and np.array_equal(solver.faces, G)
    # no solver was needed, and what it reads is what Solver() takes
    assert tc.Solver(W, G).topology[0]["genus"] == 1


def test_read_mesh_polygons_and_errors(tmp_path):
    # a square of four quads: refused as it is, two triangles per quad with triangulate=True (the program's
    # --triangulate), the triangles of one face consecutive
    V = np.array([[x, y, 0.0] for y in range(3) for x in range(3)])
    quads = [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]]
    path = tmp_path / "quads.off"
    write_off(path, V, quads)
    with pytest.raises(tc.InvalidInput) as e:
        tc.read_mesh(path)
    assert e.value.code == "not_triangle_mesh" and "quads.off" in str(e.value)
    W, G = tc.read_mesh(path, triangulate=True)
    assert np.array_equal(W, V) and G.shape == (8, 3)
    for q in range(4):
        assert set(G[2 * q].tolist()) | set(G[2 * q + 1].tolist()) == set(quads[q])
    assert np.array_equal(tc.Solver.from_file(path, triangulate=True).faces, G)
    with pytest.raises(tc.InvalidInput) as e:
        tc.read_mesh(tmp_path / "missing.off")
    assert e.value.code == "io_error"
    (tmp_path / "mesh.xyz").write_text("0 0 0\n")
    with pytest.raises(tc.InvalidInput):
        tc.read_mesh(tmp_path / "mesh.xyz")


def test_read_mesh_of_cgal_meshes():
    for name in ["elephant.off", "sphere.ply", "sphere.stl", "colored_tetra.ply"]:
        path = cgal_mesh(name)
        V, F = tc.read_mesh(path)
        solver = tc.Solver.from_file(path)
        assert np.array_equal(V, solver.vertices) and np.array_equal(F, solver.faces)


# ---- topology -------------------------------------------------------------------------------------------------------


def numpy_topology(V, F):
    """per component (as sets of faces): (faces, chi, boundary loops), counted from V and F alone"""
    parent = list(range(len(F)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    by_edge = {}
    for f, t in enumerate(F.tolist()):
        for k in range(3):
            by_edge.setdefault(tuple(sorted((t[k], t[(k + 1) % 3]))), []).append(f)
    for faces in by_edge.values():
        for g in faces[1:]:
            parent[root(g)] = root(faces[0])
    out = {}
    for f in range(len(F)):
        out.setdefault(root(f), []).append(f)
    result = []
    for faces in out.values():
        face_set = set(faces)
        vertices = {int(v) for f in faces for v in F[f]}
        edges = [e for e, fs in by_edge.items() if fs[0] in face_set]
        border = [e for e in edges if len(by_edge[e]) == 1]
        # boundary loops: components of the border edges' graph (every border vertex is on one loop here)
        loop_parent = {v: v for e in border for v in e}

        def loop_root(v):
            while loop_parent[v] != v:
                v = loop_parent[v]
            return v

        for a, b in border:
            loop_parent[loop_root(a)] = loop_root(b)
        loops = len({loop_root(v) for v in loop_parent})
        result.append((frozenset(faces), len(vertices) - len(edges) + len(faces), loops))
    return result


def test_topology_is_that_of_the_mesh():
    V, F = concatenated(icosphere(1), torus(8, 6), bumpy_disk(5))
    solver = tc.Solver(V, F)
    topology = solver.topology
    expected = {faces: (chi, loops) for faces, chi, loops in numpy_topology(V, F)}
    assert len(topology) == len(expected) == 3
    for c in topology:
        faces = frozenset(c["faces"].tolist())
        chi, loops = expected[faces]
        assert c["number_of_faces"] == len(faces)
        assert c["euler_characteristic"] == chi and c["number_of_boundary_loops"] == loops
        assert c["genus"] == (2 - chi - loops) // 2 and c["closed"] == (loops == 0)
    assert sorted(c["euler_characteristic"] for c in topology) == [0, 1, 2]
    # what the README says: on every closed component, indices summing to its Euler characteristic
    singularities = {}
    for c in topology:
        if c["closed"] and c["euler_characteristic"] != 0:
            v = int(F[c["faces"][0]][0])
            singularities[v] = c["euler_characteristic"]
    result = solver.solve(singularities)
    assert result.max_residual < 1e-9


def test_topology_of_a_cgal_mesh():
    solver = tc.Solver.from_file(cgal_mesh("elephant.off"))  # closed, genus 3 (test_module.test_real_meshes)
    (c,) = solver.topology
    assert (c["euler_characteristic"], c["genus"], c["number_of_boundary_loops"]) == (-4, 3, 0)
    assert c["number_of_faces"] == solver.number_of_faces


# ---- progress, logging, Ctrl-C --------------------------------------------------------------------------------------


def test_progress_reports_the_phases():
    V, F = icosphere(2)
    calls = []
    solver = tc.Solver(V, F, progress=lambda phase, fraction: calls.append((phase, fraction)))
    phases = ["mesh setup", "geometry", "trees", "assembly", "factorization", "loop metric"]
    assert [p for p, f in calls if f == 1] == phases
    # from arrays the library reports only the end of the mesh setup (the arrays were made by the binding)
    assert [p for p, f in calls if f == 0] == phases[1:]
    assert all(0 <= f <= 1 for _, f in calls)
    calls.clear()
    solver.solve({0: 1, 1: 1}, n=4, progress=lambda p, f: calls.append((p, f)))
    assert ("solve", 0.0) in calls and ("solve", 1.0) in calls and ("field", 1.0) in calls
    calls.clear()
    solver.place_singularities(n=4, progress=lambda p, f: calls.append((p, f)))
    assert calls[0] == ("placement", 0.0) and calls[-1] == ("placement", 1.0)
    calls.clear()
    placed, _ = solver.place_singularities(n=4)
    solver.refine_singularities(placed, n=4, maximum_trials=3, progress=lambda p, f: calls.append((p, f)))
    assert sum(1 for c in calls if c == ("solve", 0.0)) >= 2  # every trial solve
    with pytest.raises(TypeError, match="progress must be a callable"):
        solver.solve({0: 1, 1: 1}, progress=3)


def test_progress_is_logged(caplog):
    V, F = icosphere(1)
    with caplog.at_level(logging.INFO, logger="trivial_connections"):
        tc.Solver(V, F).solve({0: 1, 1: 1})
    messages = [r.getMessage() for r in caplog.records if r.name == "trivial_connections"]
    assert "Solver() factorization: started" in messages
    assert any(re.fullmatch(r"solve\(\) solve: done in [0-9.]+ s", m) for m in messages)
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="trivial_connections"):
        tc.Solver(V, F)
    assert not [r for r in caplog.records if r.name == "trivial_connections"]


def test_an_exception_of_the_callback_abandons_the_call():
    V, F = icosphere(2)
    solver = tc.Solver(V, F)
    before = solver.solve({0: 1, 1: 1}, n=4)

    def stop(phase, fraction):
        if phase == "field":
            raise RuntimeError("stopped by the user")

    with pytest.raises(RuntimeError, match="stopped by the user"):
        solver.solve({0: 1, 1: 1}, n=4, progress=stop)
    after = solver.solve({0: 1, 1: 1}, n=4)
    assert np.array_equal(before.connection, after.connection) and np.array_equal(before.field, after.field)
    with pytest.raises(RuntimeError, match="stopped"):
        tc.Solver(V, F, progress=lambda p, f: (_ for _ in ()).throw(RuntimeError("stopped")))


def test_ctrl_c_between_phases():
    """A KeyboardInterrupt that arrives during a call (here: raised by interrupt_main() from the progress callable,
    as Ctrl-C would) stops it at the next phase; the solver stays usable."""
    V, F = icosphere(2)
    solver = tc.Solver(V, F)
    before = solver.solve({0: 1, 1: 1}, n=4)
    seen = []

    def interrupt_once(phase, fraction):
        seen.append(phase)
        if len(seen) == 1:
            _thread.interrupt_main()

    with pytest.raises(KeyboardInterrupt):
        solver.solve({0: 1, 1: 1}, n=4, progress=interrupt_once)
    assert len(seen) == 1  # abandoned at the next phase
    after = solver.solve({0: 1, 1: 1}, n=4)
    assert np.array_equal(before.connection, after.connection)
    seen.clear()
    with pytest.raises(KeyboardInterrupt):
        tc.Solver(V, F, progress=interrupt_once)
    assert len(seen) == 1


def interrupted_during(call, duration):
    """call(), which took about `duration` seconds, with SIGINT sent to this process (from a thread, as a user's
    Ctrl-C) 40 % of the way, again at 20 % if the call ended first: the seconds until KeyboardInterrupt"""
    for delay in [0.4 * duration, 0.2 * duration]:
        timer = threading.Timer(delay, os.kill, (os.getpid(), signal.SIGINT))
        start = time.perf_counter()
        timer.start()
        try:
            call()
        except KeyboardInterrupt:
            timer.join()
            return time.perf_counter() - start
        try:  # the signal still comes: take it here
            timer.join()
            time.sleep(2)
        except KeyboardInterrupt:
            pass
    pytest.fail(f"the call ({duration:.2f} s) ended before the interrupt twice")


@pytest.mark.skipif(not hasattr(signal, "SIGINT") or sys.platform == "win32", reason="needs POSIX signals")
def test_ctrl_c_during_long_calls_on_a_cgal_mesh():
    """SIGINT, as a user's Ctrl-C, during the constructor, the automatic placement and the refinement on the largest
    mesh of CGAL's data set (89k faces): KeyboardInterrupt soon after, and the solver still solves as it did."""
    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        pytest.skip("SIGINT is not Python's default handler here")
    V, F = tc.read_mesh(cgal_mesh("refined_elephant.off"))

    def timed(call):
        start = time.perf_counter()
        value = call()
        return value, time.perf_counter() - start

    solver, build = timed(lambda: tc.Solver(V, F))
    (placed, _), place = timed(lambda: solver.place_singularities(n=4))
    _, refine = timed(lambda: solver.refine_singularities(placed, n=4, cancel_pairs=True))
    reference = solver.solve(placed, n=4)
    # each raised before the call would have ended, give or take a phase (the constructor checks between phases)
    assert interrupted_during(lambda: tc.Solver(V, F), build) < 2 * build + 1
    assert interrupted_during(lambda: solver.place_singularities(n=4), place) < 2 * place + 1
    assert interrupted_during(lambda: solver.refine_singularities(placed, n=4, cancel_pairs=True), refine) < \
        2 * refine + 1
    again = solver.solve(placed, n=4)
    assert again.max_residual < 1e-8 and abs(again.energy - reference.energy) <= 1e-9 * reference.energy


def test_progress_from_threads_does_not_deadlock():
    V, F = icosphere(2)
    solver = tc.Solver(V, F)
    counts = []

    def work():
        calls = []
        for _ in range(5):
            solver.solve({0: 1, 1: 1}, n=4, progress=lambda p, f: calls.append(p))
        counts.append(len(calls))

    threads = [threading.Thread(target=work) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(60)
    assert len(counts) == 4 and min(counts) > 0
