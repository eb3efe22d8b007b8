"""The field editor's server on bad requests (issue 22): a 4xx with a one-line reason, the session keeps
working, nothing written. Runs editor/serve.py in this process on a generated mesh (PYTHONPATH: the module)."""
import http.client
import importlib.util
import json
import os
import threading

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("serve", os.path.join(HERE, "..", "..", "editor", "serve.py"))
serve = importlib.util.module_from_spec(spec)
spec.loader.exec_module(serve)


def octahedron_file(folder):
    V = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    F = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    path = os.path.join(folder, "octahedron.off")
    with open(path, "w") as f:
        f.write(f"OFF\n{len(V)} {len(F)} 0\n")
        f.writelines(f"{x} {y} {z}\n" for x, y, z in V)
        f.writelines(f"3 {a} {b} {c}\n" for a, b, c in F)
    return path


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    folder = tmp_path_factory.mktemp("editor")
    serve.Handler.session = serve.Session(octahedron_file(str(folder)), 4)
    serve.Handler.bundle = str(folder)
    httpd = serve.http.server.ThreadingHTTPServer(("127.0.0.1", 0), serve.Handler)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield httpd.server_address[1], folder
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
    [field] = header["arrays"]
    assert field["name"] == "field" and field["shape"] == [8, 3] and header["max_residual"] < 1e-9


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
    status, data = request(port, "POST", "/api/solve", b"{}", {"Content-Length": str(serve.MAX_BODY + 1)})
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
