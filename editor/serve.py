#!/usr/bin/python3
"""The field editor's server: one mesh, its prefactored solver, a page.

    PYTHONPATH=build/python python3 editor/serve.py MESH [--n N] [--port P] [--bundle DIR] [--folder DIR]

Binds 127.0.0.1 only. Serves its page (editor/web/index.html and the bundle the build made, DIR/editor.js with
its source map DIR/editor.js.map: these three files by name, never a path taken from the URL) and the mesh it was
given; every edit the page sends is a solve on the solver factored once at start. Arrays travel
as binary (see `frame`), never as JSON numbers. The only files it reads or writes for the page are in --folder
(default: the current directory at start).

API. Requests are JSON objects (UTF-8, sent with a Content-Length); replies are frames (`frame`: a JSON header,
then arrays), or, when refused, a text/plain line giving the reason: 400 malformed request (not JSON, not an object,
nested too deeply, an integer of more than {MAX_DIGITS} digits, NaN or Infinity, a field of the wrong type, a bad
Content-Length or a body shorter than it), 403 a path outside the folder or the mesh itself, 404 unknown URL or
missing file, 405 a method the URL does not take (with an Allow header), 408 the body did not arrive within
{BODY_TIMEOUT} seconds, 409 saving over an existing file without "overwrite": true, 411 a POST without Content-Length
(a chunked body is not read), 413 a body longer than max_body (see Size below), 422 refused by the library
("code: message", e.g. "poincare_hopf_violated: ..."). GET and HEAD (the headers of the GET) on the page, its
bundle and the mesh, POST on the rest.
  GET  /api/mesh         header {vertices, faces, n, chi, closed (per component), singularities (placed at start),
                         quad_size (the quad mesh's default: {QUAD_SIZE_EDGES} mean edge lengths)};
                         arrays V <f4 (V, 3), F <u4 (F, 3), component <i4 (V,) (-1: no face), boundary <u4 (b, 2)
                         (boundary edges), angle_defect <f4 (V,) (2 pi minus the corner angles at the vertex)
  POST /api/place        {n?, align_boundary?, constraints?}: automatic placement -> header {n, singularities}: the
                         singularities of the smoothest n-direction field that follows the constrained faces'
                         directions (and the boundary, with align_boundary), as the module's place_singularities()
  POST /api/features     {threshold?, n?, align_boundary?}: the pins of the sharp features (the module's
                         feature_aligned_faces(): the faces beside the feature curves whose normals differ by more than
                         `threshold` degrees, default {DEFAULT_FEATURE_ANGLE}, each pinned to the curve's direction)
                         -> header {threshold, constraints: [[f, [x, y, z]]] (increasing f; with align_boundary,
                         none on the boundary: the field follows the boundary there), on_aligned_boundary (the
                         faces left out for it), report (the module's dict: number_of_sharp_edges, number_of_curves,
                         disagreeing_pairs, ...)}. A threshold that is not a number is a 400, one outside [0, 180]
                         a 422 (invalid_argument). The page adds them where the user has no pin of their own (the
                         user's pins win)
  POST /api/solve        {SOLVE} -> header {n, energy, max_residual, timings, constraints}; array angle <f4 (F,):
                         one direction per face, as its angle counter-clockwise from the face's first edge (F[f, 0]
                         to F[f, 1]) about its normal (the page turns it by 2 pi / n for the others). constraints: the
                         solve's report on the paths joining the request's constrained faces (to each other or to
                         the aligned boundary): [{component, from_face, to_face, length, period, residual,
                         decided (True: a link between touching pins, its integer by rounding)}]
  POST /api/streamlines  {SOLVE, seeds?} -> header {n, energy, lines, seeds, maximum_faces_per_ray, timings};
                         arrays points <f4 (k, 3), offsets <u4 (lines + 1,): line i is points[offsets[i]:offsets[i+1]].
                         seeds: the number of seed faces asked for (1 to {MAX_SEEDS}, default
                         min(faces, {DEFAULT_SEEDS})), spread over the mesh the same way every time; header seeds:
                         the number used. The rays are cut (to maximum_faces_per_ray faces, at least 8), then seeds
                         left out, so that all of them cross at most {RAY_STEPS} faces: about half a second at most
                         on 100k faces
  POST /api/quads        {SOLVE, quad_size? | target_faces?, feature_threshold?, scale_smoothness?,
                         move_off_features?} -> header {n, energy, report, timings, moved_off_features?}; arrays
                         points <f4 (k, 3), quads <u4 (q, 4) (vertex numbers into points, counter-clockwise): the
                         quad mesh of the request's cross field (the module's
                         Solver.quad_mesh()), n = 4 only (422 invalid_symmetry_order otherwise). quad_size H (a
                         number; not positive or finite: 422 invalid_argument) or target_faces (an integer from 1
                         to {MAX_QUADS}), not both; neither: H = {QUAD_SIZE_EDGES} mean edge lengths. More than about
                         {MAX_QUADS} quads is a 422 invalid_argument (H too small). report: the module's dict (quads,
                         valence_errors, folded_triangles, border_corners, feature_edges, hausdorff_distance, ...).
                         On a mesh with boundary the field must follow it (align_boundary: true; otherwise a 422
                         that says so). feature_threshold (degrees): the sharp edges of the module's
                         feature_curves() at that angle go on iso-lines, so that quad edges follow them (the field
                         must follow them, as the features' pins make it; otherwise a 422 that names the edge).
                         scale_smoothness S (a number, default 0): the field's length first scaled per face towards a
                         gradient (the program's --quad-scale-smoothness; negative: 422 invalid_argument).
                         move_off_features (true or false, default false; needs feature_threshold): the
                         singularities closer than H to a sharp edge, but not on one, moved to the nearest vertex at
                         least H from every sharp edge, the field solved again with them, then the quads (the
                         module's move_singularities_off_features(), as the program does with --auto
                         --align-features); the request's singularities are not changed: moved_off_features is the
                         module's report (moves, stuck, on_features, quad_size) and the quads' singularities
  POST /api/save         {kind, path, overwrite?, SOLVE, seeds?}: solves, then writes (completely or not at all)
                         `path` in the folder -> header {saved: the path relative to the folder, bytes}. kind:
                         "singularities", "constraints" (lines "f x y z"), "field" (the program's field file, path
                         ending in .txt), "vtk" / "ply" (mesh and field for a viewer, path ending in .vtk / .ply),
                         "streamlines" (VTK lines, as /api/streamlines). An existing file is replaced only with
                         overwrite: true (default false: 409, the page asks first; the new file is linked into place,
                         which fails if one appeared meanwhile). The mesh being edited is never replaced, even with
                         overwrite (403): neither its path nor another name of it (symbolic or hard link)
  POST /api/load         {kind: "singularities" | "constraints", path} -> header {singularities: [[v, "p/q"]]} or
                         {constraints: [[f, [x, y, z]]]}, in file order, checked by the library's readers against the
                         mesh (vertex and face numbers in range, no repeat)
SOLVE: n (1 to {MAX_N}, default --n); singularities [[vertex, "p/q" or integer]] (default []: each vertex once, a
vertex listed twice is a 422 duplicate_singularity, never last-wins); constraints
[[face, [x, y, z]]] (default []: faces in range and each once, a face listed twice is a 422 invalid_constraint
(the library's code for it); directions three finite numbers, not all zero; the field points along the direction
projected onto the face); align_boundary (default false: true follows the boundary, with a second solver made on
first use; on a mesh without boundary it is the same solve).
Paths (save, load): a non-empty relative path; with symbolic links resolved it must lie in the folder (403
otherwise); to save, its directory must exist (404), it must not be the mesh (403) and, if it exists, it must be a
regular file (400) and overwrite must be true (409); to load, it must be a regular file (404 if missing, 400
otherwise, 413 above {MAX_LOAD}). Nothing is written when a request is refused.
Constraints and alignment: each solver (plain, aligned) keeps the constrained faces of its last request; a request
with another set of faces calls set_constraints() first (cheap: pins cost about what the faces they pin cost, and
thousands are fine), under a lock held until its solve is done, so concurrent requests each get their own answer.
Size: there is no limit on the number of pins other than one per face; the body of a request is limited to
max_body bytes ({MAX_BODY} plus {BODY_PER_FACE} per face of the mesh: every face pinned with 17-digit numbers fits),
because it is read whole into memory and parsed before anything is checked.
"""
# The HTTP side and the command line; the session, streamlines, files and frames are in editor_server/.
import argparse
import http.server
import json
import os
import sys
import traceback

import numpy as np  # noqa: F401 (first, as before the split: without numpy, the same error)
import trivial_connections as tc

HERE = os.path.dirname(os.path.abspath(__file__))
if HERE not in sys.path:  # the package beside this file, also when loaded by path (test/editor/test_server.py)
    sys.path.insert(0, HERE)

# every name serve.py had before its parts moved (its tests read them here); BODY_TIMEOUT is read from here
from editor_server.files import exists_refusal  # noqa: E402,F401
from editor_server.limits import (BODY_PER_FACE, BODY_TIMEOUT, DEFAULT_SEEDS, MAX_BODY,  # noqa: E402,F401
                                  MAX_DIGITS, MAX_LOAD, MAX_N, MAX_QUADS, MAX_SEEDS, QUAD_SIZE_EDGES, RAY_STEPS,
                                  SAVE_KINDS)
from editor_server.session import Problem, Session, Solver_state  # noqa: E402,F401
from editor_server.topology import angle_defects, components_of  # noqa: E402,F401
from editor_server.wire import Refusal, frame, json_constant, json_integer, json_safe, shown  # noqa: E402,F401


def megabytes(size):
    return f"{size / (1 << 20):g} MB"


# the limits the docstring states, as it states them: written into it from the constants (its {NAME}s), so that
# the text (and --help) says what the code does
DOCUMENTED = {"MAX_DIGITS": MAX_DIGITS, "BODY_TIMEOUT": BODY_TIMEOUT, "MAX_SEEDS": MAX_SEEDS,
              "DEFAULT_SEEDS": DEFAULT_SEEDS, "RAY_STEPS": RAY_STEPS, "MAX_N": MAX_N, "MAX_LOAD": megabytes(MAX_LOAD),
              "MAX_BODY": megabytes(MAX_BODY), "BODY_PER_FACE": f"{BODY_PER_FACE} bytes",
              "DEFAULT_FEATURE_ANGLE": f"{tc.DEFAULT_FEATURE_ANGLE:g}", "MAX_QUADS": MAX_QUADS,
              "QUAD_SIZE_EDGES": QUAD_SIZE_EDGES}
for _name, _value in DOCUMENTED.items():
    __doc__ = __doc__.replace("{" + _name + "}", str(_value))


class Handler(http.server.BaseHTTPRequestHandler):
    """GET (and HEAD) on the page and the mesh, POST on the API; other methods 405 with an Allow header, methods
    nobody knows 501. Every refusal, the base class's own (a malformed request line or header) included, is a
    text/plain line; a refusal that leaves a body unread (or half read) closes the connection after it"""
    session = None
    bundle = None
    protocol_version = "HTTP/1.1"
    disable_nagle_algorithm = True  # no 40 ms wait for the client's delayed ACK between packets of a reply
    GETS = ("/", "/editor.js", "/editor.js.map", "/api/mesh")
    # the static files: URL -> (the file, from the page's folder or the bundle's, never a path from the request; type)
    FILES = {"/": ("web", "index.html", "text/html; charset=utf-8"),
             "/editor.js": ("bundle", "editor.js", "text/javascript"),
             "/editor.js.map": ("bundle", "editor.js.map", "application/json")}
    POSTS = {"/api/solve": "solve_frame", "/api/place": "place_frame", "/api/streamlines": "streamlines_frame",
             "/api/save": "save_frame", "/api/load": "load_frame", "/api/features": "features_frame",
             "/api/quads": "quads_frame"}

    def log_message(self, *args):
        pass

    def reply(self, code, body, kind, headers=()):
        """the status line, the headers and the body (not for HEAD) in one write; a client gone is not an error"""
        head = (f"{self.protocol_version} {code} {self.responses.get(code, ('',))[0]}\r\n"
                f"Content-Type: {kind}\r\nContent-Length: {len(body)}\r\nCache-Control: no-store\r\n"
                + "".join(f"{name}: {value}\r\n" for name, value in headers)
                + ("Connection: close\r\n" if self.close_connection else "") + "\r\n")
        try:
            self.wfile.write(head.encode("latin-1") + (b"" if self.command == "HEAD" else body))
        except (BrokenPipeError, ConnectionResetError):
            self.close_connection = True

    def refuse(self, code, reason, headers=()):
        """a 4xx (or 500) with a one-line reason; the folder's own path is left out of it"""
        folder = self.session.folder if self.session is not None else None
        if folder and folder != os.sep:
            reason = reason.replace(folder + os.sep, "")
        self.reply(code, (" ".join(reason.split()) + "\n").encode("utf-8", "backslashreplace"),
                   "text/plain; charset=utf-8", headers)

    def send_error(self, code, message=None, explain=None):
        """the base class's refusals (a malformed request line or header, 414, 431, 501, 505) as one line too"""
        self.close_connection = True
        self.refuse(code, message or self.responses.get(code, ("refused",))[0])

    def not_allowed(self, body_read=False):
        """405 for a method the URL does not take (404 for an unknown URL); unless the body was read, the
        connection closes after it"""
        self.close_connection = self.close_connection or not body_read
        if self.path in self.GETS:
            return self.refuse(405, f"{self.command} {self.path}: this URL takes GET and HEAD",
                               [("Allow", "GET, HEAD")])
        if self.path in self.POSTS:
            return self.refuse(405, f"{self.command} {self.path}: this URL takes POST", [("Allow", "POST")])
        return self.refuse(404, f"not found: {self.path}")

    do_PUT = do_DELETE = do_PATCH = do_OPTIONS = do_TRACE = do_CONNECT = not_allowed

    def do_GET(self):
        if self.headers.get("Transfer-Encoding") or self.headers.get("Content-Length", "0").strip() != "0":
            self.close_connection = True  # a body with a GET: not read, so nothing more can be on this connection
        if self.path not in self.GETS:
            return self.not_allowed(body_read=True)  # (or the connection closes, as just said)
        if self.path == "/api/mesh":
            return self.reply(200, self.session.mesh_frame(), "application/octet-stream")
        where, name, kind = self.FILES[self.path]
        path = os.path.join(os.path.join(HERE, "web") if where == "web" else self.bundle, name)
        try:
            with open(path, "rb") as f:
                body = f.read()
        except OSError as e:
            return self.refuse(404, f"not found: {self.path} ({e.strerror}; the page's bundle is built by the "
                                    f"target trivial_connections_editor)")
        self.reply(200, body, kind)

    do_HEAD = do_GET  # the headers of the GET (reply() leaves the body out)

    def request_object(self):
        """the body, read whole (Content-Length) and parsed: a JSON object, or None once refused"""
        if "Transfer-Encoding" in self.headers:
            self.close_connection = True
            return self.refuse(411, "a body in chunks (Transfer-Encoding) is not read: send it with a "
                                    "Content-Length")
        lengths = {value.strip() for value in self.headers.get_all("Content-Length", [])}
        if not lengths:
            self.close_connection = True  # a body could follow (read to the end of the connection): not read
            return self.refuse(411, "a POST needs a Content-Length")
        length = lengths.pop()
        if lengths or not length.isascii() or not length.isdigit():
            self.close_connection = True
            return self.refuse(400, f"bad Content-Length: {shown(self.headers.get_all('Content-Length'))}")
        length = int(length)
        limit = self.session.max_body
        if length > limit:
            self.close_connection = True  # the body is not read: nothing more can be on this connection
            return self.refuse(413, f"request body of {length} bytes (at most {limit})")
        self.connection.settimeout(BODY_TIMEOUT)
        try:
            data = self.rfile.read(length)
        except TimeoutError:
            self.close_connection = True
            return self.refuse(408, f"the body ({length} bytes) did not arrive within {BODY_TIMEOUT} s")
        except (ConnectionResetError, BrokenPipeError):
            self.close_connection = True  # nobody to answer
            return None
        finally:
            self.connection.settimeout(self.timeout)
        if len(data) < length:
            self.close_connection = True
            return self.refuse(400, f"the body ended after {len(data)} of its {length} bytes (Content-Length)")
        try:
            request = json.loads(data.decode("utf-8") or "{}", parse_int=json_integer, parse_constant=json_constant)
        except UnicodeDecodeError as e:
            return self.refuse(400, f"the body is not UTF-8: {e}")
        except RecursionError:
            return self.refuse(400, "malformed JSON: nested too deeply")
        except ValueError as e:  # json.JSONDecodeError, json_integer(), json_constant()
            return self.refuse(400, f"malformed JSON: {e}")
        if not isinstance(request, dict):
            names = {list: "an array", str: "a string", bool: "true or false", type(None): "null"}
            return self.refuse(400, f"the body must be a JSON object, got {names.get(type(request), 'a number')}")
        return request

    def do_POST(self):
        request = self.request_object()  # read first, so that the connection stays usable after a 404 or 405
        if request is None:
            return
        if self.path not in self.POSTS:
            return self.not_allowed(body_read=True)
        try:
            body = getattr(self.session, self.POSTS[self.path])(request)
        except Refusal as e:
            return self.refuse(e.status, str(e))
        except tc.InvalidInput as e:
            return self.refuse(422, f"{e.code}: {e}")
        except (TypeError, ValueError, KeyError, OverflowError) as e:
            return self.refuse(400, f"bad request: {e}")
        except RecursionError:
            return self.refuse(400, "bad request: nested too deeply")
        except Exception as e:  # noqa: BLE001 (a reply rather than a dropped connection; the trace on stderr)
            traceback.print_exc()
            return self.refuse(500, f"internal error: {type(e).__name__}: {e}")
        return self.reply(200, body, "application/octet-stream")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh")
    ap.add_argument("--n", type=int, default=4)
    ap.add_argument("--port", type=int, default=8000)
    ap.add_argument("--bundle", default=os.path.join(HERE, "..", "build", "editor"))
    ap.add_argument("--folder", default=os.getcwd(),
                    help="the only folder whose files the page may save and load (default: the current directory)")
    a = ap.parse_args()
    if not os.path.isdir(a.folder):
        ap.error(f"--folder {a.folder}: not a directory")
    Handler.session = Session(a.mesh, a.n, a.folder)
    Handler.bundle = a.bundle
    server = http.server.ThreadingHTTPServer(("127.0.0.1", a.port), Handler)
    print(f"http://127.0.0.1:{server.server_address[1]}/ (files in {Handler.session.folder})", flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    sys.exit(main())
