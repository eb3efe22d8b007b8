"""The field editor's server (issues 22 and 36): its answers (constraints, boundary alignment, streamlines, files
saved and loaded in its folder, the mesh's angle defects) checked against the module, and bad requests: a 4xx with a
one-line reason, the session keeps working, nothing written; saves that never replace the mesh, nor another file
without "overwrite": true; malformed bodies, framings and methods answered, never a dropped connection. Runs editor/serve.py in this process on generated
meshes (PYTHONPATH: the module)."""
import ast
import fractions
import http.client
import importlib.util
import json
import math
import os
import re
import socket
import threading

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("serve", os.path.join(HERE, "..", "..", "editor", "serve.py"))
serve = importlib.util.module_from_spec(spec)
spec.loader.exec_module(serve)
tc = serve.tc


def off_file(path, V, F):
    """writes the points V and triangles F as an OFF file (coordinates exactly) and returns its path"""
    with open(path, "w") as f:
        f.write(f"OFF\n{len(V)} {len(F)} 0\n")
        f.writelines(f"{float(x)!r} {float(y)!r} {float(z)!r}\n" for x, y, z in V)
        f.writelines(f"3 {a} {b} {c}\n" for a, b, c in F)
    return path


def octahedron_file(folder):
    V = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    F = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    return off_file(os.path.join(folder, "octahedron.off"), V, F)


def disk_file(folder, n=6):
    """a bumpy square disk of 2 n^2 triangles (one boundary loop)"""
    x, y = np.meshgrid(np.linspace(-1, 1, n + 1), np.linspace(-1, 1, n + 1), indexing="ij")
    V = np.stack([x, y, 0.3 * np.exp(-2 * (x**2 + y**2)) + 0.1 * x * y], -1).reshape(-1, 3)
    idx = lambda i, j: i * (n + 1) + j
    F = [t for i in range(n) for j in range(n)
         for t in [(idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)), (idx(i, j), idx(i + 1, j + 1), idx(i, j + 1))]]
    return off_file(os.path.join(folder, "disk.off"), V, F)


def start(mesh, folder):
    """the server on `mesh`, its files in `folder`, on a free port (a Handler class of its own)"""
    handler = type("Handler", (serve.Handler,), {"session": serve.Session(mesh, 4, folder), "bundle": folder})
    httpd = serve.http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    return httpd


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    folder = tmp_path_factory.mktemp("editor")
    httpd = start(octahedron_file(str(folder)), str(folder))
    yield httpd.server_address[1], folder
    httpd.shutdown()


@pytest.fixture(scope="module")
def disk(tmp_path_factory):
    """the server on a bordered mesh, with a folder of files and a folder outside it"""
    meshes = tmp_path_factory.mktemp("meshes")
    folder = tmp_path_factory.mktemp("files")
    outside = tmp_path_factory.mktemp("outside")
    mesh = disk_file(str(meshes))
    httpd = start(mesh, str(folder))
    yield httpd.server_address[1], mesh, folder, outside
    httpd.shutdown()


def request(port, method, path, body=None, headers=None):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    c.request(method, path, body=body, headers=headers or {})
    r = c.getresponse()
    data = r.read()
    c.close()
    return r.status, data


def solve(port, singularities, n=4):
    return request(port, "POST", "/api/solve", json.dumps({"n": n, "singularities": singularities}))


def post(port, path, body):
    return request(port, "POST", path, json.dumps(body))


def parse(data):
    """a frame: its header and {name: array}"""
    assert data[:4] == b"TCB1"
    length = int.from_bytes(data[4:8], "little")
    assert (8 + length) % 8 == 0
    header = json.loads(data[8:8 + length])
    arrays = {}
    for a in header["arrays"]:
        assert a["offset"] % 8 == 0
        count = int(np.prod(a["shape"]))
        arrays[a["name"]] = np.frombuffer(data, a["dtype"], count, 8 + length + a["offset"]).reshape(a["shape"])
    return header, arrays


def answer(port, path, body):
    """the header and arrays of a request that must succeed; a solve's field (one unit vector per face) made from
    its angles"""
    status, data = post(port, path, body)
    assert status == 200, data
    header, arrays = parse(data)
    if "angle" in arrays:
        arrays["field"] = field_of(port, arrays["angle"])
    return header, arrays


def field_of(port, angle):
    """the unit vectors of the angles of /api/solve: counter-clockwise from each face's first edge"""
    V, F = mesh_of(port)
    a, b, c = (V[F[:, k]] for k in range(3))
    e1 = (b - a) / np.linalg.norm(b - a, axis=1)[:, None]
    normal = np.cross(b - a, c - a)
    e2 = np.cross(normal / np.linalg.norm(normal, axis=1)[:, None], e1)
    angle = angle.astype(float)[:, None]
    return np.cos(angle) * e1 + np.sin(angle) * e2


def test_a_good_solve_gives_n_directions_per_face(server):
    port, _ = server
    status, data = solve(port, [[v, "1/4"] for v in range(6)])  # 6 x 1/4: sum 3/2, not 2
    assert status == 422 and b"Poincare-Hopf" in data
    status, data = solve(port, [[v, "1/3"] for v in range(6)], n=3)
    assert status == 200
    frame = data
    assert frame[:4] == b"TCB1"
    length = int.from_bytes(frame[4:8], "little")
    header = json.loads(frame[8:8 + length])
    [angle] = header["arrays"]
    assert angle["name"] == "angle" and angle["shape"] == [8] and header["max_residual"] < 1e-9


@pytest.mark.parametrize("body, code", [
    (b"{not json", 400),
    (b"[1, 2]", 400),
    (json.dumps({"n": "four"}).encode(), 400),
    (json.dumps({"n": 4, "singularities": [[0]]}).encode(), 400),
    (json.dumps({"n": 4, "singularities": [[99, "1"], [0, "1"]]}).encode(), 422),  # no vertex 99
    (json.dumps({"n": 4, "singularities": [[0, "1/3"], [1, "5/3"]]}).encode(), 422),  # not multiples of 1/4
    (json.dumps({"n": 4, "singularities": [[0, "1"]]}).encode(), 422),  # unbalanced: 1 of chi = 2
])
def test_bad_requests_get_a_4xx_and_the_session_keeps_working(server, body, code):
    port, folder = server
    before = sorted(os.listdir(folder))
    status, data = request(port, "POST", "/api/solve", body)
    assert status == code
    assert data.endswith(b"\n") and data.count(b"\n") == 1 and len(data) > 10  # one line, with a reason
    status, _ = solve(port, [[0, 1], [1, 1]])
    assert status == 200
    assert sorted(os.listdir(folder)) == before  # nothing written


def test_huge_payloads_and_paths_outside(server):
    port, _ = server
    # refused on its Content-Length, before reading it
    limit = serve.MAX_BODY + serve.BODY_PER_FACE * 8  # the octahedron's 8 faces
    status, data = request(port, "POST", "/api/solve", b"{}", {"Content-Length": str(limit + 1)})
    assert status == 413 and b"at most" in data
    status, data = request(port, "POST", "/api/solve", b"{}", {"Content-Length": "-5"})
    assert status == 400
    for path in ["/../serve.py", "/%2e%2e/serve.py", "/editor.js/../../etc/passwd", "/etc/passwd"]:
        status, _ = request(port, "GET", path)
        assert status == 404
    assert solve(port, [[0, 1], [1, 1]])[0] == 200


def test_two_clients_get_consistent_answers(server):
    port, _ = server
    answers = []

    def client():
        for _ in range(5):
            frame = solve(port, [[2, 1], [3, 1]])[1]
            length = int.from_bytes(frame[4:8], "little")
            header = json.loads(frame[8:8 + length])
            answers.append((header["energy"], frame[8 + length:]))  # all but the timings

    threads = [threading.Thread(target=client) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(answers) == 10 and len(set(answers)) == 1


# ---- the mesh frame ----------------------------------------------------------------------------------------


def corner_angle_sums(V, F):
    """per vertex, the sum of its corner angles, one corner at a time (acos, not the server's arctan2)"""
    total = np.zeros(len(V))
    for face in F:
        for k in range(3):
            a, b, c = V[face[k]], V[face[(k + 1) % 3]], V[face[(k + 2) % 3]]
            u, w = b - a, c - a
            total[face[k]] += math.acos(max(-1.0, min(1.0, u @ w / (np.linalg.norm(u) * np.linalg.norm(w)))))
    return total


def test_the_mesh_frame_has_the_angle_defects(server, disk):
    port, _ = server
    status, data = request(port, "GET", "/api/mesh")
    header, arrays = parse(data)
    K = arrays["angle_defect"]
    assert K.dtype == np.dtype("<f4") and K.shape == (6,)
    assert np.allclose(K, 2 * np.pi / 3, atol=1e-6)  # four corners of 60 degrees
    assert abs(K.sum() - 2 * np.pi * 2) < 1e-5  # Gauss-Bonnet: 2 pi chi
    port, mesh, _, _ = disk
    header, arrays = parse(request(port, "GET", "/api/mesh")[1])
    V, F = arrays["V"].astype(float), arrays["F"].astype(int)
    expected = 2 * np.pi - corner_angle_sums(V, F)
    assert arrays["angle_defect"].shape == (len(V),)
    assert np.allclose(arrays["angle_defect"], expected, atol=1e-5)
    assert header["closed"] == [False]


# ---- constraints -------------------------------------------------------------------------------------------


def mesh_of(port):
    _, arrays = parse(request(port, "GET", "/api/mesh")[1])
    return arrays["V"].astype(float), arrays["F"].astype(int)


def unit(v):
    return v / np.linalg.norm(v)


def face_normal(V, F, f):
    a, b, c = V[F[f]]
    return unit(np.cross(b - a, c - a))


def turn_to(field, target, N, n):
    """the angle from the target to the field about N, modulo 2 pi / n, in (-pi / n, pi / n]"""
    angle = math.atan2(np.cross(target, field) @ N, target @ field)
    period = 2 * np.pi / n
    return (angle + period / 2) % period - period / 2


@pytest.mark.parametrize("n", [1, 4])
def test_a_pinned_face_points_along_its_direction_projected(server, n):
    port, _ = server
    V, F = mesh_of(port)
    pins = {2: [0.3, -1.0, 2.0], 5: [-1.0, 0.2, 0.1]}  # not tangent: projected onto the face
    header, arrays = answer(port, "/api/solve", {"n": n, "singularities": [[0, 1], [1, 1]],
                                                 "constraints": [[f, d] for f, d in pins.items()]})
    field = arrays["field"].astype(float)
    for f, d in pins.items():
        N = face_normal(V, F, f)
        target = unit(np.array(d) - (np.array(d) @ N) * N)
        if n == 1:
            assert np.allclose(field[f], target, atol=2e-6)
        else:
            assert abs(turn_to(unit(field[f]), target, N, n)) < 2e-6
    assert isinstance(header["constraints"], list) and len(header["constraints"]) == 1  # one path joins the two
    json.dumps(header["constraints"], allow_nan=False)


def test_constraint_sets_switch_and_each_request_gets_its_own(server):
    port, _ = server
    base = {"n": 4, "singularities": [[2, 1], [3, 1]]}
    bodies = [dict(base, constraints=[[1, [1, 0, 0]]]), dict(base, constraints=[[6, [0, 1, 0]], [0, [0, 0, 1]]]),
              dict(base)]
    field = lambda body: answer(port, "/api/solve", body)[1]["field"]
    expected = [field(b) for b in bodies]
    assert min(np.abs(expected[i] - expected[j]).max() for i, j in [(0, 1), (1, 2), (0, 2)]) > 1e-2
    again = [field(b) for b in reversed(bodies)]
    # the same answers (to rounding: the constrained faces' links in the factor are updated as the sets change)
    assert all(np.allclose(a, e, atol=1e-6) for a, e in zip(again[::-1], expected))
    # two tabs, each with its own constraints, at the same time
    wrong = []

    def tab(k):
        for _ in range(25):
            try:
                if not np.allclose(field(bodies[k]), expected[k], atol=1e-6):
                    wrong.append(k)
            except Exception as e:  # e.g. a refusal: the solver had another tab's constraints
                wrong.append((k, repr(e)))

    threads = [threading.Thread(target=tab, args=(k,)) for k in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert wrong == []


@pytest.mark.parametrize("endpoint, extra", [("/api/solve", {}), ("/api/streamlines", {}),
                                             ("/api/save", {"kind": "singularities", "path": "twice.sing"}),
                                             ("/api/save", {"kind": "field", "path": "twice.txt"})])
@pytest.mark.parametrize("singularities, vertex", [
    ([[0, 1], [1, 1], [1, 1]], 1),          # last-wins would be {0: 1, 1: 1}: balanced, and solved
    ([[0, 1], [1, "1/4"], [1, "3/4"]], 1),  # last-wins would be balanced too
    ([[0, 1], [0, "1"], [1, 1]], 0),        # the same index, written two ways
    ([[3, 2], [3, -1], [3, 1]], 3),
])
def test_a_vertex_listed_twice_is_refused(server, endpoint, extra, singularities, vertex):
    port, folder = server
    before = tree(str(folder))
    status, data = post(port, endpoint, dict({"n": 4, "singularities": singularities}, **extra))
    assert status == 422 and one_line(data), (status, data)
    assert data == f"duplicate_singularity: vertex {vertex} is listed twice\n".encode()
    assert solve(port, [[0, 1], [1, 1]])[0] == 200
    assert tree(str(folder)) == before


@pytest.mark.parametrize("endpoint, extra", [("/api/solve", {}), ("/api/place", {}), ("/api/streamlines", {}),
                                             ("/api/save", {"kind": "constraints", "path": "twice.dirs"})])
def test_a_face_listed_twice_is_refused(server, endpoint, extra):
    port, folder = server
    before = tree(str(folder))
    body = {"n": 4, "singularities": [[0, 1], [1, 1]], "constraints": [[5, [1, 0, 0]], [2, [0, 0, 1]], [5, [0, 1, 0]]]}
    status, data = post(port, endpoint, dict(body, **extra))
    assert status == 422 and data == b"invalid_constraint: face 5 is constrained twice\n", (status, data)
    assert tree(str(folder)) == before


@pytest.mark.parametrize("constraints, code", [
    ({"2": [1, 0, 0]}, 400),                  # not a list
    ([2, [1, 0, 0]], 400),                    # not a list of pairs
    ([[2]], 400),
    ([[2, [1, 0]]], 400),                     # two numbers
    ([["2", [1, 0, 0]]], 400),                # the face a string
    ([[True, [1, 0, 0]]], 400),
    ([[2, [1, "0", 0]]], 400),
    ([[8, [1, 0, 0]]], 422),                  # no face 8
    ([[-1, [1, 0, 0]]], 422),
    ([[2, [0, 0, 0.0]]], 422),                # zero
    ([[2, [float("inf"), 0, 0]]], 400),       # Infinity: Python's json writes it, the server reads no such JSON
    ([[2, [float("nan"), 0, 0]]], 400),
    ([[2, [10**400, 0, 0]]], 422),            # too large for a float
    ([[2, [1, 0, 0]], [2, [0, 1, 0]]], 422),  # face 2 twice
    ([[0, [1, 1, 1]]], 422),                  # normal to face 0 (the library refuses it)
    ([[0, [1, 0, 0]]] * 2001, 422),           # no cap on the number of pins, but each face once
])
def test_bad_constraints_are_refused(server, constraints, code):
    port, folder = server
    before = sorted(os.listdir(folder))
    status, data = post(port, "/api/solve", {"n": 4, "singularities": [[0, 1], [1, 1]], "constraints": constraints})
    assert status == code, data
    assert data.endswith(b"\n") and data.count(b"\n") == 1
    if code == 422:
        assert data.startswith(b"invalid_constraint:")
    assert solve(port, [[0, 1], [1, 1]])[0] == 200
    assert sorted(os.listdir(folder)) == before


@pytest.mark.parametrize("body", [{"align_boundary": "yes"}, {"align_boundary": 1}, {"seeds": 0}])
def test_bad_options_are_refused(server, body):
    port, _ = server
    status, data = post(port, "/api/streamlines", dict({"n": 4, "singularities": [[0, 1], [1, 1]]}, **body))
    assert status == 400 and data.count(b"\n") == 1
    assert solve(port, [[0, 1], [1, 1]])[0] == 200


# ---- boundary alignment ------------------------------------------------------------------------------------


def test_align_boundary_follows_the_boundary_and_is_the_modules_answer(disk):
    port, mesh, _, _ = disk
    V, F = mesh_of(port)
    body = {"n": 4, "singularities": []}
    plain = answer(port, "/api/solve", body)[1]["field"]
    aligned = answer(port, "/api/solve", dict(body, align_boundary=True))[1]["field"]
    assert np.abs(plain - aligned).max() > 1e-2
    direct = tc.Solver.from_file(mesh, align_boundary=True).solve({}, n=4).field
    assert np.allclose(aligned, direct, atol=1e-6)
    assert np.array_equal(answer(port, "/api/solve", body)[1]["field"], plain)  # the plain solver is untouched
    # on every face with a border edge, the cross is along that edge
    edges = {}
    for f, t in enumerate(F):
        for a, b in zip(t, np.roll(t, -1)):
            edges.setdefault((min(a, b), max(a, b)), []).append((f, a, b))
    checked = 0
    for (a, b), sides in edges.items():
        if len(sides) == 1 and sum(len(edges[(min(p, q), max(p, q))]) == 1
                                   for p, q in zip(F[sides[0][0]], np.roll(F[sides[0][0]], -1))) == 1:
            f, p, q = sides[0]
            assert abs(turn_to(unit(aligned[f].astype(float)), unit(V[q] - V[p]), face_normal(V, F, f), 4)) < 1e-5
            checked += 1
    assert checked >= 10
    # with constraints inside, on its own constraint state
    pinned = dict(body, align_boundary=True, constraints=[[30, [1, 0.5, 0]]])
    field = answer(port, "/api/solve", pinned)[1]["field"]
    N = face_normal(V, F, 30)
    assert abs(turn_to(unit(field[30].astype(float)), unit(np.array([1, 0.5, 0]) - (N @ [1, 0.5, 0]) * N), N, 4)) < 2e-6
    assert np.array_equal(answer(port, "/api/solve", body)[1]["field"], plain)
    # a constraint on an aligned boundary face is the library's refusal
    status, data = post(port, "/api/solve", dict(pinned, constraints=[[0, [1, 0, 0]]]))
    assert status == 422 and data.startswith(b"invalid_constraint:")
    # back to no constraint: the same field (to rounding: the factor's links were updated twice)
    assert np.allclose(answer(port, "/api/solve", dict(body, align_boundary=True))[1]["field"], aligned, atol=1e-6)


def test_align_boundary_on_a_closed_mesh_is_the_plain_solve(server):
    port, _ = server
    body = {"n": 4, "singularities": [[0, 1], [1, 1]]}
    assert (answer(port, "/api/solve", dict(body, align_boundary=True))[1]["field"].tobytes()
            == answer(port, "/api/solve", body)[1]["field"].tobytes())


# ---- streamlines -------------------------------------------------------------------------------------------


@pytest.mark.parametrize("n, seeds", [(4, None), (1, 10), (3, 5000)])
def test_streamlines_frame_is_well_formed(disk, n, seeds):
    port, _, _, _ = disk
    V, F = mesh_of(port)
    body = {"n": n, "singularities": [], "align_boundary": True}
    if seeds is not None:
        body["seeds"] = seeds
    header, arrays = answer(port, "/api/streamlines", body)
    points, offsets = arrays["points"], arrays["offsets"]
    assert points.dtype == np.dtype("<f4") and points.ndim == 2 and points.shape[1] == 3
    assert offsets.dtype == np.dtype("<u4") and offsets.shape == (header["lines"] + 1,)
    assert header["lines"] > 0 and offsets[0] == 0 and offsets[-1] == len(points)
    assert np.all(np.diff(offsets.astype(int)) >= 2)  # every line has two points or more
    assert np.all(points >= V.min(0) - 1e-5) and np.all(points <= V.max(0) + 1e-5)
    assert 1 <= header["seeds"] <= min(len(F), seeds or serve.DEFAULT_SEEDS)
    assert header["maximum_faces_per_ray"] >= 2
    again = answer(port, "/api/streamlines", body)[1]
    assert again["points"].tobytes() == points.tobytes()  # the same seeds every time


# ---- files: save and load ----------------------------------------------------------------------------------


def tree(*folders):
    """every path under the folders (and the folders' parents' entries): to see that nothing was written"""
    out = set()
    for folder in folders:
        for root, dirs, files in os.walk(folder):
            out.update(os.path.join(root, name) for name in dirs + files)
        out.update(os.path.join(os.path.dirname(folder), name) for name in os.listdir(os.path.dirname(folder)))
    return out


SING = [[8, "1/4"], [24, -1], [38, "3/4"]]  # interior vertices of the disk
PINS = [[40, [0.1, 0.7, 0.2]], [7, [1.0, -0.25, 1 / 3]]]


def test_save_every_kind_and_read_it_back(disk):
    port, mesh, folder, _ = disk
    os.makedirs(os.path.join(folder, "sub"), exist_ok=True)
    body = {"n": 4, "singularities": SING, "constraints": PINS}
    saved = {}
    for kind, name in [("singularities", "s.sing"), ("constraints", "sub/c.dir"), ("field", "f.txt"),
                       ("vtk", "f.vtk"), ("ply", "f.ply"), ("streamlines", "lines.vtk")]:
        header, arrays = answer(port, "/api/save", dict(body, kind=kind, path=name))
        assert header["saved"] == name and arrays == {}
        assert header["bytes"] == os.path.getsize(os.path.join(folder, name)) > 0
        saved[kind] = os.path.join(folder, name)
    solver = tc.Solver.from_file(mesh)
    assert tc.read_singularities(saved["singularities"], solver.number_of_vertices) == {
        v: fractions.Fraction(k) for v, k in SING}
    faces, directions = tc.read_face_directions(saved["constraints"], solver.number_of_faces)
    assert faces.tolist() == [f for f, _ in PINS] and directions.tolist() == [d for _, d in PINS]
    solver.set_constraints(constrained_faces=[f for f, _ in PINS])
    result = solver.solve(dict(SING), n=4, directions={f: d for f, d in PINS})
    with open(saved["field"]) as f:
        field = np.array([[float(x) for x in line.split()] for line in f if not line.startswith("#")])
    assert field.shape == result.field.shape and np.abs(field - result.field).max() < 1e-12
    with open(saved["vtk"]) as f:
        assert f.readline().startswith("# vtk DataFile")
    with open(saved["ply"], "rb") as f:
        assert f.readline().strip() == b"ply"
    with open(saved["streamlines"]) as f:
        assert "LINES" in f.read()
    assert not [name for name in os.listdir(folder) if name.startswith(".")]  # no temporary file left
    # saving again replaces the file only when the request says so
    again = dict(body, singularities=[], kind="singularities", path="s.sing")
    status, data = post(port, "/api/save", again)
    assert status == 409 and b"already exists" in data
    assert tc.read_singularities(saved["singularities"]) == {v: fractions.Fraction(k) for v, k in SING}
    header, _ = answer(port, "/api/save", dict(again, overwrite=True))
    assert tc.read_singularities(saved["singularities"]) == {}
    assert not [name for name in os.listdir(folder) if name.startswith(".")]


def test_load_round_trip(disk):
    port, _, folder, _ = disk
    body = {"n": 4, "singularities": SING, "constraints": PINS}
    answer(port, "/api/save", dict(body, kind="singularities", path="round.sing"))
    answer(port, "/api/save", dict(body, kind="constraints", path="round.dir"))
    header, _ = answer(port, "/api/load", {"kind": "singularities", "path": "round.sing"})
    assert header["singularities"] == [[v, str(fractions.Fraction(k))] for v, k in SING]
    header, _ = answer(port, "/api/load", {"kind": "constraints", "path": "round.dir"})
    assert header["constraints"] == PINS  # the same floats
    # what was loaded solves as it was saved
    assert (answer(port, "/api/solve", dict(body, **header))[1]["field"].tobytes()
            == answer(port, "/api/solve", body)[1]["field"].tobytes())


def refusals(folder, outside):
    """(endpoint, body, status, part of the reason) for paths and files the server must refuse"""
    with open(os.path.join(outside, "secret.sing"), "w") as f:
        f.write("3 1\n")
    for name, target in [("out", outside), ("secret.sing", os.path.join(outside, "secret.sing")),
                         ("new.sing", os.path.join(outside, "new.sing"))]:
        if not os.path.lexists(os.path.join(folder, name)):
            os.symlink(target, os.path.join(folder, name))
    os.makedirs(os.path.join(folder, "adir"), exist_ok=True)
    with open(os.path.join(folder, "bad.sing"), "w") as f:
        f.write("# two lines\n3 1/4\n10\n")
    with open(os.path.join(folder, "far.dir"), "w") as f:
        f.write("0 1 0 0\n72 1 0 0\n")
    save = {"n": 4, "singularities": SING, "kind": "singularities"}
    cases = []
    for path, status in [("../x.sing", 403), ("adir/../../x.sing", 403), (os.path.join(outside, "x.sing"), 400),
                         (os.path.join(folder, "x.sing"), 400), ("out/x.sing", 403), ("new.sing", 403),
                         ("secret.sing", 403), ("adir", 400), (".", 400), ("nodir/x.sing", 404), ("", 400),
                         (5, 400), (None, 400), ("x\0.sing", 400)]:
        cases.append(("/api/save", dict(save, path=path), status, ""))
    cases += [
        ("/api/save", dict(save, kind="pdf", path="x.pdf"), 400, "kind"),
        ("/api/save", dict(save, kind="field", path="x.vtk"), 400, ".txt"),
        ("/api/save", dict(save, kind="vtk", path="x.ply"), 400, ".vtk"),
        ("/api/save", dict(save, path="x.sing", singularities=[[999, 1]]), 422, "invalid_vertex"),
        ("/api/save", dict(save, path="x.sing", constraints=[[0, [0, 0, 0]]]), 422, "invalid_constraint"),
        ("/api/save", dict(save, path="x.sing", align_boundary=True, constraints=[[0, [1, 0, 0]]]), 422,
         "invalid_constraint"),  # on the aligned boundary
        ("/api/save", dict(save, kind="streamlines", path="x.vtk", seeds=-1), 400, "seeds"),
        ("/api/save", dict(save, path="x.sing", n="4"), 400, "n must be"),
    ]
    for path, status in [("../x.sing", 403), ("secret.sing", 403), ("out/secret.sing", 403),
                         (os.path.join(outside, "secret.sing"), 400), ("missing.sing", 404), ("adir", 400),
                         ("", 400), ([], 400)]:
        cases.append(("/api/load", {"kind": "singularities", "path": path}, status, ""))
    cases += [
        ("/api/load", {"kind": "field", "path": "bad.sing"}, 400, "kind"),
        ("/api/load", {"kind": "singularities", "path": "bad.sing"}, 422, "parse_error: bad.sing:3:"),
        ("/api/load", {"kind": "constraints", "path": "bad.sing"}, 422, "parse_error: bad.sing:2:"),
        ("/api/load", {"kind": "constraints", "path": "far.dir"}, 422, "invalid_constraint: far.dir:2: face 72"),
    ]
    return cases


def test_refusals_write_nothing_and_the_session_keeps_working(disk):
    port, _, folder, outside = disk
    folder, outside = str(folder), str(outside)
    cases = refusals(folder, outside)
    before = tree(folder, outside)
    for endpoint, body, status, part in cases:
        code, data = post(port, endpoint, body)
        assert code == status, (endpoint, body, data)
        reason = data.decode()
        assert reason.endswith("\n") and reason.count("\n") == 1 and len(reason) > 10, reason
        assert part in reason, (reason, part)
        assert folder not in reason  # paths as the page named them
        assert answer(port, "/api/solve", {"n": 4, "singularities": SING})[0]["max_residual"] < 1e-9
        assert tree(folder, outside) == before, (endpoint, body)
    with open(os.path.join(outside, "secret.sing")) as f:
        assert f.read() == "3 1\n"


def test_one_connection_many_requests(server):
    """keep-alive: replies of every kind, refusals included, on one connection, each whole"""
    port, _ = server
    assert serve.Handler.disable_nagle_algorithm
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    for body, status in [({"n": 4, "singularities": [[0, 1], [1, 1]]}, 200), ({"n": 0}, 400),
                         ({"n": 4, "singularities": [[0, 1]]}, 422), ({"n": 4, "singularities": [[0, 1], [1, 1]]}, 200)]:
        c.request("POST", "/api/solve", json.dumps(body))
        r = c.getresponse()
        data = r.read()
        assert r.status == status and int(r.getheader("Content-Length")) == len(data)
        if status == 200:
            assert parse(data)[1]["angle"].shape == (8,)
    c.request("GET", "/api/mesh")
    r = c.getresponse()
    assert r.status == 200 and parse(r.read())[0]["faces"] == 8
    c.close()


# ---- saving over files: never the mesh, other files only with "overwrite": true (issue 36) ---------------------


@pytest.fixture
def held(tmp_path):
    """the server as `cd DIR; trivial_connections-serve held.off` starts it: the mesh in the folder (the current
    directory, by default)"""
    mesh = os.path.join(str(tmp_path), "held.off")
    os.rename(octahedron_file(str(tmp_path)), mesh)
    httpd = start(mesh, str(tmp_path))
    yield httpd.server_address[1], str(tmp_path), mesh
    httpd.shutdown()


def contents(path):
    with open(path, "rb") as f:
        return f.read()


def one_line(data):
    return data.endswith(b"\n") and data.count(b"\n") == 1 and len(data) > 10


OCTAHEDRON_SOLVE = {"n": 4, "singularities": [[0, 1], [1, 1]]}


def test_save_never_replaces_the_mesh(held):
    port, folder, mesh = held
    os.link(mesh, os.path.join(folder, "hard.off"))  # another name of the same file
    os.symlink("held.off", os.path.join(folder, "soft.off"))
    os.symlink(mesh, os.path.join(folder, "absolute.off"))
    os.makedirs(os.path.join(folder, "sub"))
    os.symlink(os.path.join("..", "hard.off"), os.path.join(folder, "sub", "up.off"))
    before, stat = contents(mesh), os.stat(mesh)
    names = tree(folder)
    for path in ["held.off", "./held.off", "sub/../held.off", "hard.off", "soft.off", "absolute.off", "sub/up.off"]:
        for kind in ["singularities", "constraints", "streamlines"]:
            for overwrite in [{}, {"overwrite": False}, {"overwrite": True}]:
                status, data = post(port, "/api/save", dict(OCTAHEDRON_SOLVE, kind=kind, path=path, **overwrite))
                assert status == 403, (path, kind, overwrite, status, data)
                assert one_line(data) and b"the mesh being edited" in data and folder.encode() not in data, data
    assert contents(mesh) == before and os.stat(mesh).st_ino == stat.st_ino
    assert tree(folder) == names  # nothing written, no temporary left
    assert answer(port, "/api/solve", OCTAHEDRON_SOLVE)[0]["max_residual"] < 1e-9


def test_save_over_an_existing_file_needs_overwrite(held):
    port, folder, _ = held
    taken = os.path.join(folder, "taken.sing")
    with open(taken, "w") as f:
        f.write("# someone's file\n")
    os.symlink("taken.sing", os.path.join(folder, "alias.sing"))
    names = tree(folder)
    body = dict(OCTAHEDRON_SOLVE, kind="singularities")
    for path in ["taken.sing", "alias.sing"]:
        for overwrite in [{}, {"overwrite": False}]:
            status, data = post(port, "/api/save", dict(body, path=path, **overwrite))
            assert status == 409 and one_line(data) and b"already exists" in data, (status, data)
    for overwrite in ["yes", 1, None]:
        status, data = post(port, "/api/save", dict(body, path="taken.sing", overwrite=overwrite))
        assert status == 400 and b"overwrite must be" in data, data
    # a save that would fail anyway is refused for that, not for the file: the page asks only about saves that work
    status, data = post(port, "/api/save", dict(body, path="taken.sing", singularities=[[0, 1]]))
    assert status == 422 and data.startswith(b"poincare_hopf_violated"), data
    assert contents(taken) == b"# someone's file\n" and tree(folder) == names
    # confirmed: replaced, whole
    header, _ = answer(port, "/api/save", dict(body, path="taken.sing", overwrite=True))
    assert header["saved"] == "taken.sing" and header["bytes"] == os.path.getsize(taken)
    assert tc.read_singularities(taken) == {0: 1, 1: 1}
    # through a link inside the folder, the file it names is replaced (the link stays)
    header, _ = answer(port, "/api/save", dict(body, singularities=[[2, 1], [3, 1]], path="alias.sing",
                                               overwrite=True))
    assert header["saved"] == "taken.sing" and os.path.islink(os.path.join(folder, "alias.sing"))
    assert tc.read_singularities(taken) == {2: 1, 3: 1}
    # a new name needs no confirmation; overwrite: true on a new name writes it too
    answer(port, "/api/save", dict(body, path="new.sing"))
    answer(port, "/api/save", dict(body, path="newer.sing", overwrite=True))
    assert tree(folder) == names | {os.path.join(folder, "new.sing"), os.path.join(folder, "newer.sing")}
    # not a regular file: never replaced
    os.mkfifo(os.path.join(folder, "pipe.sing"))
    status, data = post(port, "/api/save", dict(body, path="pipe.sing", overwrite=True))
    assert status == 400 and b"not a regular file" in data


def test_a_file_that_appears_during_a_save_is_not_replaced(held, monkeypatch):
    """the check for an existing file comes before the solve; a file given the name after it (here: while the
    library writes) is not replaced either: without overwrite the new file is linked into place, never renamed"""
    port, folder, _ = held
    late = os.path.join(folder, "late.sing")
    write = tc.write_singularities

    def racing(path, singularities):
        with open(late, "w") as f:
            f.write("# written meanwhile\n")
        write(path, singularities)

    monkeypatch.setattr(tc, "write_singularities", racing)
    status, data = post(port, "/api/save", dict(OCTAHEDRON_SOLVE, kind="singularities", path="late.sing"))
    assert status == 409 and one_line(data) and b"already exists" in data, (status, data)
    assert contents(late) == b"# written meanwhile\n"
    assert not [name for name in os.listdir(folder) if name.startswith(".")]  # no temporary left


@pytest.mark.parametrize("refusal", [PermissionError(1, "Operation not permitted"), OSError(95, "Not supported")])
def test_save_on_a_file_system_without_hard_links(held, monkeypatch, refusal):
    """os.link refused (EPERM, EOPNOTSUPP: e.g. FAT, some network file systems): the name is taken with O_EXCL,
    still never replacing a file"""
    port, folder, _ = held

    def no_link(*args, **kwargs):
        raise refusal

    monkeypatch.setattr(serve.os, "link", no_link)
    body = dict(OCTAHEDRON_SOLVE, kind="singularities", path="fat.sing")
    answer(port, "/api/save", body)
    assert tc.read_singularities(os.path.join(folder, "fat.sing")) == {0: 1, 1: 1}
    status, data = post(port, "/api/save", dict(body, singularities=[[4, 1], [5, 1]]))
    assert status == 409 and tc.read_singularities(os.path.join(folder, "fat.sing")) == {0: 1, 1: 1}
    answer(port, "/api/save", dict(body, singularities=[[2, 1], [3, 1]], overwrite=True))
    assert tc.read_singularities(os.path.join(folder, "fat.sing")) == {2: 1, 3: 1}
    assert not [name for name in os.listdir(folder) if name.startswith(".")]


# ---- malformed bodies, framings and methods: a reply, never a dropped connection (issue 36) ----------------------


POSTS = ["/api/solve", "/api/place", "/api/streamlines", "/api/save", "/api/load", "/api/features", "/api/quads"]


@pytest.mark.parametrize("body, part", [
    (b"[" * 100000 + b"]" * 100000, b"nested too deeply"),  # RecursionError in the parser
    (b"[" * 900 + b"]" * 900, b"JSON object"),  # parsed, but no object (and not repr'd whole)
    (b'{"n": 1' + b"0" * 5000 + b"}", b"5001 digits"),  # past Python's integer-digit limit (a ValueError)
    (b'{"n": 1' + b"0" * 1000 + b"}", b"1001 digits"),
    (b'{"singularities": [[0, -' + b"9" * 4400 + b"], [1, 1]]}", b"4400 digits"),
    (b'{"n": NaN}', b"NaN"),
    (b'{"constraints": [[2, [Infinity, 0, 0]]]}', b"Infinity"),
    (b'{"constraints": [[2, [-Infinity, 0, 0]]]}', b"-Infinity"),
    (b'\xff\xfe{\x00}\x00', b"not UTF-8"),
    (b'{"path": "\xe9.sing"}', b"not UTF-8"),
    (b'\xef\xbb\xbf{}', b"malformed JSON"),  # a byte order mark
    (b"5", b"JSON object"), (b"[]", b"JSON object"), (b'"{}"', b"JSON object"), (b"null", b"JSON object"),
    (b"true", b"JSON object"), (b"{", b"malformed JSON"), (b"{}{}", b"malformed JSON"),
], ids=["deep", "deep-900", "digits-5001", "digits-1001", "digits-4400", "NaN", "Infinity", "-Infinity", "utf-16",
        "latin-1", "bom", "number", "array", "string", "null", "true", "unclosed", "two-objects"])
@pytest.mark.parametrize("endpoint", POSTS)
def test_malformed_bodies_get_a_400_line(server, capfd, endpoint, body, part):
    port, folder = server
    before = tree(str(folder))
    status, data = request(port, "POST", endpoint, body)
    assert status == 400 and one_line(data) and part in data, (status, data[:200])
    assert solve(port, [[0, 1], [1, 1]])[0] == 200
    assert tree(str(folder)) == before
    assert "Traceback" not in capfd.readouterr().err


@pytest.mark.parametrize("endpoint, body, status, part", [
    ("/api/save", {"kind": ["singularities"], "path": "x.sing"}, 400, b"kind must be"),
    ("/api/save", {"kind": {"field": 1}, "path": "x.txt"}, 400, b"kind must be"),
    ("/api/load", {"kind": ["singularities"], "path": "x.sing"}, 400, b"kind must be"),
    ("/api/solve", {"singularities": [[True, 1], [0, 1]]}, 400, b"a singularity must be"),
    ("/api/solve", {"singularities": [[0, True], [1, 1]]}, 400, b"a singularity must be"),
    ("/api/solve", {"singularities": [[0, 1.0], [1, 1]]}, 400, b"a singularity must be"),
    ("/api/solve", {"singularities": [[0, [1]]]}, 400, b"a singularity must be"),
    ("/api/solve", {"singularities": [[0, "x/y"], [1, 1]]}, 422, b""),
    ("/api/solve", {"singularities": [[10**100, 1], [1, 1]]}, 422, b""),
    ("/api/streamlines", {"seeds": 1.5}, 400, b"seeds must be"),
    ("/api/features", {"threshold": "30"}, 400, b"threshold must be a number"),
    ("/api/features", {"threshold": True}, 400, b"threshold must be a number"),
    ("/api/features", {"threshold": [30]}, 400, b"threshold must be a number"),
    ("/api/features", {"threshold": -1}, 422, b"invalid_argument:"),
    ("/api/features", {"threshold": 180.5}, 422, b"invalid_argument:"),
    ("/api/features", {"threshold": 10**400}, 422, b"invalid_argument:"),  # too large for a float
    ("/api/features", {"align_boundary": 1}, 400, b"align_boundary must be"),
    ("/api/place", {"constraints": [[99, [1, 0, 0]]]}, 422, b"invalid_constraint:"),
    ("/api/quads", {"quad_size": "1"}, 400, b"quad_size must be a number"),
    ("/api/quads", {"quad_size": [1]}, 400, b"quad_size must be a number"),
    ("/api/quads", {"quad_size": True}, 400, b"quad_size must be a number"),
    ("/api/quads", {"target_faces": 1.5}, 400, b"target_faces must be an integer"),
    ("/api/quads", {"target_faces": 0}, 400, b"target_faces must be an integer"),
    ("/api/quads", {"quad_size": 1, "target_faces": 8}, 400, b"not both"),
    ("/api/quads", {"singularities": [[0, 1], [1, 1]], "quad_size": 0}, 422, b"invalid_argument:"),
    ("/api/quads", {"singularities": [[0, 1], [1, 1]], "quad_size": -1}, 422, b"invalid_argument:"),
    ("/api/quads", {"singularities": [[0, 1], [1, 1]], "quad_size": 10**400}, 422, b"invalid_argument:"),
    # far more than MAX_QUADS quads
    ("/api/quads", {"singularities": [[0, 1], [1, 1]], "quad_size": 1e-9}, 422, b"invalid_argument:"),
    ("/api/quads", {"n": 6}, 422, b"invalid_symmetry_order:"),
    ("/api/quads", {"feature_threshold": "30"}, 400, b"feature_threshold must be a number"),
    ("/api/quads", {"singularities": [[0, 1], [1, 1]], "feature_threshold": 200}, 422, b"invalid_argument:"),
    ("/api/quads", {"scale_smoothness": "0.1"}, 400, b"scale_smoothness must be a number"),
    ("/api/quads", {"scale_smoothness": None}, 400, b"scale_smoothness must be a number"),
    ("/api/quads", {"singularities": [[0, 1], [1, 1]], "scale_smoothness": -1}, 422, b"quad_scale_smoothness must"),
    ("/api/quads", {"singularities": [[0, 1], [1, 1]], "scale_smoothness": 10**400}, 422, b"quad_scale_smoothness must"),
    ("/api/save", {"kind": "singularities", "path": "x\ud800.sing"}, 400, b""),
    ("/api/load", {"kind": "singularities", "path": "x\udcff.sing"}, 404, b""),
])
def test_fields_of_the_wrong_type_get_a_4xx_line(server, capfd, endpoint, body, status, part):
    port, folder = server
    before = tree(str(folder))
    code, data = post(port, endpoint, dict({"n": 4}, **body))
    assert code == status and one_line(data) and part in data, (code, data)
    assert solve(port, [[0, 1], [1, 1]])[0] == 200
    assert tree(str(folder)) == before
    assert "Traceback" not in capfd.readouterr().err


def exchange(port, data, close=True, timeout=10):
    """sends raw bytes on a new connection (then closes its sending side, unless told not to) and returns what the
    server answers until it closes the connection"""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        s.sendall(data)
        if close:
            s.shutdown(socket.SHUT_WR)
        chunks = []
        while chunk := s.recv(65536):
            chunks.append(chunk)
    return b"".join(chunks)


def status_of(reply):
    """the status, the headers ({lower-case name: value}) and the body of one raw reply"""
    head, _, body = reply.partition(b"\r\n\r\n")
    lines = head.decode("latin-1").split("\r\n")
    headers = dict((k.strip().lower(), v.strip()) for k, v in (line.split(":", 1) for line in lines[1:]))
    return int(lines[0].split()[1]), headers, body


def post_head(path, extra):
    return (f"POST {path} HTTP/1.1\r\nHost: x\r\n" + "".join(f"{h}\r\n" for h in extra) + "\r\n").encode()


@pytest.mark.parametrize("data, code, part", [
    # chunked: not read (was answered 200/422 as a solve of {})
    (post_head("/api/solve", ["Transfer-Encoding: chunked"]) + b"2\r\n{}\r\n0\r\n\r\n", 411, b"Content-Length"),
    (post_head("/api/solve", ["Transfer-Encoding: chunked", "Content-Length: 2"]) + b"2\r\n{}\r\n0\r\n\r\n", 411,
     b"Content-Length"),
    (post_head("/api/solve", []) + b"{}", 411, b"Content-Length"),  # no Content-Length at all
    (post_head("/api/solve", ["Content-Length: abc"]) + b"{}", 400, b"Content-Length"),
    (post_head("/api/solve", ["Content-Length: -5"]) + b"{}", 400, b"Content-Length"),
    (post_head("/api/solve", ["Content-Length: 1_0"]) + b"{}", 400, b"Content-Length"),
    (post_head("/api/solve", ["Content-Length: +2"]) + b"{}", 400, b"Content-Length"),
    (post_head("/api/solve", ["Content-Length: 2", "Content-Length: 3"]) + b"{} ", 400, b"Content-Length"),
    (post_head("/api/solve", ["Content-Length: 99999999999999999999999"]), 413, b"at most"),
    # a body shorter than its Content-Length, the client done sending
    (post_head("/api/solve", ["Content-Length: 100"]) + json.dumps(OCTAHEDRON_SOLVE).encode(), 400,
     b"ended after 43 of its 100 bytes"),
    (b"GET / HTTP/1.1\r\nHost: x\r\n" + b"X-Long: " + b"a" * 70000 + b"\r\n\r\n", 431, b""),
    (b"GET /" + b"a" * 70000 + b" HTTP/1.1\r\n\r\n", 414, b""),
    (b"GET / HTTP/2.0\r\n\r\n", 505, b""),
    (b"GET\r\n\r\n", 400, b""),
], ids=["chunked", "chunked-and-length", "no-length", "length-abc", "length-negative", "length-underscore",
        "length-plus", "two-lengths", "length-huge", "short-body", "long-header", "long-url", "http-2", "no-url"])
def test_bad_framing_gets_a_reply_and_a_closed_connection(server, capfd, data, code, part):
    port, _ = server
    status, headers, body = status_of(exchange(port, data))
    assert status == code and one_line(body) and part in body, (status, body)
    assert headers["content-type"].startswith("text/plain") and int(headers["content-length"]) == len(body)
    assert solve(port, [[0, 1], [1, 1]])[0] == 200
    assert "Traceback" not in capfd.readouterr().err


def test_a_body_that_does_not_arrive_gets_408(server, monkeypatch):
    port, _ = server
    monkeypatch.setattr(serve, "BODY_TIMEOUT", 0.5)
    # 10 bytes of the 100 announced, and the connection kept open
    status, headers, body = status_of(exchange(port, post_head("/api/solve", ["Content-Length: 100"]) + b'{"n": 4, ',
                                               close=False))
    assert status == 408 and headers["connection"] == "close" and one_line(body)
    assert solve(port, [[0, 1], [1, 1]])[0] == 200


def test_other_methods_get_405_with_allow(server):
    port, _ = server
    for method in ["PUT", "DELETE", "PATCH", "OPTIONS", "TRACE"]:
        for path, allow in [("/api/solve", "POST"), ("/api/save", "POST"), ("/", "GET, HEAD"),
                            ("/api/mesh", "GET, HEAD")]:
            c = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
            c.request(method, path, body=b"{}")
            r = c.getresponse()
            data = r.read()
            assert r.status == 405 and r.getheader("Allow") == allow and one_line(data), (method, path, data)
            c.close()
        assert request(port, method, "/nowhere", b"{}")[0] == 404
    status, data = request(port, "FROB", "/api/solve", b"{}")  # a method nobody knows
    assert status == 501 and one_line(data)
    # the wrong one of GET and POST, on one connection that stays usable (the body was read)
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    for method, path, body, allow in [("GET", "/api/solve", None, "POST"), ("POST", "/", b"{}", "GET, HEAD"),
                                      ("POST", "/api/mesh", b"{}", "GET, HEAD")]:
        c.request(method, path, body=body)
        r = c.getresponse()
        assert r.status == 405 and r.getheader("Allow") == allow and one_line(r.read())
    c.request("POST", "/api/solve", json.dumps(OCTAHEDRON_SOLVE))
    assert c.getresponse().status == 200
    c.close()


def test_head_gives_the_headers_of_the_get(server):
    """HEAD on the page and the mesh: the GET's status and Content-Length, no body (the next reply on the same
    connection is whole)"""
    port, _ = server
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    for path in ["/", "/api/mesh", "/nowhere"]:
        c.request("GET", path)
        r = c.getresponse()
        body = r.read()
        c.request("HEAD", path)
        h = c.getresponse()
        assert h.read() == b"" and h.status == r.status and int(h.getheader("Content-Length")) == len(body)
        assert h.getheader("Content-Type") == r.getheader("Content-Type")
    c.request("GET", "/api/mesh")
    assert parse(c.getresponse().read())[0]["faces"] == 8
    c.close()
    with socket.create_connection(("127.0.0.1", port), timeout=10) as s:  # no body bytes at all
        s.sendall(b"HEAD / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")
        reply = b""
        while chunk := s.recv(65536):
            reply += chunk
    assert reply.endswith(b"\r\n\r\n") and reply.count(b"\r\n\r\n") == 1


def test_a_missing_bundle_is_a_404_line(server, capfd):
    port, _ = server  # its bundle folder has no editor.js
    status, data = request(port, "GET", "/editor.js")
    assert status == 404 and one_line(data) and b"trivial_connections_editor" in data
    assert request(port, "GET", "/")[0] == 200
    assert "Traceback" not in capfd.readouterr().err


def test_the_docstring_states_the_limits_of_the_code():
    """every limit the server's docstring (and so --help) states is written into it from its constant"""
    with open(serve.__file__) as f:
        raw = ast.get_docstring(ast.parse(f.read()), clean=False)
    named = set(re.findall(r"\{([A-Z][A-Z_]*)\}", raw)) - {"SOLVE"}  # {SOLVE}: the API's notation
    assert named == set(serve.DOCUMENTED)
    doc = serve.__doc__
    assert not any("{" + name + "}" in doc for name in named)
    assert f"(1 to {serve.MAX_SEEDS}, default\n" in doc and f"min(faces, {serve.DEFAULT_SEEDS})" in doc
    assert f"SOLVE: n (1 to {serve.MAX_N}," in doc and f"more than {serve.MAX_DIGITS} digits" in doc
    assert f"413 above {serve.MAX_LOAD >> 20} MB" in doc and f"at most {serve.RAY_STEPS} faces" in doc
    assert f"({serve.MAX_BODY >> 20} MB plus {serve.BODY_PER_FACE} bytes per face" in doc
    assert f"{serve.BODY_TIMEOUT} seconds" in doc and f"default {tc.DEFAULT_FEATURE_ANGLE:g}," in doc
    # the code keeps to them
    session = serve.Session.__new__(serve.Session)
    session.n, session.F = 4, np.zeros((10, 3), int)
    assert session.symmetry_order({"n": serve.MAX_N}) == serve.MAX_N
    with pytest.raises(ValueError, match=f"from 1 to {serve.MAX_N}"):
        session.symmetry_order({"n": serve.MAX_N + 1})
    with pytest.raises(ValueError, match=f"from 1 to {serve.MAX_SEEDS}"):
        session.seed_count({"seeds": serve.MAX_SEEDS + 1})
    assert session.seed_count({}) == min(10, serve.DEFAULT_SEEDS)


def test_the_bundle_and_its_source_map_are_served_by_name_only(tmp_path, capfd):
    """GET /editor.js.map: the source map esbuild writes beside editor.js (--sourcemap), from the bundle folder,
    as application/json; no other file of that folder, nor a path built from the URL"""
    bundle, files = tmp_path / "bundle", tmp_path / "files"
    bundle.mkdir()
    files.mkdir()
    (bundle / "editor.js").write_text("//# sourceMappingURL=editor.js.map\n")
    source_map = json.dumps({"version": 3, "sources": ["main.js"], "mappings": ""}).encode()
    (bundle / "editor.js.map").write_bytes(source_map)
    (bundle / "secret.txt").write_text("not served\n")
    httpd = start(octahedron_file(str(files)), str(files))
    httpd.RequestHandlerClass.bundle = str(bundle)
    port = httpd.server_address[1]
    try:
        c = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
        for method in ["GET", "HEAD"]:
            c.request(method, "/editor.js.map")
            r = c.getresponse()
            body = r.read()
            assert r.status == 200 and r.getheader("Content-Type") == "application/json"
            assert int(r.getheader("Content-Length")) == len(source_map)
            assert body == (source_map if method == "GET" else b"")
        c.close()
        assert request(port, "GET", "/editor.js")[0] == 200
        for path in ["/secret.txt", "/bundle/editor.js.map", "/editor.js.map/", "/editor.js.map/../secret.txt",
                     "/../bundle/editor.js.map", "/%2e%2e/bundle/secret.txt", "/editor.js.map?x=1", "/editor.map"]:
            status, data = request(port, "GET", path)
            assert status == 404 and one_line(data), (path, status, data)
        status, data = post(port, "/editor.js.map", {})
        assert status == 405 and one_line(data)
        (bundle / "editor.js.map").unlink()  # a bundle built without it: a 404 line, the page still served
        status, data = request(port, "GET", "/editor.js.map")
        assert status == 404 and one_line(data) and b"trivial_connections_editor" in data
        assert request(port, "GET", "/")[0] == 200
    finally:
        httpd.shutdown()
    assert "Traceback" not in capfd.readouterr().err


# ---- issue 37: pins are cheap (no cap), the sharp features' pins, placement under pins --------------------------


def box_file(folder, k=5, open_top=False):
    """the unit cube, each face a k x k grid of squares split in two (the twelve edges sharp); open_top: without
    its face z = 1 (a box with a boundary loop whose top triangles beside the vertical edges touch the rim)"""
    index, V, F = {}, [], []

    def vertex(p):
        key = tuple(int(round(c * k)) for c in p)
        if key not in index:
            index[key] = len(V)
            V.append(tuple(float(c) for c in p))
        return index[key]

    for axis in range(3):
        for side in (0, 1):
            if open_top and axis == 2 and side == 1:
                continue
            u, w = (axis + 1) % 3, (axis + 2) % 3

            def point(i, j):
                p = [0.0] * 3
                p[axis], p[u], p[w] = side, i / k, j / k
                return p

            for i in range(k):
                for j in range(k):
                    a, b = vertex(point(i, j)), vertex(point(i + 1, j))
                    c, d = vertex(point(i + 1, j + 1)), vertex(point(i, j + 1))
                    two = [(a, b, c), (a, c, d)] if (i + j) % 2 == 0 else [(a, b, d), (b, c, d)]
                    F += [(x, z, y) for x, y, z in two] if side == 0 else two
    return off_file(os.path.join(folder, "open_box.off" if open_top else "box.off"), V, F)


@pytest.fixture(scope="module")
def box(tmp_path_factory):
    folder = tmp_path_factory.mktemp("box")
    httpd = start(box_file(str(folder)), str(folder))
    yield httpd.server_address[1], folder
    httpd.shutdown()


def corners_of(V):
    return [i for i, p in enumerate(V) if np.all(np.abs(p - np.round(p)) < 1e-9)]


def test_features_are_the_modules_pins_and_the_field_follows_them(box):
    port, _ = box
    V, F = mesh_of(port)
    header, _ = answer(port, "/api/features", {"n": 4})
    faces, directions, report = tc.feature_aligned_faces(V, F)  # the same mesh (the frame's V is float32-exact)
    assert header["threshold"] == 30 and header["report"]["number_of_curves"] == 12 == report["number_of_curves"]
    assert [f for f, _ in header["constraints"]] == faces.tolist() and header["on_aligned_boundary"] == 0
    pins = header["constraints"]
    assert np.allclose([d for _, d in pins], directions, atol=1e-7)
    # the placement under those pins: the eight corners at +1/4, and a field that follows every pin
    placed, _ = answer(port, "/api/place", {"n": 4, "constraints": pins})
    singularities = placed["singularities"]
    assert sorted(v for v, _ in singularities) == corners_of(V) and all(k == "1/4" for _, k in singularities)
    h, arrays = answer(port, "/api/solve", {"n": 4, "singularities": singularities, "constraints": pins})
    assert h["energy"] < 1e-9
    for f, d in pins:
        assert abs(turn_to(unit(arrays["field"][f].astype(float)), unit(np.array(d)), face_normal(V, F, f), 4)) < 2e-6
    assert all(c["decided"] for c in h["constraints"])
    # a higher threshold than the cube's 90 degrees: no pin, not an error
    header, _ = answer(port, "/api/features", {"threshold": 95})
    assert header["constraints"] == [] and header["report"]["number_of_sharp_edges"] == 0
    # the placement without pins after a solve with them: the solver's pins are dropped, not an error
    answer(port, "/api/place", {"n": 4})


def test_features_with_boundary_alignment_leave_the_boundary_faces(tmp_path):
    httpd = start(box_file(str(tmp_path), k=5, open_top=True), str(tmp_path))
    try:
        port = httpd.server_address[1]
        V, F = mesh_of(port)
        everything, _ = answer(port, "/api/features", {})
        aligned, _ = answer(port, "/api/features", {"align_boundary": True})
        assert aligned["on_aligned_boundary"] == 4
        assert len(aligned["constraints"]) == len(everything["constraints"]) - 4
        # the aligned solve takes the pins left (the boundary faces' pins would be refused)
        placed, _ = answer(port, "/api/place", {"n": 4, "align_boundary": True, "constraints": aligned["constraints"]})
        h, arrays = answer(port, "/api/solve", {"n": 4, "align_boundary": True, "singularities": placed["singularities"],
                                                "constraints": aligned["constraints"]})
        for f, d in aligned["constraints"]:
            assert abs(turn_to(unit(arrays["field"][f].astype(float)), unit(np.array(d)), face_normal(V, F, f), 4)) < 2e-6
        status, data = post(port, "/api/solve", {"n": 4, "align_boundary": True, "singularities": placed["singularities"],
                                                 "constraints": everything["constraints"]})
        assert status == 422 and data.startswith(b"invalid_constraint:")
    finally:
        httpd.shutdown()


def test_thousands_of_pins_in_one_request(tmp_path):
    """more pins than the old cap of 2,000: every face of a 20,000-face disk pinned (a body over 1 MB, within the
    mesh's max_body), solved in a few seconds at most"""
    httpd = start(disk_file(str(tmp_path), n=100), str(tmp_path))
    try:
        port = httpd.server_address[1]
        V, F = mesh_of(port)
        assert len(F) == 20000
        rng = np.random.default_rng(3)
        pins = [[f, d] for f, d in enumerate(rng.normal(size=(len(F), 3)).tolist())]
        body = json.dumps({"n": 4, "singularities": [], "constraints": pins}).encode()
        assert 1 << 20 < len(body) < httpd.RequestHandlerClass.session.max_body
        status, data = request(port, "POST", "/api/solve", body)
        assert status == 200, data[:200]
        header, arrays = parse(data)
        assert header["max_residual"] < 1e-9
        field = field_of(port, arrays["angle"])
        for f in rng.choice(len(F), 50, replace=False):
            N = face_normal(V, F, f)
            d = np.array(pins[f][1])
            assert abs(turn_to(unit(field[f].astype(float)), unit(d - (d @ N) * N), N, 4)) < 1e-5  # float32 V
        # and saved and loaded back whole
        answer(port, "/api/save", {"kind": "constraints", "path": "all.dirs", "n": 4, "constraints": pins})
        loaded, _ = answer(port, "/api/load", {"kind": "constraints", "path": "all.dirs"})
        assert len(loaded["constraints"]) == len(F)
    finally:
        httpd.shutdown()


# ---- issue 43: the quad mesh of the request's cross field ----------------------------------------------------------


def quad_valences(points, quads):
    """per point: the number of other points it shares a quad edge with; and the edges in one quad only"""
    directed = {(int(q[j]), int(q[(j + 1) % 4])) for q in quads for j in range(4)}
    neighbours = [set() for _ in range(len(points))]
    for a, b in directed:
        neighbours[a].add(b)
        neighbours[b].add(a)
    return [len(n) for n in neighbours], [(a, b) for a, b in directed if (b, a) not in directed]


def test_quads_of_the_cube_are_its_squares(box):
    # the cube of 5 x 5 squares per face, the field along the sharp edges (the features' pins), its corners +1/4:
    # with H = 1/k, 6 k^2 quads, closed, valence 3 at the 8 corners and 4 elsewhere, on the cube; target_faces 54
    # gives H = sqrt(6 / 54) = 1/3; no size: H = 4 mean edge lengths (from the mesh's own edges)
    port, folder = box
    V, F = mesh_of(port)
    before = tree(str(folder))
    pins, _ = answer(port, "/api/features", {"n": 4})
    body = {"n": 4, "singularities": [[v, "1/4"] for v in corners_of(V)], "constraints": pins["constraints"]}
    # scale_smoothness: the cube's field is a gradient already (flat faces, unit length), so scaled its quads stay
    for k, size in [(5, {"quad_size": 0.2}), (3, {"target_faces": 54}), (1, {"quad_size": 1}),
                    (5, {"quad_size": 0.2, "scale_smoothness": 0.1})]:
        header, arrays = answer(port, "/api/quads", dict(body, **size))
        points, quads, report = arrays["points"], arrays["quads"], header["report"]
        assert quads.shape == (6 * k * k, 4) and report["quads"] == len(quads) and report["vertices"] == len(points)
        assert abs(report["quad_size"] - 1 / k) < 1e-9 and header["n"] == 4
        valence, border = quad_valences(points, quads)
        assert border == [] and sorted(valence) == [3] * 8 + [4] * (len(points) - 8)
        assert len(points) - len(quads) * 2 + len(quads) == 2  # V - E + F, E = 4 q / 2
        assert np.all(np.min(np.minimum(np.abs(points), np.abs(points - 1)), axis=1) < 1e-6)  # on the cube
        assert report["valence_errors"] == 0 and report["folded_triangles"] == 0 and report["flipped_quads"] == 0
    edges = np.unique(np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1), axis=0)
    mean = np.linalg.norm(V[edges[:, 0]].astype(float) - V[edges[:, 1]], axis=1).mean()
    header, arrays = answer(port, "/api/quads", body)
    assert abs(header["report"]["quad_size"] - serve.QUAD_SIZE_EDGES * mean) < 1e-6 * mean
    mesh_header, _ = parse(request(port, "GET", "/api/mesh")[1])  # the page's default: the same size
    assert mesh_header["quad_size"] == header["report"]["quad_size"]
    assert header["report"]["quads"] == len(arrays["quads"]) > 0
    assert tree(str(folder)) == before  # nothing written


def test_quads_follow_the_sharp_edges_with_a_feature_threshold(box):
    # the cube of 5 x 5 squares per face with H = 0.4 (the side is not a multiple of H: no iso-line runs along the
    # cube's edges by itself): with feature_threshold every edge of the cube is a chain of quad edges and the
    # report counts its 60 mesh edges; a threshold over the cube's 90 degrees puts none on iso-lines
    port, _ = box
    V, F = mesh_of(port)
    pins, _ = answer(port, "/api/features", {"n": 4})
    body = {"n": 4, "singularities": [[v, "1/4"] for v in corners_of(V)], "constraints": pins["constraints"],
            "quad_size": 0.4}
    header, arrays = answer(port, "/api/quads", dict(body, feature_threshold=30))
    points, quads, report = arrays["points"], arrays["quads"], header["report"]
    assert report["feature_edges"] == 60 and report["valence_errors"] == 0 and report["folded_triangles"] == 0
    edges = {tuple(sorted((int(q[j]), int(q[(j + 1) % 4])))) for q in quads for j in range(4)}
    for axis in range(3):
        others = [a for a in range(3) if a != axis]
        for c in [(0, 0), (0, 1), (1, 0), (1, 1)]:
            on = lambda v: all(abs(points[v][others[t]] - c[t]) < 1e-6 for t in range(2))
            along = sum(abs(points[a][axis] - points[b][axis]) for a, b in edges if on(a) and on(b))
            assert abs(along - 1) < 1e-5, (axis, c, along)  # the whole edge of the cube
    header, _ = answer(port, "/api/quads", dict(body, feature_threshold=95))
    assert header["report"]["feature_edges"] == 0


def test_quads_with_the_singularities_moved_off_the_sharp_edges(box):
    # the cube of 5 x 5 squares per face, its corners +1/4 (on the sharp edges: they stay) and a +1/4 / -1/4 pair on
    # its top face one square from an edge: with H = 0.4 both move to vertices at least H from every sharp edge,
    # the quads are those of the moved set, and the request's own singularities are not changed
    port, folder = box
    V, F = mesh_of(port)
    before = tree(str(folder))
    pins, _ = answer(port, "/api/features", {"n": 4})
    at = lambda p: int(np.argmin(np.linalg.norm(V - np.array(p), axis=1)))
    plus, minus = at([0.2, 0.4, 1]), at([0.2, 0.6, 1])
    corners = [[v, "1/4"] for v in corners_of(V)]
    body = {"n": 4, "singularities": corners + [[plus, "1/4"], [minus, "-1/4"]], "constraints": pins["constraints"],
            "quad_size": 0.4, "feature_threshold": 30}
    header, arrays = answer(port, "/api/quads", dict(body, move_off_features=True))
    moved = header["moved_off_features"]
    assert sorted(m["from"] for m in moved["moves"]) == sorted([plus, minus]), moved
    assert abs(moved["quad_size"] - 0.4) < 1e-12
    for m in moved["moves"]:
        assert m["distance_before"] < 0.4 <= m["distance_after"] + 1e-9, m
        assert min(np.min(np.abs(V[m["to"]])), np.min(np.abs(V[m["to"]] - 1)[:2])) >= 0.4 - 1e-6  # off every edge (V: float32)
    ends = {m["from"]: m["to"] for m in moved["moves"]}
    assert sorted(map(tuple, moved["singularities"])) == sorted(
        [tuple(c) for c in corners] + [(ends[plus], "1/4"), (ends[minus], "-1/4")])
    assert header["report"]["quads"] == len(arrays["quads"]) > 0 and header["report"]["feature_edges"] == 60
    # the quads' field is that of the moved set: its energy is the plain solve's of those singularities
    solved, _ = answer(port, "/api/solve", dict(body, singularities=moved["singularities"]))
    assert abs(solved["energy"] - header["energy"]) <= 1e-9 * (1 + solved["energy"])
    unmoved, _ = answer(port, "/api/quads", body)  # not asked: nothing moved, no such header
    assert "moved_off_features" not in unmoved and unmoved["energy"] != header["energy"]
    for bad, part in [({"move_off_features": "yes"}, b"move_off_features must be true or false"),
                      ({"move_off_features": 1}, b"move_off_features must be true or false"),
                      ({"move_off_features": True, "feature_threshold": None}, b"needs feature_threshold")]:
        request_body = dict(body, **bad)
        if request_body.get("feature_threshold", 0) is None:
            del request_body["feature_threshold"]
        status, data = post(port, "/api/quads", request_body)
        assert status == 400 and part in data, (bad, status, data)
    assert tree(str(folder)) == before  # nothing written


def test_quads_on_a_bordered_mesh_need_the_field_along_the_boundary(disk):
    port, mesh, folder, _ = disk
    with open(mesh, "rb") as f:
        original = f.read()
    before = tree(str(folder))
    # a pin at 45 degrees to the square's sides (no singularity: the field turns with it): not along the boundary
    status, data = post(port, "/api/quads", {"n": 4, "quad_size": 0.5, "constraints": [[40, [1, 1, 0]]]})
    assert status == 422 and one_line(data) and b"border" in data, data
    header, arrays = answer(port, "/api/quads", {"n": 4, "quad_size": 0.5, "align_boundary": True})
    points, quads, report = arrays["points"], arrays["quads"], header["report"]
    assert report["quads"] == len(quads) > 0 and quads.max() < len(points)
    _, border = quad_valences(points, quads)
    # the quads end on the boundary: edges in one quad, on the square's sides, which are not open edges (holes)
    assert len(border) > 0 and report["open_edges"] == 0
    on_side = lambda p: np.isclose(np.abs(p[:2]), 1, atol=1e-6).any()
    assert all(on_side(points[a]) and on_side(points[b]) for a, b in border)
    assert solve(port, [])[0] == 200  # the session keeps working
    with open(mesh, "rb") as f:
        assert f.read() == original
    assert tree(str(folder)) == before
