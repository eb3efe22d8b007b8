# Copyright (c) 2026 CGAL Trivial Connections contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Many meshes at once: the program trivial_connections on every mesh of a data set, as Dask tasks.

    trivial_connections-batch INPUT... --out DIR [program options] [--workers K] [--scheduler ADDRESS]
                              [--timeout S] [--memory-limit M] [--retries R] [--redo-failed]

or, from Python, ``run_batch(inputs, out, options)``. Each mesh is one task; the task runs the program in a
child process of a Dask worker (a local cluster of K worker processes on 127.0.0.1 by default, any Dask
scheduler with --scheduler). A crash, a hang (--timeout) or an out-of-memory (--memory-limit) ends only that
mesh's program; a worker that dies is restarted by its nanny and its meshes go to the others. Such failures
are retried up to R times, then recorded. A mesh the program refuses (an input error) is recorded at once.

Outputs, per mesh, in a folder that mirrors the input tree: ``DIR/<path of the mesh>/`` holds ``field.txt``,
``connection.txt``, ``singularities.txt`` (the program's files), ``mesh.off`` (the mesh the field is on, when
--repair or --triangulate changed it) and ``record.json``; a failed mesh's folder holds only its record. Each
folder is written in a temporary folder and renamed into place: it is complete or absent. At the end:
``DIR/summary.csv`` and ``DIR/summary.json`` (one row per mesh) and a report on stdout.

A rerun skips the meshes whose folder is complete for the same input (SHA-256 of its content, and of its
singularity file) and the same options; --redo-failed runs the failed ones again too.
"""

from __future__ import annotations

import argparse
import csv
import ctypes
import glob
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple

MESH_EXTENSIONS = (".off", ".obj", ".ply", ".stl", ".ts")
RECORD = "record.json"
OUTPUT_FILES = ("field.txt", "connection.txt", "singularities.txt")
# failures that another attempt may not repeat: the mesh's program, or its worker, died or ran out of time/memory
RETRYABLE = ("crashed", "timeout", "out_of_memory", "worker_lost")
# program options that name the batch's outputs (the batch chooses them) or that make no sense per mesh
RESERVED_OPTIONS = ("--connection", "--field", "--write-singularities", "--write-mesh", "--error-codes",
                    "--singularities", "--help", "-h", "--version", "--progress")
VALUED_PROGRAM_OPTIONS = ("--boundary-indices", "--constraints", "--guidance", "--guidance-weight", "--n",
                          "--weights", "--vtk", "--ply", "--singularity-points", "--streamlines",
                          "--streamline-seeds", "--alignment-strength", "--feature-lines", "--write-constraints")
FLAG_PROGRAM_OPTIONS = ("--triangulate", "--repair", "--align-boundary", "--auto", "--no-refine",
                        "--align-curvature", "--refine", "--cancel-pairs", "--align-features")
PER_MESH_FILE_OPTIONS = ("--vtk", "--ply", "--singularity-points", "--streamlines", "--feature-lines",
                         "--write-constraints")


class BatchError(Exception):
    """A bad batch command (unknown option, no mesh, two inputs with the same output folder, ...)."""


@dataclass
class Mesh_job:
    """One mesh of the batch: where it is, where its outputs go, and what identifies its result."""
    path: str        # absolute path of the mesh
    relative: str    # its path under the output folder
    sha256: str      # of its content (and of its singularity file)
    singularities: Optional[str] = None  # --singularities-from: the file for this mesh


@dataclass
class Batch_summary:
    """What run_batch() did: one row per mesh, and the totals."""
    rows: List[Dict[str, Any]] = field(default_factory=list)
    done: int = 0
    failed: int = 0
    skipped: int = 0
    failed_by_code: Dict[str, int] = field(default_factory=dict)
    seconds: float = 0.0
    interrupted: bool = False

    @property
    def throughput(self) -> float:
        """meshes computed (done or failed, not skipped) per second"""
        return (self.done + self.failed) / self.seconds if self.seconds > 0 else 0.0


# ---------------------------------------------------------------------------------------------- inputs

def _is_glob(text: str) -> bool:
    return any(c in text for c in "*?[")


def _meshes_in(folder: Path) -> List[Path]:
    return sorted(p for p in folder.rglob("*") if p.is_file() and p.suffix.lower() in MESH_EXTENSIONS
                  and not any(part.startswith(".") for part in p.relative_to(folder).parts))


def collect_meshes(inputs: Sequence[str]) -> List[Tuple[Path, str]]:
    """(absolute mesh path, relative output path) for every INPUT: files, folders (recursively, by extension),
    globs, or text files listing paths (one a line, relative to the list's folder, '#' comments)."""
    found: List[Tuple[Path, str]] = []

    def absolute(q: Path) -> Path:  # as given (a symbolic link is not followed: the messages name the user's path)
        return Path(os.path.abspath(q))
    for text in inputs:
        p = Path(text)
        if p.is_dir():
            found += [(absolute(m), m.relative_to(p).as_posix()) for m in _meshes_in(p)]
        elif p.is_file() and p.suffix.lower() in MESH_EXTENSIONS:
            found.append((absolute(p), p.name))
        elif p.is_file():  # a list of paths
            listed = []
            for line in p.read_text().splitlines():
                line = line.strip()
                if line and not line.startswith("#"):
                    q = Path(line) if Path(line).is_absolute() else p.parent / line
                    if not q.is_file():
                        raise BatchError(f"{text}: '{line}' is not a file")
                    listed.append(absolute(q))
            if listed:
                root = Path(os.path.commonpath([str(q.parent) for q in listed]))
                found += [(q, q.relative_to(root).as_posix()) for q in listed]
        elif _is_glob(text):
            matches = sorted(Path(m) for m in glob.glob(text, recursive=True))
            matches = [m for m in matches if m.is_file() and m.suffix.lower() in MESH_EXTENSIONS]
            if not matches:
                raise BatchError(f"'{text}' matches no mesh file")
            parts = Path(text).parts
            fixed = Path(*parts[:next(i for i, s in enumerate(parts) if _is_glob(s))]) if not _is_glob(parts[0]) \
                else Path(".")
            found += [(absolute(m), m.relative_to(fixed).as_posix()) for m in matches]
        else:
            raise BatchError(f"'{text}': no such file, folder or glob match")
    unique: Dict[Path, str] = {}
    owners: Dict[str, Path] = {}
    real: set = set()
    for path, relative in found:
        if path.resolve() in real:  # the same file twice
            continue
        real.add(path.resolve())
        if relative in owners:
            raise BatchError(f"'{owners[relative]}' and '{path}' would have the same output folder '{relative}' "
                             "(give them as separate batches, or from their common folder)")
        unique[path] = relative
        owners[relative] = path
    if not unique:
        raise BatchError("no mesh found in the inputs (extensions: " + ", ".join(MESH_EXTENSIONS) + ")")
    return list(unique.items())


def _sha256(paths: Iterable[Optional[str]]) -> str:
    h = hashlib.sha256()
    for p in paths:
        if p is None:
            continue
        with open(p, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                h.update(block)
        h.update(b"\0")
    return h.hexdigest()


def _singularities_for(pattern: Optional[str], mesh: Path) -> Optional[str]:
    """--singularities-from PATTERN: {stem}, {name} and {dir} of the mesh; a relative result is taken from the
    mesh's folder. A mesh without that file has no singularity file (the program's default)."""
    if pattern is None:
        return None
    p = Path(pattern.format(stem=mesh.stem, name=mesh.name, dir=str(mesh.parent)))
    if not p.is_absolute():
        p = mesh.parent / p
    return str(p) if p.is_file() else None


def check_program_options(options: Sequence[str]) -> List[str]:
    """The program options as given, checked: known, valued ones with a value, none of the batch's own."""
    out: List[str] = []
    i = 0
    while i < len(options):
        o = options[i]
        name = o.split("=", 1)[0]
        if name in RESERVED_OPTIONS:
            raise BatchError(f"{name} is chosen by the batch per mesh (see --singularities-from)")
        if name in PER_MESH_FILE_OPTIONS:
            raise BatchError(f"{name} writes one file: not available in a batch")
        if name in VALUED_PROGRAM_OPTIONS and "=" not in o:
            if i + 1 >= len(options):
                raise BatchError(f"option {name} needs a value")
            out += [o, options[i + 1]]
            i += 2
            continue
        if name == "--align-features" and i + 1 < len(options) and re.fullmatch(r"[0-9.eE+-]+", options[i + 1]):
            out += [o, options[i + 1]]
            i += 2
            continue
        if name not in VALUED_PROGRAM_OPTIONS and name not in FLAG_PROGRAM_OPTIONS:
            raise BatchError(f"unknown option '{o}'")
        out.append(o)
        i += 1
    return out


# ------------------------------------------------------------------------------------ the task (a worker)

_PR_SET_PDEATHSIG = 1


def _child_setup(cores: Optional[List[int]]) -> None:
    """In the program's process before exec: its own process group (a timeout kills it all), killed if its
    worker dies, and on its worker's cores when the batch shares the machine's cores among its workers."""
    os.setpgrp()
    try:
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)
    except OSError:
        pass
    if cores:
        try:
            os.sched_setaffinity(0, cores)
        except OSError:
            pass  # cores gone since (a cpuset changed): the program runs where it may


def _cores_of_worker(cores_per_mesh: int) -> Optional[List[int]]:
    """The cores of this worker's programs: worker i of a local cluster (Dask names them 0, 1, ...) gets the i-th
    `cores_per_mesh` of the cores this process may use, round the list; None when not pinned (0, fewer usable
    cores than asked, or a worker that is not a local cluster's)."""
    if cores_per_mesh <= 0 or not hasattr(os, "sched_getaffinity"):
        return None
    try:
        from distributed import get_worker
        name = get_worker().name
    except Exception:  # not in a worker (run_mesh called directly)
        return None
    if not isinstance(name, int):
        return None
    usable = sorted(os.sched_getaffinity(0))
    if cores_per_mesh >= len(usable):
        return None
    start = (name * cores_per_mesh) % len(usable)
    return [usable[(start + j) % len(usable)] for j in range(cores_per_mesh)]


def _run_program(cmd: List[str], timeout: Optional[float], memory_limit: Optional[int],
                 cores: Optional[List[int]] = None) -> Tuple[Optional[int], str, str, bool]:
    """(status or None after the timeout, stdout, stderr, killed for memory). With a memory limit a thread of the
    worker samples the program's resident memory every 20 ms and kills it above the limit, as Dask's nanny does
    for a worker (an address-space limit, RLIMIT_AS, counts reserved memory, not used memory, and made the program
    spin in a failing allocation instead of stopping)."""
    # Dask's nanny sets MALLOC_TRIM_THRESHOLD_ for its Python workers: not for the program. One thread of BLAS
    # (Dask's OPENBLAS_NUM_THREADS=1 too): the batch fills the cores with meshes.
    env = {k: v for k, v in os.environ.items() if k != "MALLOC_TRIM_THRESHOLD_"}
    env.setdefault("OPENBLAS_NUM_THREADS", "1")
    env.setdefault("OMP_NUM_THREADS", "1")
    p = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         preexec_fn=lambda: _child_setup(cores), env=env)
    over = threading.Event()
    done = threading.Event()
    if memory_limit:
        import psutil  # type: ignore[import]  # (Debian ships no stubs for it)

        def watch() -> None:
            try:
                child = psutil.Process(p.pid)
                while not done.wait(0.02):
                    if child.memory_info().rss > memory_limit:
                        over.set()
                        os.killpg(p.pid, signal.SIGKILL)
                        return
            except (psutil.Error, ProcessLookupError):
                pass
        threading.Thread(target=watch, daemon=True).start()
    try:
        out, err = p.communicate(timeout=timeout)
        status: Optional[int] = p.returncode
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, err = p.communicate()
        status = None
    finally:
        done.set()
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
    return status, out, err, over.is_set()


_NUMBER = r"[-+0-9.eE]+|nan|inf"


def parse_program_report(stdout: str) -> Dict[str, Any]:
    """The figures of the program's report (stdout) that the record keeps."""
    r: Dict[str, Any] = {}
    m = re.search(r"^mesh: .*: (\d+) vertices, (\d+) faces, (\d+) edges \((\d+) interior\), (\d+) components?$",
                  stdout, re.M)
    if m:
        r.update(vertices=int(m[1]), faces=int(m[2]), edges=int(m[3]), interior_edges=int(m[4]),
                 components=int(m[5]))
    genus = [int(g) for g in re.findall(r"^  component \d+: .*, genus (\d+),", stdout, re.M)]
    if genus:
        r["genus"] = genus  # per component (the first ten)
    m = re.search(r"^repaired: (.*)$", stdout, re.M)
    if m:
        r["repair"] = m[1].strip()
    m = re.search(r"^energy: (" + _NUMBER + ")", stdout, re.M)
    if m:
        r["energy"] = float(m[1])
    m = re.search(r"^max residual: vertices (" + _NUMBER + "), loops (" + _NUMBER + ")", stdout, re.M)
    if m:
        r["residuals"] = {"vertices": float(m[1]), "loops": float(m[2])}
    m = re.search(r"^time: (.*)$", stdout, re.M)
    if m:
        r["phase_seconds"] = {k.replace("-", "_"): float(v) for k, v in re.findall(r"([a-z-]+) ([0-9.]+) s", m[1])}
    return r


def _read_singularities(path: Path) -> List[List[Any]]:
    out: List[List[Any]] = []
    for line in path.read_text().splitlines():
        words = line.split("#", 1)[0].split()
        if len(words) == 2:
            out.append([int(words[0]), words[1]])
    return out


def _write_json_atomically(path: Path, value: Any) -> None:
    """Written to a temporary file, then renamed: complete or absent if a process dies. Not fsync'ed (7 ms a
    file here): after a power loss a record may be empty or lost, and the rerun then computes that mesh again
    (an unreadable record counts as absent)."""
    tmp = path.with_name(f".{path.name}.tmp-{uuid.uuid4().hex}")
    with open(tmp, "w") as f:
        json.dump(value, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)


def _install_folder(tmp: Path, target: Path) -> None:
    """Renames the complete folder `tmp` to `target` (which may exist: it is replaced)."""
    if target.exists():
        old = target.with_name(f".{target.name}.old-{uuid.uuid4().hex}")
        os.rename(target, old)
        os.rename(tmp, target)
        shutil.rmtree(old, ignore_errors=True)
    else:
        os.rename(tmp, target)


def _worker_name() -> str:
    try:
        from distributed import get_worker
        w = get_worker()
        return f"{w.name}@{w.address}"
    except Exception:  # not in a worker (run_mesh called directly)
        return f"pid {os.getpid()}"


def run_mesh(job: Dict[str, Any]) -> Dict[str, Any]:
    """The task: runs the program on one mesh into a temporary folder beside its target, writes the record and
    renames the folder into place. A retryable failure (crash, timeout, out of memory) installs nothing and
    returns its record with "retryable": the client retries or records it."""
    target = Path(job["target"])
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.tmp-", dir=target.parent))
    record: Dict[str, Any] = {
        "mesh": job["path"], "input_sha256": job["sha256"], "options": job["options"],
        "singularities_file": job["singularities"], "worker": _worker_name(), "attempt": job["attempt"]}
    cores = _cores_of_worker(job.get("cores_per_mesh", 0))
    record["cores"] = cores  # the cores the program was pinned to, or None
    cmd = [job["program"], job["path"], *job["options"], "--error-codes",
           "--connection", str(tmp / "connection.txt"), "--field", str(tmp / "field.txt"),
           "--write-singularities", str(tmp / "singularities.txt")]
    if job["singularities"]:
        cmd += ["--singularities", job["singularities"]]
    if job["write_mesh"]:
        cmd += ["--write-mesh", str(tmp / "mesh.off")]
    start = time.perf_counter()
    try:
        returncode, out, err, over_memory = _run_program(cmd, job["timeout"], job["memory_limit"], cores)
        record["seconds"] = time.perf_counter() - start
        record["returncode"] = returncode
        if returncode == 0:
            record.update(parse_program_report(out))
            record["status"] = "done"
            sing = tmp / "singularities.txt"
            record["singularities"] = _read_singularities(sing) if sing.exists() else []
            mesh_out = tmp / "mesh.off"
            if mesh_out.exists() and not _changed_mesh(record):
                mesh_out.unlink()  # the input mesh as it is: no copy
            missing = [f for f in OUTPUT_FILES if not (tmp / f).exists()]
            if missing:
                record.update(status="failed", error_code="internal_error",
                              error_message="the program succeeded without writing " + ", ".join(missing))
        else:
            record["status"] = "failed"
            if over_memory:
                record.update(error_code="out_of_memory",
                              error_message=f"the program used more than --memory-limit ({job['memory_limit']} bytes) "
                                            "and was killed")
            elif returncode is None:
                record.update(error_code="timeout",
                              error_message=f"the program ran longer than --timeout {job['timeout']} s and was killed")
            elif returncode < 0:
                name = signal.Signals(-returncode).name
                record.update(error_code="crashed", error_message=f"the program was killed by {name}")
                if -returncode == signal.SIGKILL:
                    record["error_message"] += " (by the kernel's out-of-memory killer?)"
            else:
                m = re.search(r"error \[([a-z_]+)\]: (.*)", err)
                code, message = (m[1], m[2]) if m else ("internal_error", err.strip()[-500:] or f"status {returncode}")
                record.update(error_code=code, error_message=message)
        record["retryable"] = record["status"] == "failed" and record["error_code"] in RETRYABLE
        if record["retryable"]:
            shutil.rmtree(tmp, ignore_errors=True)
            return record
        if record["status"] == "failed":
            for f in tmp.iterdir():  # no partial output beside a failure's record
                f.unlink()
        _write_json_atomically(tmp / RECORD, record)
        _install_folder(tmp, target)
        record["installed"] = True
        return record
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise


def _changed_mesh(record: Dict[str, Any]) -> bool:
    r = record.get("repair")
    return bool(r) and not str(r).startswith("nothing to repair")


# ------------------------------------------------------------------------------------------ the client

def _failed_record(job: Dict[str, Any], code: str, message: str) -> Dict[str, Any]:
    return {"mesh": job["path"], "input_sha256": job["sha256"], "options": job["options"],
            "singularities_file": job["singularities"], "worker": None, "attempt": job["attempt"],
            "status": "failed", "error_code": code, "error_message": message, "retryable": True}


def _record_failure(job: Dict[str, Any], record: Dict[str, Any]) -> None:
    target = Path(job["target"])
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.tmp-", dir=target.parent))
    _write_json_atomically(tmp / RECORD, record)
    _install_folder(tmp, target)


def _existing_record(target: Path) -> Optional[Dict[str, Any]]:
    try:
        with open(target / RECORD) as f:
            record: Dict[str, Any] = json.load(f)
        return record
    except (OSError, ValueError):
        return None


def _complete(target: Path, record: Dict[str, Any]) -> bool:
    return record.get("status") != "done" or all((target / f).exists() for f in OUTPUT_FILES)


def _remove_temporaries(out: Path) -> None:
    for p in out.rglob(".*.tmp-*"):
        shutil.rmtree(p, ignore_errors=True) if p.is_dir() else p.unlink(missing_ok=True)
    for p in out.rglob(".*.old-*"):
        shutil.rmtree(p, ignore_errors=True)


class _Progress:
    def __init__(self, total: int, stream: Any) -> None:
        self.total, self.stream, self.tty = total, stream, stream.isatty()
        self.start = self.last = time.perf_counter()
        self.done = self.failed = 0

    def update(self, status: str, mesh: str) -> None:
        self.done += status == "done"
        self.failed += status == "failed"
        n = self.done + self.failed
        now = time.perf_counter()
        if self.tty:
            width = 30
            bar = "#" * (width * n // max(self.total, 1))
            self.stream.write(f"\r[{bar:<{width}}] {n}/{self.total}  {self.failed} failed  {now - self.start:.0f} s")
            if n == self.total:
                self.stream.write("\n")
            self.stream.flush()
        elif status == "failed" or now - self.last >= 10 or n == self.total:
            self.last = now
            what = f"failed: {mesh}" if status == "failed" else "progress"
            self.stream.write(f"batch: {n}/{self.total} ({self.failed} failed), {now - self.start:.0f} s; {what}\n")
            self.stream.flush()


def _parse_memory(text: Optional[str]) -> Optional[int]:
    if text is None:
        return None
    from dask.utils import parse_bytes
    try:
        return int(parse_bytes(text))
    except (ValueError, TypeError) as e:
        raise BatchError(f"--memory-limit: '{text}' is not a size (e.g. 2GB, 500MiB)") from e


def run_batch(inputs: Sequence[str], out: str, options: Sequence[str] = (), *, workers: Optional[int] = None,
              scheduler: Optional[str] = None, timeout: Optional[float] = None,
              memory_limit: Optional[str] = None, retries: int = 2, redo_failed: bool = False,
              repair: bool = False, singularities_from: Optional[str] = None, program: Optional[str] = None,
              progress: Any = None, client: Any = None, cores_per_mesh: Optional[int] = None) -> Batch_summary:
    """Runs the program on every mesh of `inputs` (see the module's doc), returns the summary and writes it
    (summary.csv, summary.json) under `out`. `options` are the program's options (e.g. ["--auto", "--n", "4"]);
    `repair` adds --repair. `workers` (default: the cores) sizes the local cluster; `scheduler` is the address of
    a running Dask scheduler to use instead; `client` an existing distributed.Client to use. `memory_limit`
    (e.g. "2GB") bounds each mesh's program (its resident memory, sampled every 20 ms). `cores_per_mesh` pins each
    local worker's programs to that many cores of their own (default: the batch's own cluster of K workers shares
    the cores, C // K each, when 2 <= K <= C; no pinning with one worker, which may use them all, or with
    `scheduler`/`client` unless given, and never for workers that are not a local cluster's). Raises BatchError for a bad
    command, KeyboardInterrupt after a clean stop (finished meshes stay, no partial file)."""
    from distributed import Client, LocalCluster, as_completed
    import cloudpickle  # type: ignore[import]  # (Debian ships no stubs for it)

    program = program or os.environ.get("TC_PROGRAM") or shutil.which("trivial_connections")
    if not program or not os.access(program, os.X_OK):
        raise BatchError("the program trivial_connections is not found (PATH, TC_PROGRAM or program=)")
    program = str(Path(program).resolve())
    if retries < 0:
        raise BatchError("--retries must be at least 0")
    if timeout is not None and timeout <= 0:
        raise BatchError("--timeout must be positive")
    if workers is not None and workers < 1:
        raise BatchError("--workers must be at least 1")
    if cores_per_mesh is not None and cores_per_mesh < 1:
        raise BatchError("--cores-per-mesh must be at least 1")
    if cores_per_mesh is None and client is None and not scheduler:
        # a program's own second thread gains less than a core of its own (30 largest data-set meshes, 2 workers on
        # 2 cores: 4.03 s pinned, 4.28 s not)
        usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
        k = workers or os.cpu_count() or 1
        cores_per_mesh = usable // k if 2 <= k <= usable else 0
    memory = _parse_memory(memory_limit)
    options = check_program_options(list(options))
    if repair and "--repair" not in options:
        options.append("--repair")
    write_mesh = "--repair" in options or "--triangulate" in options
    out_dir = Path(out).resolve()
    meshes = collect_meshes(inputs)
    for path, _ in meshes:
        if out_dir == path.resolve() or out_dir in path.resolve().parents:
            raise BatchError(f"the output folder {out_dir} holds the input {path}: inputs are never overwritten")
    out_dir.mkdir(parents=True, exist_ok=True)
    _remove_temporaries(out_dir)
    stream = progress if progress is not None else sys.stderr

    summary = Batch_summary()
    start = time.perf_counter()
    jobs: List[Dict[str, Any]] = []
    for path, relative in meshes:
        sing = _singularities_for(singularities_from, path)
        job: Dict[str, Any] = {"path": str(path), "relative": relative, "target": str(out_dir / relative),
               "sha256": _sha256([str(path), sing]), "singularities": sing, "options": options,
               "program": program, "write_mesh": write_mesh, "timeout": timeout, "memory_limit": memory,
               "attempt": 1, "cores_per_mesh": cores_per_mesh or 0}
        previous = _existing_record(Path(job["target"]))
        if previous is not None and previous.get("input_sha256") == job["sha256"] and \
           previous.get("options") == options and previous.get("singularities_file") == sing and \
           _complete(Path(job["target"]), previous) and not (redo_failed and previous.get("status") == "failed"):
            summary.skipped += 1
            summary.rows.append(dict(previous, skipped=True))
            continue
        jobs.append(job)

    own_cluster = None
    cloudpickle.register_pickle_by_value(sys.modules[__name__])  # workers need not import this module
    try:
        if client is None:
            if scheduler:
                client = Client(scheduler, timeout="30s")
            else:
                n = workers or os.cpu_count() or 1
                import dask
                # a worker that dies fails its tasks at once (KilledWorker): the attempts are counted here
                with dask.config.set({"distributed.scheduler.allowed-failures": 0,
                                      "distributed.worker.daemon": False}):
                    own_cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                               host="127.0.0.1", dashboard_address=None,
                                               memory_limit="auto", silence_logs=40)
                client = Client(own_cluster)
        bar = _Progress(len(jobs), stream)
        by_future: Dict[Any, Dict[str, Any]] = {}
        futures = []
        for job in jobs:
            f = client.submit(run_mesh, job, key=f"mesh-{uuid.uuid4().hex}", pure=False)
            by_future[f] = job
            futures.append(f)
        pending = as_completed(futures)
        for f in pending:
            job = by_future.pop(f)
            try:
                record = f.result()
            except Exception as e:  # the worker died (KilledWorker) or the task raised
                name = type(e).__name__
                code = "worker_lost" if name == "KilledWorker" else "internal_error"
                record = _failed_record(job, code, f"{name}: {e}")
                record["retryable"] = code == "worker_lost"
            if record["status"] == "failed" and record.get("retryable") and job["attempt"] <= retries:
                job = dict(job, attempt=job["attempt"] + 1)
                g = client.submit(run_mesh, job, key=f"mesh-{uuid.uuid4().hex}", pure=False)
                by_future[g] = job
                pending.add(g)
                continue
            if record["status"] == "failed" and not record.get("installed"):
                _record_failure(job, record)
            record.pop("installed", None)
            if record["status"] == "done":
                summary.done += 1
            else:
                summary.failed += 1
                code = record.get("error_code", "internal_error")
                summary.failed_by_code[code] = summary.failed_by_code.get(code, 0) + 1
            summary.rows.append(dict(record, skipped=False))
            bar.update(record["status"], job["relative"])
    except KeyboardInterrupt:
        summary.interrupted = True
        raise
    finally:
        if own_cluster is not None:
            try:
                client.close()
                own_cluster.close()
            except Exception:
                pass
        elif scheduler and client is not None:
            client.close()
        _remove_temporaries(out_dir)
        summary.seconds = time.perf_counter() - start
        if summary.rows:
            write_summary(out_dir, summary)
    return summary


SUMMARY_COLUMNS = ("mesh", "status", "skipped", "error_code", "error_message", "faces", "components", "genus",
                   "singularities", "energy", "residual_vertices", "residual_loops", "seconds", "attempt", "worker",
                   "repair")


def write_summary(out: Path, summary: Batch_summary) -> None:
    """summary.csv and summary.json under `out` (written atomically), one row per mesh, sorted by mesh."""
    rows = sorted(summary.rows, key=lambda r: r["mesh"])
    flat = []
    for r in rows:
        flat.append({"mesh": r["mesh"], "status": r["status"], "skipped": r.get("skipped", False),
                     "error_code": r.get("error_code", ""), "error_message": r.get("error_message", ""),
                     "faces": r.get("faces", ""), "components": r.get("components", ""),
                     "genus": " ".join(map(str, r.get("genus", []))), "singularities": len(r.get("singularities", [])),
                     "energy": r.get("energy", ""), "residual_vertices": r.get("residuals", {}).get("vertices", ""),
                     "residual_loops": r.get("residuals", {}).get("loops", ""), "seconds": r.get("seconds", ""),
                     "attempt": r.get("attempt", ""), "worker": r.get("worker", ""), "repair": r.get("repair", "")})
    tmp = out / f".summary.csv.tmp-{uuid.uuid4().hex}"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=SUMMARY_COLUMNS)
        w.writeheader()
        w.writerows(flat)
    os.replace(tmp, out / "summary.csv")
    _write_json_atomically(out / "summary.json", {
        "done": summary.done, "failed": summary.failed, "skipped": summary.skipped,
        "failed_by_code": summary.failed_by_code, "seconds": summary.seconds,
        "throughput_per_second": summary.throughput, "interrupted": summary.interrupted, "meshes": flat})


def report(summary: Batch_summary) -> str:
    """The one-screen report."""
    lines = [f"done: {summary.done}   failed: {summary.failed}   skipped (already computed): {summary.skipped}"]
    for code, n in sorted(summary.failed_by_code.items(), key=lambda kv: (-kv[1], kv[0])):
        lines.append(f"  failed {code}: {n}")
    failed = [r for r in summary.rows if r["status"] == "failed" and not r.get("skipped")]
    for r in failed[:10]:
        lines.append(f"    {r['mesh']}: {r.get('error_code')}: {str(r.get('error_message', ''))[:100]}")
    if len(failed) > 10:
        lines.append(f"    ... and {len(failed) - 10} more (summary.csv)")
    lines.append(f"time: {summary.seconds:.1f} s, throughput {summary.throughput:.2f} meshes/s")
    return "\n".join(lines)


def split_arguments(argv: List[str]) -> Tuple[List[str], List[str]]:
    """(the batch's arguments, the program's options): the program's options are taken out with their values, so
    that a value (--n 4) is never read as an INPUT."""
    batch: List[str] = []
    program: List[str] = []
    i = 0
    while i < len(argv):
        a = argv[i]
        name = a.split("=", 1)[0]
        if name in VALUED_PROGRAM_OPTIONS or name in RESERVED_OPTIONS[:5] or name in PER_MESH_FILE_OPTIONS:
            program.append(a)
            if "=" not in a and i + 1 < len(argv):
                program.append(argv[i + 1])
                i += 1
        elif name in FLAG_PROGRAM_OPTIONS or name == "--error-codes" or name == "--progress" or name == "--version":
            program.append(a)
            if name == "--align-features" and i + 1 < len(argv) and re.fullmatch(r"[0-9.eE+-]+", argv[i + 1]):
                program.append(argv[i + 1])
                i += 1
        else:
            batch.append(a)
        i += 1
    return batch, program


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        prog="trivial_connections-batch",
        description="The program trivial_connections on many meshes, as tasks of a Dask cluster; resumable.",
        epilog="Any other option is passed to the program (--auto, --n N, --align-features, --refine, ...).")
    parser.add_argument("inputs", nargs="+", metavar="INPUT", help="mesh files, folders, globs or text files of paths")
    parser.add_argument("--out", required=True, metavar="DIR", help="output folder (mirrors the inputs' tree)")
    parser.add_argument("--workers", type=int, metavar="K", help="local worker processes (default: the cores)")
    parser.add_argument("--scheduler", metavar="ADDRESS", help="a running Dask scheduler (tcp://host:port)")
    parser.add_argument("--cores-per-mesh", type=int, metavar="C",
                        help="pin each local worker's programs to C cores of their own (default: the cores shared "
                             "among 2 or more local workers; none with one worker or --scheduler)")
    parser.add_argument("--timeout", type=float, metavar="S", help="seconds per mesh before its program is killed")
    parser.add_argument("--memory-limit", metavar="M", help="memory per mesh (the program's resident memory), e.g. 2GB")
    parser.add_argument("--retries", type=int, default=2, metavar="R",
                        help="attempts after a crash, timeout, out-of-memory or lost worker (default 2)")
    parser.add_argument("--redo-failed", action="store_true", help="run the meshes that failed before again")
    parser.add_argument("--singularities-from", metavar="PATTERN",
                        help="per mesh singularity file, e.g. '{stem}.sing' (beside the mesh); {name}, {dir} too")
    parser.add_argument("--program", metavar="PATH", help="the program (default: TC_PROGRAM, then PATH)")
    batch_args, program_options = split_arguments(list(sys.argv[1:] if argv is None else argv))
    args = parser.parse_args(batch_args)
    try:
        summary = run_batch(args.inputs, args.out, program_options, workers=args.workers,
                            scheduler=args.scheduler, timeout=args.timeout, memory_limit=args.memory_limit,
                            retries=args.retries, redo_failed=args.redo_failed,
                            singularities_from=args.singularities_from, program=args.program,
                            cores_per_mesh=args.cores_per_mesh)
    except BatchError as e:
        print(f"trivial_connections-batch: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("\ntrivial_connections-batch: interrupted; the finished meshes are kept, a rerun does the rest",
              file=sys.stderr)
        return 130
    print(report(summary))
    return 0 if summary.failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
