#!/usr/bin/python3
"""The field editor's server (issue 22, work in progress): one mesh, its prefactored solver, a page.

    PYTHONPATH=build/python python3 editor/serve.py MESH [--n N] [--port P] [--bundle DIR]

Binds 127.0.0.1 only. Serves its page (editor/web/index.html and the bundle the build made, DIR/editor.js) and
the mesh it was given; every edit the page sends is a solve on the solver factored once at start. Arrays travel
as binary (see `frame`), never as JSON numbers.
"""
import argparse
import http.server
import json
import os
import struct
import sys
import threading

import numpy as np
import trivial_connections as tc

MAX_BODY = 1 << 20  # bytes of a request body
HERE = os.path.dirname(os.path.abspath(__file__))


def frame(header, arrays):
    """b"TCB1", the JSON header's length (uint32, little endian), the header, then each array (little endian, each
    at a multiple of 8 bytes); the header lists them: {"arrays": [{"name", "dtype", "shape", "offset"}]}"""
    entries, blobs, offset = [], [], 0
    for name, a in arrays:
        a = np.ascontiguousarray(a)
        entries.append({"name": name, "dtype": a.dtype.str, "shape": list(a.shape), "offset": offset})
        raw = a.tobytes()
        raw += b"\0" * (-len(raw) % 8)
        blobs.append(raw)
        offset += len(raw)
    head = json.dumps(dict(header, arrays=entries)).encode()
    head += b" " * (-(8 + len(head)) % 8)
    return b"TCB1" + struct.pack("<I", len(head)) + head + b"".join(blobs)


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
    edges = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    edges = np.unique(edges, axis=0)
    chi = np.zeros(len(labels), int)
    np.add.at(chi, component[used], 1)
    np.add.at(chi, component[edges[:, 0]], -1)
    np.add.at(chi, component[F[:, 0]], 1)
    return component, chi


class Session:
    def __init__(self, path, n):
        self.solver = tc.Solver.from_file(path)
        self.V, self.F = self.solver.vertices, self.solver.faces
        self.n = n
        self.component, self.chi = components_of(self.V, self.F)
        self.closed = [True] * len(self.chi)
        for loop in self.solver.loops:
            if loop["kind"] == "boundary":
                self.closed[loop["component"]] = False
        self.initial, _ = self.solver.place_singularities(n=n)

    def symmetry_order(self, request):
        """n of a request (a JSON object), checked"""
        if not isinstance(request, dict):
            raise ValueError("the body must be a JSON object")
        n = request.get("n", self.n)
        if not isinstance(n, int) or isinstance(n, bool) or not 1 <= n <= 64:
            raise ValueError(f"n must be an integer from 1 to 64, got {n!r}")
        return n

    def place_frame(self, request):
        n = self.symmetry_order(request)
        placed, _ = self.solver.place_singularities(n=n)
        return frame({"n": n, "singularities": [[int(v), str(k)] for v, k in sorted(placed.items())]}, [])

    def mesh_frame(self):
        header = {"vertices": len(self.V), "faces": len(self.F), "n": self.n, "chi": self.chi.tolist(),
                  "closed": self.closed,
                  "singularities": [[int(v), str(k)] for v, k in sorted(self.initial.items())]}
        edges = np.sort(np.concatenate([self.F[:, [0, 1]], self.F[:, [1, 2]], self.F[:, [2, 0]]]), axis=1)
        unique, count = np.unique(edges, axis=0, return_counts=True)
        return frame(header, [("V", self.V.astype("<f4")), ("F", self.F.astype("<u4")),
                              ("component", self.component.astype("<i4")),
                              ("boundary", unique[count == 1].astype("<u4"))])

    def solve_frame(self, request):
        n = self.symmetry_order(request)
        singularities = {}
        for item in request.get("singularities", []):
            if not (isinstance(item, list) and len(item) == 2 and isinstance(item[0], int)
                    and isinstance(item[1], (int, str))):
                raise ValueError(f"a singularity must be [vertex, index], got {item!r}")
            singularities[item[0]] = str(item[1])
        result = self.solver.solve(singularities, n=n)
        header = {"n": n, "energy": result.energy, "max_residual": result.max_residual,
                  "timings": result.timings}
        # one direction per face: the page turns it by 2 pi / n about the face's normal for the others
        return frame(header, [("field", result.field.astype("<f4"))])


class Handler(http.server.BaseHTTPRequestHandler):
    session = None
    bundle = None
    protocol_version = "HTTP/1.1"

    def log_message(self, *args):
        pass

    def reply(self, code, body, kind):
        self.send_response(code)
        self.send_header("Content-Type", kind)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.end_headers()
        self.wfile.write(body)

    def refuse(self, code, reason):
        """a 4xx with a one-line reason"""
        self.reply(code, (" ".join(reason.split()) + "\n").encode(), "text/plain; charset=utf-8")

    def do_GET(self):
        files = {"/": (os.path.join(HERE, "web", "index.html"), "text/html; charset=utf-8"),
                 "/editor.js": (os.path.join(self.bundle, "editor.js"), "text/javascript")}
        if self.path == "/api/mesh":
            return self.reply(200, self.session.mesh_frame(), "application/octet-stream")
        if self.path not in files:
            return self.refuse(404, f"not found: {self.path}")
        path, kind = files[self.path]
        with open(path, "rb") as f:
            self.reply(200, f.read(), kind)

    def do_POST(self):
        try:
            length = int(self.headers.get("Content-Length", "0") or 0)
        except ValueError:
            length = -1
        if length < 0 or length > MAX_BODY:
            self.close_connection = True  # the body is not read: nothing more can be on this connection
            return self.refuse(413 if length > 0 else 400,
                               f"request body of {length} bytes (at most {MAX_BODY})" if length > 0
                               else "bad Content-Length")
        try:
            request = json.loads(self.rfile.read(length) or b"{}")
        except (json.JSONDecodeError, UnicodeDecodeError) as e:
            return self.refuse(400, f"malformed JSON: {e}")
        try:
            if self.path == "/api/solve":
                return self.reply(200, self.session.solve_frame(request), "application/octet-stream")
            if self.path == "/api/place":
                return self.reply(200, self.session.place_frame(request), "application/octet-stream")
        except tc.InvalidInput as e:
            return self.refuse(422, f"{e.code}: {e}".replace("\n", " "))
        except (TypeError, ValueError, KeyError) as e:
            return self.refuse(400, f"bad request: {e}".replace("\n", " "))
        return self.refuse(404, f"not found: {self.path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh")
    ap.add_argument("--n", type=int, default=4)
    ap.add_argument("--port", type=int, default=8000)
    ap.add_argument("--bundle", default=os.path.join(HERE, "..", "build", "editor"))
    a = ap.parse_args()
    Handler.session = Session(a.mesh, a.n)
    Handler.bundle = a.bundle
    server = http.server.ThreadingHTTPServer(("127.0.0.1", a.port), Handler)
    print(f"http://127.0.0.1:{server.server_address[1]}/", flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    sys.exit(main())
