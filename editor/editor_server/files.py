"""The files of the folder: paths checked, files written completely or not at all, saves and loads."""

import errno
import os
import tempfile

import trivial_connections as tc

from .limits import MAX_LOAD, SAVE_KINDS
from .wire import Refusal, frame, shown


class Folder_files:
    """the save and load requests of a Session (a part of it: self.folder, the mesh's path and file, its solves)"""

    def user_path(self, path, saving):
        """the real path of a file of the folder named by a request (relative to the folder), checked"""
        if not isinstance(path, str) or not path:
            raise Refusal(400, f"path must be a non-empty string (relative to the folder), got {shown(path)}")
        if "\0" in path:
            raise Refusal(400, f"path {shown(path)} contains a NUL character")
        if os.path.isabs(path):
            raise Refusal(400, f"path {shown(path)} must be relative to the folder")
        real = os.path.realpath(os.path.join(self.folder, path))
        if os.path.commonpath([self.folder, real]) != self.folder:
            raise Refusal(403, f"path {shown(path)} is outside the folder")
        if saving:
            if os.path.isdir(real):
                raise Refusal(400, f"path {shown(path)} is a directory")
            if not os.path.isdir(os.path.dirname(real)):
                raise Refusal(404, f"path {shown(path)}: its directory does not exist")
            self.not_the_mesh(real, path)
            if os.path.lexists(real) and not os.path.isfile(real):
                raise Refusal(400, f"path {shown(path)} exists and is not a regular file")
        else:
            if not os.path.lexists(real):
                raise Refusal(404, f"no file {shown(path)} in the folder")
            if not os.path.isfile(real):
                raise Refusal(400, f"path {shown(path)} is not a regular file")
            if os.path.getsize(real) > MAX_LOAD:
                raise Refusal(413, f"file {shown(path)} is larger than {MAX_LOAD} bytes")
        return real

    def not_the_mesh(self, real, path):
        """refuses (403) a path to save to that is the mesh being edited: its real path, or another name of its
        file (a hard link; a symbolic link resolves to its real path) as it was at start or as it is now"""
        if real == self.mesh_real:
            raise Refusal(403, f"path {shown(path)} is the mesh being edited: it is never replaced")
        try:
            stat = os.stat(real)
        except (OSError, ValueError):
            return  # no such file (yet): link_into_place() will not replace one that appears
        files = {self.mesh_file}
        try:
            now = os.stat(self.path)
            files.add((now.st_dev, now.st_ino))
        except OSError:
            pass
        if (stat.st_dev, stat.st_ino) in files:
            raise Refusal(403, f"path {shown(path)} is another name of the mesh being edited: it is never replaced")

    def write(self, target, path, overwrite, writer):
        """writes a file completely or not at all: writer(temporary) writes a temporary file beside `target` (the
        library writes atomically: its own temporary, renamed), which then takes the target's name. Without
        overwrite, an existing file is a 409 (checked after the solve: the page asks to replace a file only when
        the save would succeed) and the new file is linked to the name, which fails if a file has it (one that
        appeared meanwhile: 409 too), so it never replaces one; with overwrite it is renamed over it, the mesh
        checked again just before"""
        if not overwrite and os.path.lexists(target):
            raise exists_refusal(path)
        directory, name = os.path.split(target)
        temporary = None
        try:
            # the temporary keeps the name's ending: the library picks the field's format from it
            fd, temporary = tempfile.mkstemp(prefix=".tc-save-", suffix="-" + name, dir=directory)
            os.close(fd)
            writer(temporary)
            self.not_the_mesh(target, path)
            if overwrite:
                os.replace(temporary, target)
            else:
                self.link_into_place(temporary, target, path)
        except OSError as e:  # e.g. a folder one may not write in: the library's code for it
            raise Refusal(422, f"io_error: cannot write {shown(path)}: {e.strerror or e}") from None
        finally:
            if temporary is not None and os.path.lexists(temporary):
                os.unlink(temporary)

    @staticmethod
    def link_into_place(temporary, target, path):
        """gives the temporary file the target's name if no file has it, else 409 (the temporary stays, and the
        caller removes it)"""
        exists = exists_refusal(path)
        try:
            os.link(temporary, target)
            return
        except FileExistsError:
            raise exists from None
        except OSError as e:
            if e.errno not in (errno.EPERM, errno.ENOTSUP, errno.EOPNOTSUPP, errno.EMLINK, errno.EACCES):
                raise
        # a file system without hard links: the name is taken (O_EXCL, empty until the rename fills it)
        try:
            os.close(os.open(target, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644))
        except FileExistsError:
            raise exists from None
        os.replace(temporary, target)

    def save_frame(self, request):
        """solves (and traces), checks everything, then writes the file completely or not at all; an existing file
        is replaced only with overwrite: true, the mesh never"""
        if not isinstance(request, dict):
            raise ValueError("the body must be a JSON object")
        kind = request.get("kind")
        if not isinstance(kind, str) or kind not in SAVE_KINDS:
            raise ValueError(f"kind must be one of {', '.join(SAVE_KINDS)}, got {shown(kind)}")
        overwrite = request.get("overwrite", False)
        if not isinstance(overwrite, bool):
            raise ValueError(f"overwrite must be true or false, got {shown(overwrite)}")
        path = request.get("path")
        target = self.user_path(path, saving=True)
        if not target.endswith(SAVE_KINDS[kind]):
            raise ValueError(f"a {kind} file must end in {SAVE_KINDS[kind]}, got {shown(path)}")
        p = self.problem(request)
        count = self.seed_count(request) if kind == "streamlines" else 0
        result, solver = self.solve(p)
        if kind == "singularities":
            writer = lambda temporary: tc.write_singularities(temporary, p.singularities)
        elif kind == "constraints":
            writer = lambda temporary: tc.write_face_directions(temporary, p.faces, p.directions)
        elif kind == "streamlines":
            lines = self.streamlines(p, result, solver, count)[0]
            writer = lambda temporary: tc.write_streamlines(temporary, lines)
        else:
            writer = lambda temporary: solver.write_field(temporary, result, p.singularities)
        self.write(target, path, overwrite, writer)
        return frame({"saved": os.path.relpath(target, self.folder), "bytes": os.path.getsize(target)}, [])

    def load_frame(self, request):
        if not isinstance(request, dict):
            raise ValueError("the body must be a JSON object")
        kind = request.get("kind")
        if not isinstance(kind, str) or kind not in ("singularities", "constraints"):
            raise ValueError(f"kind must be singularities or constraints, got {shown(kind)}")
        real = self.user_path(request.get("path"), saving=False)
        if kind == "singularities":
            s = tc.read_singularities(real, len(self.V))
            return frame({"singularities": [[int(v), str(k)] for v, k in s.items()]}, [])
        faces, directions = tc.read_face_directions(real, len(self.F))
        return frame({"constraints": [[f, d] for f, d in zip(faces.tolist(), directions.tolist())]}, [])


def exists_refusal(path):
    """the 409 of a save to an existing file without "overwrite": true"""
    return Refusal(409, f"file {shown(path)} already exists in the folder: it is replaced only with "
                        f'"overwrite": true')
