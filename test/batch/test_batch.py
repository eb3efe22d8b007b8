# Copyright (c) 2026 CGAL Trivial Connections contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""trivial_connections-batch (python/trivial_connections_batch.py) on CGAL's data set, loopback only.

Environment (set by ctest python_batch): TC_PROGRAM the program, TC_CGAL_MESHES CGAL's data/meshes,
PYTHONPATH the build's python/ folder, TC_BATCH_OUT a scratch folder, TC_CHECKER the independent checker.

The options are --auto --n 4 --no-refine: the data set in about 15 s of CPU (with the refinement it is minutes),
and the automatic placement is still exercised on every mesh."""

import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

distributed = pytest.importorskip("distributed")  # Debian's python3-distributed (scripts/install_dependencies.sh)
import trivial_connections_batch as tcb  # noqa: E402

PROGRAM = os.environ.get("TC_PROGRAM", "")
MESHES = Path(os.path.abspath(os.environ.get("TC_CGAL_MESHES", "")))
SCRATCH = Path(os.environ.get("TC_BATCH_OUT", "/tmp/tc_batch_test"))
CHECKER = os.environ.get("TC_CHECKER", "")
OPTIONS = ["--auto", "--n", "4", "--no-refine"]

pytestmark = pytest.mark.skipif(not PROGRAM or not MESHES.is_dir(),
                                reason="TC_PROGRAM and TC_CGAL_MESHES (bash scripts/fetch_cgal_data.sh) needed")


def records_while_running(out):
    """The records written so far under `out`, while a batch writes there: a temporary folder it renames while
    the listing walks the tree is skipped (the listing is started again)."""
    while True:
        try:
            return list(out.rglob(tcb.RECORD))
        except FileNotFoundError:
            continue


def scratch(name):
    d = SCRATCH / name
    shutil.rmtree(d, ignore_errors=True)
    d.mkdir(parents=True)
    return d


def all_meshes():
    return sorted(p for p in MESHES.iterdir() if p.suffix.lower() in tcb.MESH_EXTENSIONS)


def data_lines(path):
    """a file's lines without its '#' header (which names the output paths)"""
    return [l for l in Path(path).read_text().splitlines() if not l.startswith("#")]


def run_program(mesh, out, extra=()):
    out.mkdir(parents=True, exist_ok=True)
    cmd = [PROGRAM, str(mesh), *OPTIONS, *extra, "--error-codes", "--connection", str(out / "connection.txt"),
           "--field", str(out / "field.txt"), "--write-singularities", str(out / "singularities.txt")]
    return subprocess.run(cmd, capture_output=True, text=True, stdin=subprocess.DEVNULL)


def no_temporaries(out):
    left = [p for p in out.rglob("*") if ".tmp-" in p.name or ".old-" in p.name]
    assert not left, left


def complete_folders(out):
    """every mesh folder holds a record, and a done one the three files: nothing partial"""
    folders = [p.parent for p in out.rglob(tcb.RECORD)]
    for f in folders:
        record = json.loads((f / tcb.RECORD).read_text())
        if record["status"] == "done":
            assert all((f / name).is_file() for name in tcb.OUTPUT_FILES), f
        else:
            assert sorted(p.name for p in f.iterdir()) == [tcb.RECORD], f
    for f in out.rglob("*"):  # no folder of a mesh without its record
        if f.is_dir() and f.suffix.lower() in tcb.MESH_EXTENSIONS:
            assert (f / tcb.RECORD).is_file(), f
    return folders


def test_data_set_two_workers_as_the_program():
    """CGAL's whole data set, broken meshes included: each good mesh gives exactly the program's outputs, each
    bad one the program's error as its record; with --repair every mesh that is a surface gets a field."""
    out = scratch("data_set")
    meshes = all_meshes()
    summary = tcb.run_batch([str(MESHES)], str(out), OPTIONS, workers=2, program=PROGRAM)
    assert summary.done + summary.failed == len(meshes) and summary.skipped == 0
    no_temporaries(out)
    assert len(complete_folders(out)) == len(meshes)
    direct = scratch("data_set_direct")
    codes = {}
    for mesh in meshes:
        got = out / mesh.name
        record = json.loads((got / tcb.RECORD).read_text())
        p = run_program(mesh, direct / mesh.name)
        assert record["input_sha256"] == tcb._sha256([str(mesh)])
        if p.returncode == 0:
            assert record["status"] == "done", (mesh, record)
            for name in tcb.OUTPUT_FILES:
                assert data_lines(got / name) == data_lines(direct / mesh.name / name), (mesh, name)
            faces = len(data_lines(got / "field.txt"))
            assert record["faces"] == faces
            assert len(record["singularities"]) == len(data_lines(got / "singularities.txt"))
            assert record["residuals"]["vertices"] < 1e-8 and "solve" in record["phase_seconds"]
        else:
            assert p.returncode == 1 and record["status"] == "failed", (mesh, record)
            assert p.stderr.strip() == f"trivial_connections: error [{record['error_code']}]: " \
                                       f"{record['error_message']}"
            codes[record["error_code"]] = codes.get(record["error_code"], 0) + 1
    # the data set's known defects: polygons, orientation, a non-manifold vertex, a degenerate face, a point cloud
    assert codes.get("not_triangle_mesh", 0) >= 19 and codes.get("inconsistent_orientation", 0) >= 3
    assert codes.get("non_manifold", 0) >= 1 and codes.get("degenerate_face", 0) >= 1
    assert summary.failed == sum(codes.values()) and summary.failed_by_code == codes
    table = json.loads((out / "summary.json").read_text())
    assert len(table["meshes"]) == len(meshes) and table["failed"] == summary.failed
    assert (out / "summary.csv").read_text().count("\n") == len(meshes) + 1

    # --repair: every mesh with faces gets a field, on the mesh written beside it
    repaired = scratch("data_set_repair")
    summary = tcb.run_batch([str(MESHES)], str(repaired), OPTIONS, workers=2, program=PROGRAM, repair=True)
    failed = {Path(r["mesh"]).name: r["error_code"] for r in summary.rows if r["status"] == "failed"}
    assert failed == {"b9.ply": "empty_mesh"}, failed  # b9.ply is a point cloud: no face
    no_temporaries(repaired)
    for mesh in meshes:
        if mesh.name in failed:
            continue
        record = json.loads((repaired / mesh.name / tcb.RECORD).read_text())
        assert record["status"] == "done" and "repair" in record
        was_good = json.loads((out / mesh.name / tcb.RECORD).read_text())["status"] == "done"
        mesh_off = repaired / mesh.name / "mesh.off"
        assert mesh_off.exists() == (not was_good), mesh  # a good mesh is not changed by --repair
        if was_good:
            assert data_lines(repaired / mesh.name / "field.txt") == data_lines(out / mesh.name / "field.txt")
        else:
            assert int(mesh_off.read_text().split("\n")[1].split()[1]) == record["faces"]
            if CHECKER and os.path.exists(CHECKER):
                d = repaired / mesh.name
                c = subprocess.run([sys.executable, CHECKER, str(mesh_off), "--connection", str(d / "connection.txt"),
                                    "--field", str(d / "field.txt"), "--singularities", str(d / "singularities.txt"),
                                    "--n", "4"], capture_output=True, text=True)
                assert c.returncode == 0 and "PASS" in c.stdout, (mesh, c.stdout[-2000:], c.stderr[-2000:])


def largest(k):
    return sorted(all_meshes(), key=lambda p: p.stat().st_size)[-k:]


def test_killed_worker_and_memory_limit():
    """A worker killed with SIGKILL mid-run: its nanny restarts it, its mesh is retried, the batch finishes with
    every mesh done. A mesh above --memory-limit: recorded out_of_memory after its retries, the others done."""
    meshes = [m for m in largest(12) if m.name != "b9.ply"]
    out = scratch("killed")
    import dask
    # as the batch's own cluster: a dead worker's task fails at once, and the batch counts the attempts
    with dask.config.set({"distributed.scheduler.allowed-failures": 0}), \
         distributed.LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as client:
        pids = client.run(os.getpid)
        victim = sorted(pids.items())[0]
        result = {}

        def batch():
            result["summary"] = tcb.run_batch([str(m) for m in meshes], str(out), ["--repair", "--auto", "--n", "4"],
                                              program=PROGRAM, client=client, retries=2)
        t = threading.Thread(target=batch)
        t.start()
        deadline = time.time() + 120
        while not records_while_running(out) and time.time() < deadline:  # a few meshes done, others running
            time.sleep(0.05)
        time.sleep(0.3)
        os.kill(victim[1], signal.SIGKILL)
        t.join(300)
        assert not t.is_alive()
        client.wait_for_workers(2, timeout=60)  # restarted by its nanny
        assert victim[1] not in client.run(os.getpid).values()
    summary = result["summary"]
    assert summary.done == len(meshes) and summary.failed == 0, tcb.report(summary)
    assert any(r["attempt"] > 1 for r in summary.rows)  # the killed worker's mesh, run again
    no_temporaries(out)
    complete_folders(out)

    out = scratch("memory")
    big, small = largest(1)[0], MESHES / "elephant.off"
    summary = tcb.run_batch([str(big), str(small)], str(out), OPTIONS, workers=2, program=PROGRAM,
                            memory_limit="60MB", retries=1)  # peaks: about 15 MB and 115 MB
    records = {Path(r["mesh"]).name: r for r in summary.rows}
    assert records[small.name]["status"] == "done"
    assert records[big.name]["status"] == "failed" and records[big.name]["error_code"] == "out_of_memory"
    assert records[big.name]["attempt"] == 2  # retried once
    assert summary.failed_by_code == {"out_of_memory": 1}
    no_temporaries(out)
    complete_folders(out)


def test_interrupted_batch_resumes():
    """Ctrl-C (SIGINT) stops the command cleanly: no partial file; a rerun computes only the rest, and
    --redo-failed only the failures."""
    src = scratch("resume_src")
    for m in all_meshes()[:60]:  # a tree: the outputs mirror it
        (src / m.suffix[1:]).mkdir(exist_ok=True)
        shutil.copy(m, src / m.suffix[1:] / m.name)
    total = len(list(p for p in src.rglob("*") if p.is_file()))
    out = scratch("resume")
    env = dict(os.environ, TC_PROGRAM=PROGRAM)
    cmd = [sys.executable, tcb.__file__, str(src), "--out", str(out), "--workers", "2", "--auto", "--n", "4"]
    p = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 120
    while len(records_while_running(out)) < 5 and time.time() < deadline and p.poll() is None:
        time.sleep(0.05)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    no_temporaries(out)
    first = complete_folders(out)
    assert 5 <= len(first) < total
    rerun = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=600)
    assert rerun.returncode == 1, rerun.stderr  # the data set's bad meshes fail
    table = json.loads((out / "summary.json").read_text())
    assert table["skipped"] == len(first) and table["done"] + table["failed"] == total - len(first)
    assert len(complete_folders(out)) == total
    failed = sum(1 for r in table["meshes"] if r["status"] == "failed")
    again = subprocess.run(cmd + ["--redo-failed"], env=env, capture_output=True, text=True, timeout=600)
    table = json.loads((out / "summary.json").read_text())
    assert table["skipped"] == total - failed and table["failed"] == failed and table["done"] == 0, again.stdout
    # other options: everything again
    changed = subprocess.run(cmd[:-2] + ["--n", "2"], env=env, capture_output=True, text=True, timeout=600)
    table = json.loads((out / "summary.json").read_text())
    assert table["skipped"] == 0, changed.stdout


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_scheduler_and_workers_started_by_hand():
    """`dask scheduler` and two `dask worker` processes on 127.0.0.1: --scheduler gives the local cluster's results."""
    meshes = [str(m) for m in all_meshes()[:40]]
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    dask_cli = shutil.which("dask") or pytest.skip("no dask command (python3-distributed)")
    procs = [subprocess.Popen([dask_cli, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        for _ in range(2):
            procs.append(subprocess.Popen([dask_cli, "worker", address,
                                           "--nthreads", "1", "--no-dashboard", "--host", "127.0.0.1"],
                                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        with distributed.Client(address, timeout="60s") as client:
            client.wait_for_workers(2, timeout=60)
        remote = scratch("remote")
        env = dict(os.environ, TC_PROGRAM=PROGRAM)
        r = subprocess.run([sys.executable, tcb.__file__, *meshes, "--out", str(remote), "--scheduler", address,
                            *OPTIONS], env=env, capture_output=True, text=True, timeout=600)
        assert r.returncode in (0, 1), r.stderr
        local = scratch("local")
        tcb.run_batch(meshes, str(local), OPTIONS, workers=2, program=PROGRAM)
        workers = set()
        for m in meshes:
            a = json.loads((remote / Path(m).name / tcb.RECORD).read_text())
            b = json.loads((local / Path(m).name / tcb.RECORD).read_text())
            workers.add(a["worker"].split("@")[1])
            for k in ("status", "error_code", "error_message", "faces", "energy", "singularities", "input_sha256"):
                assert a.get(k) == b.get(k), (m, k)
            if a["status"] == "done":
                for name in tcb.OUTPUT_FILES:
                    assert data_lines(remote / Path(m).name / name) == data_lines(local / Path(m).name / name)
        assert len(workers) == 2  # both workers took meshes
    finally:
        for p in reversed(procs):
            p.send_signal(signal.SIGINT)
        for p in procs:
            try:
                p.wait(20)
            except subprocess.TimeoutExpired:
                p.kill()


def test_bad_commands():
    out = scratch("bad")
    with pytest.raises(tcb.BatchError, match="no such file"):
        tcb.run_batch([str(MESHES / "no_such.off")], str(out), program=PROGRAM)
    with pytest.raises(tcb.BatchError, match="chosen by the batch"):
        tcb.run_batch([str(MESHES / "cow.off")], str(out), ["--field", "x"], program=PROGRAM)
    with pytest.raises(tcb.BatchError, match="unknown option"):
        tcb.run_batch([str(MESHES / "cow.off")], str(out), ["--bogus"], program=PROGRAM)
    with pytest.raises(tcb.BatchError, match="holds the input"):
        tcb.run_batch([str(MESHES / "cow.off")], str(MESHES), program=PROGRAM)
    assert tcb.split_arguments(["a", "--n", "4", "--out", "o", "--auto", "b"]) == \
        (["a", "--out", "o", "b"], ["--n", "4", "--auto"])


def test_workers_share_the_cores():
    """Local workers share the cores: with two workers each one's programs run on a core of their own (the
    affinity the program reads, and its record), with --cores-per-mesh as asked, with one worker on every core."""
    usable = sorted(os.sched_getaffinity(0))
    if len(usable) < 2:
        pytest.skip("one usable core: nothing to share")
    d = scratch("cores")
    seen = d / "seen"
    seen.mkdir()
    # the program's affinity as the kernel gives it to the program's own process
    wrapper = d / "program.sh"
    wrapper.write_text("#!/bin/sh\n"
                       f"grep Cpus_allowed_list /proc/self/status > '{seen}'/\"$(basename \"$1\")\"\n"
                       f"exec '{PROGRAM}' \"$@\"\n")
    wrapper.chmod(0o755)
    meshes = [str(p) for p in largest(8)]

    def cores_seen(name):
        text = (seen / name).read_text().split(":", 1)[1].strip()
        cores = set()
        for part in text.split(","):
            a, _, b = part.partition("-")
            cores.update(range(int(a), int(b or a) + 1))
        return sorted(cores)

    summary = tcb.run_batch(meshes, str(d / "two"), OPTIONS, workers=2, program=str(wrapper))
    by_worker = {}
    for r in summary.rows:
        assert r["status"] == "done" or r.get("error_code"), r
        assert r["cores"] is not None and len(r["cores"]) == len(usable) // 2, r
        assert cores_seen(Path(r["mesh"]).name) == r["cores"]
        by_worker.setdefault(r["worker"], set()).add(tuple(r["cores"]))
    assert all(len(c) == 1 for c in by_worker.values())  # a worker keeps its cores
    if len(by_worker) == 2:
        a, b = (next(iter(c)) for c in by_worker.values())
        assert not set(a) & set(b)  # and shares none of them
    summary = tcb.run_batch(meshes[:2], str(d / "asked"), OPTIONS, workers=2, program=str(wrapper),
                            cores_per_mesh=1)
    assert all(r["cores"] is not None and len(r["cores"]) == 1 for r in summary.rows)
    assert all(cores_seen(Path(r["mesh"]).name) == r["cores"] for r in summary.rows)
    summary = tcb.run_batch(meshes[:2], str(d / "one"), OPTIONS, workers=1, program=str(wrapper))
    assert all(r["cores"] is None for r in summary.rows)
    assert all(cores_seen(Path(r["mesh"]).name) == usable for r in summary.rows)
    with pytest.raises(tcb.BatchError, match="cores-per-mesh"):
        tcb.run_batch(meshes[:1], str(d / "bad"), OPTIONS, workers=2, program=str(wrapper), cores_per_mesh=0)


def test_crash_and_timeout_are_retried_then_recorded():
    """A program that dies of SIGSEGV, and one that hangs past --timeout: each retried once, then recorded
    (crashed with the signal, timeout); the other mesh of the batch is done."""
    d = scratch("crash")
    wrapper = d / "program.sh"
    wrapper.write_text("#!/bin/sh\n"
                       "case \"$1\" in *cow.off) kill -SEGV $$ ;; *elephant.off) exec sleep 60 ;; esac\n"
                       f"exec '{PROGRAM}' \"$@\"\n")
    wrapper.chmod(0o755)
    out = d / "out"
    meshes = [str(MESHES / m) for m in ("cow.off", "elephant.off", "pig.off")]
    summary = tcb.run_batch(meshes, str(out), OPTIONS, workers=2, program=str(wrapper), timeout=2, retries=1)
    records = {Path(r["mesh"]).name: r for r in summary.rows}
    assert records["cow.off"]["error_code"] == "crashed" and "SIGSEGV" in records["cow.off"]["error_message"]
    assert records["elephant.off"]["error_code"] == "timeout"
    assert records["cow.off"]["attempt"] == 2 and records["elephant.off"]["attempt"] == 2
    assert records["pig.off"]["status"] == "done" and summary.failed_by_code == {"crashed": 1, "timeout": 1}
    assert summary.seconds < 30  # the hung program was killed, not waited for
    no_temporaries(out)
    complete_folders(out)
