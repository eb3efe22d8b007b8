#!/usr/bin/python3
# Copyright (c) 2026 CGAL Trivial Connections contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""trivial_connections-batch: throughput with 1 and 2 local workers, and the batch's own cost per mesh.

Usage: batch_throughput.py PROGRAM MESHES_DIR --json OUT.json [--markdown RESULTS.md] [--commit C]

- throughput: the 30 largest meshes of the data set (by file size), `--repair --auto --n 4`, on a started local
  cluster of 1 then 2 workers (each run a fresh output folder), best of 3; ratio = time(1 worker) / time(2
  workers). Also the whole command once (cluster start and stop included) and the cluster start alone.
- overhead per mesh: the 40 smallest meshes, `--repair --auto --n 4 --no-refine`; the same commands run one after
  the other by subprocess (no batch) against run_batch() on an already started 1-worker cluster; overhead =
  (batch time - direct time) / meshes, best of 3 rounds each. It holds the Dask round trip, the hashes, the
  record and the renames.
"""
import argparse
import datetime
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
import trivial_connections_batch as tcb  # noqa: E402


def meshes_of(folder):
    return sorted((p for p in Path(folder).iterdir() if p.suffix.lower() in tcb.MESH_EXTENSIONS),
                  key=lambda p: (p.stat().st_size, p.name))


def timed_batch(meshes, options, program, **kw):
    out = Path(tempfile.mkdtemp(prefix="tc_batch_bench_"))
    try:
        start = time.perf_counter()
        s = tcb.run_batch([str(m) for m in meshes], str(out), options, program=program,
                          progress=open(os.devnull, "w"), **kw)
        return time.perf_counter() - start, s
    finally:
        shutil.rmtree(out, ignore_errors=True)


def direct(meshes, options, program):
    out = Path(tempfile.mkdtemp(prefix="tc_batch_bench_direct_"))
    try:
        start = time.perf_counter()
        for m in meshes:
            subprocess.run([program, str(m), *options, "--error-codes", "--connection", str(out / "c.txt"),
                            "--field", str(out / "f.txt"), "--write-singularities", str(out / "s.txt"),
                            "--write-mesh", str(out / "m.off")],
                           stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        return time.perf_counter() - start
    finally:
        shutil.rmtree(out, ignore_errors=True)


def plain_pool(meshes, options, program, k):
    """the same program commands by k threads that each start the next one (no Dask, no record): what k
    processes at once give on this machine, the ceiling of the batch's ratio; with k >= 2 each thread's programs
    on cores of their own, as the batch's workers"""
    from concurrent.futures import ThreadPoolExecutor
    out = Path(tempfile.mkdtemp(prefix="tc_batch_bench_pool_"))
    usable = sorted(os.sched_getaffinity(0))
    share = len(usable) // k if 2 <= k <= len(usable) else 0
    slots = iter(range(k))
    local = threading.local()
    lock = threading.Lock()
    try:
        def one(i_m):
            i, m = i_m
            if not hasattr(local, "cores"):
                with lock:
                    slot = next(slots)
                local.cores = usable[slot * share:(slot + 1) * share] if share else None
            cores = local.cores
            subprocess.run([program, str(m), *options, "--connection", str(out / f"c{i}.txt"),
                            "--field", str(out / f"f{i}.txt")], stdin=subprocess.DEVNULL,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=dict(os.environ, OPENBLAS_NUM_THREADS="1"),
                           preexec_fn=(lambda: os.sched_setaffinity(0, cores)) if cores else None)
        start = time.perf_counter()
        with ThreadPoolExecutor(k) as pool:
            list(pool.map(one, enumerate(reversed(meshes))))
        return time.perf_counter() - start
    finally:
        shutil.rmtree(out, ignore_errors=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("program")
    ap.add_argument("meshes")
    ap.add_argument("--json", required=True)
    ap.add_argument("--markdown")
    ap.add_argument("--commit", default="unknown")
    a = ap.parse_args()
    program = str(Path(a.program).resolve())
    all_meshes = meshes_of(a.meshes)

    from distributed import Client, LocalCluster
    large = all_meshes[-30:]
    options = ["--repair", "--auto", "--n", "4"]
    times = {1: [], 2: []}
    one_core = []  # 1 worker whose programs have one core, as each of 2 workers' on 2 cores
    startup = {1: [], 2: []}
    summaries = {}
    usable = len(os.sched_getaffinity(0))
    for k in (1, 2):
        start = time.perf_counter()
        # the cores as the command shares them among its own cluster's workers (run_batch(workers=k))
        share = usable // k if 2 <= k <= usable else None
        with LocalCluster(n_workers=k, threads_per_worker=1, host="127.0.0.1", dashboard_address=None,
                          silence_logs=40) as cluster, Client(cluster) as client:
            startup[k].append(time.perf_counter() - start)
            timed_batch(large[:2], options, program, client=client)  # warm the workers
            for _ in range(3):
                t, s = timed_batch(large, options, program, client=client, cores_per_mesh=share)
                times[k].append(t)
                summaries[k] = s
                print(f"30 largest, {k} worker(s): {t:.2f} s ({s.done} done, {s.failed} failed)", flush=True)
                if k == 1 and usable >= 2:
                    t, s = timed_batch(large, options, program, client=client, cores_per_mesh=usable // 2)
                    one_core.append(t)
                    print(f"30 largest, 1 worker on {usable // 2} core(s): {t:.2f} s", flush=True)
        t, s = timed_batch(large, options, program, workers=k)  # the whole command: cluster start included
        startup[k].append(t)
        print(f"30 largest, {k} worker(s), cluster start included: {t:.2f} s", flush=True)
    t1, t2 = min(times[1]), min(times[2])
    pool = {k: min(plain_pool(large, options, program, k) for _ in range(3)) for k in (1, 2)}
    print(f"plain pool without Dask: 1 process {pool[1]:.2f} s, 2 at once {pool[2]:.2f} s", flush=True)

    small = all_meshes[:40]
    small_options = ["--repair", "--auto", "--n", "4", "--no-refine"]
    with LocalCluster(n_workers=1, threads_per_worker=1, host="127.0.0.1", dashboard_address=None,
                      silence_logs=40) as cluster, Client(cluster) as client:
        timed_batch(small[:5], small_options, program, client=client)  # warm the worker
        batch_times = [timed_batch(small, small_options, program, client=client)[0] for _ in range(3)]
    direct_times = [direct(small, small_options, program) for _ in range(3)]
    overhead = (min(batch_times) - min(direct_times)) / len(small)
    faces = []
    for m in small:
        with open(m, errors="replace") as f:
            head = f.read(4096).split()
        if head and head[0].upper().endswith("OFF") and len(head) > 2 and head[2].isdigit():
            faces.append(int(head[2]))
    result = {
        "date": datetime.datetime.now().isoformat(timespec="seconds"), "commit": a.commit, "cores": os.cpu_count(),
        "cpu": platform.processor(), "largest": [m.name for m in large], "options": options,
        "seconds_1_worker": times[1], "seconds_2_workers": times[2], "ratio": t1 / t2,
        "seconds_1_worker_own_share": one_core, "ratio_same_share": (min(one_core) / t2) if one_core else None,
        "cluster_start_seconds": {k: v[0] for k, v in startup.items()},
        "plain_pool_seconds": pool,
        "with_start_seconds": {k: v[1] for k, v in startup.items()},
        "done": summaries[2].done, "failed": summaries[2].failed, "failed_by_code": summaries[2].failed_by_code,
        "small": [m.name for m in small], "small_options": small_options, "small_max_faces": max(faces or [0]),
        "batch_seconds": batch_times, "direct_seconds": direct_times, "overhead_per_mesh_seconds": overhead}
    with open(a.json, "w") as f:
        json.dump(result, f, indent=1)
    print(f"ratio 2 workers / 1 worker: {t1 / t2:.2f}; overhead per mesh {1000 * overhead:.1f} ms")
    if a.markdown:
        write_section(a.markdown, result)


SECTION = "## The batch (trivial_connections-batch)"


def write_section(path, r):
    # per worker count: int keys here, strings once read back from the JSON file
    r = dict(r)
    for key in ("with_start_seconds", "plain_pool_seconds", "cluster_start_seconds"):
        r[key] = {int(k): v for k, v in r[key].items()}
    cpu = ""
    try:
        cpu = next(l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    lines = [SECTION, "",
             f"Measured {r['date'][:10]} on {r['cores']} cores ({cpu}), commit {r['commit']}, by "
             "`bash scripts/run_benchmarks.sh --batch` (`benchmark/batch/batch_throughput.py`), under an exclusive "
             "lock of the machine.", "",
             "| measure | 1 worker | 2 workers | ratio |", "|---|---|---|---|",
             f"| 30 largest meshes of CGAL's data set, `{' '.join(r['options'])}`: run_batch() on a started local "
             f"cluster, the cores shared as the command shares them (1 worker: every core for each mesh; 2 workers: "
             f"one each), best of {len(r['seconds_1_worker'])} | {min(r['seconds_1_worker']):.2f} s | "
             f"{min(r['seconds_2_workers']):.2f} s | **{r['ratio']:.2f}** |",
             *([f"| the same, each mesh's program on {r['cores'] // 2} core(s) of its own in both (`--cores-per-mesh "
                f"{r['cores'] // 2}`; with 2 workers that is the default): the batch's scaling in workers | "
                f"{min(r['seconds_1_worker_own_share']):.2f} s | {min(r['seconds_2_workers']):.2f} s | "
                f"**{r['ratio_same_share']:.2f}** |"] if r.get("seconds_1_worker_own_share") else []),
             f"| the same, the whole command (local cluster start and stop included) | "
             f"{r['with_start_seconds'][1]:.2f} s | {r['with_start_seconds'][2]:.2f} s | "
             f"{r['with_start_seconds'][1] / r['with_start_seconds'][2]:.2f} |",
             f"| without the batch: the same commands by a plain pool of threads starting processes (no Dask, no "
             f"record; 2 at once on cores of their own; the machine's ceiling) | {r['plain_pool_seconds'][1]:.2f} s | {r['plain_pool_seconds'][2]:.2f} s "
             f"| {r['plain_pool_seconds'][1] / r['plain_pool_seconds'][2]:.2f} |",
             f"| start of the local cluster alone | {r['cluster_start_seconds'][1]:.2f} s | "
             f"{r['cluster_start_seconds'][2]:.2f} s | |", "",
             f"Of the 30: {r['done']} done, {r['failed']} failed ({r['failed_by_code'] or 'none'}; b9.ply is a point "
             "cloud).", "",
             *([f"Two ratios, because the program has threads of its own (the refinement's pricing, the factorization): "
                f"one worker's meshes run on every core, {min(r['seconds_1_worker']):.2f} s against "
                f"{min(r['seconds_1_worker_own_share']):.2f} s on {r['cores'] // 2} core(s) each, and two workers "
                f"cannot have that gain. Against it the ratio is {r['ratio']:.2f}, at the machine's ceiling (the plain "
                f"pool's {r['plain_pool_seconds'][1] / r['plain_pool_seconds'][2]:.2f}); with the same cores per mesh "
                f"in both, the batch's own scaling in workers, it is {r['ratio_same_share']:.2f}. Pinning each of 2 workers' "
                "programs to a core of its own (the default since commit a9471df) raised the first ratio from 1.57: "
                "unpinned, each program's second thread took turns with the other worker's program.", ""]
               if r.get("seconds_1_worker_own_share") else []),
             f"Overhead of the batch per mesh: **{1000 * r['overhead_per_mesh_seconds']:.1f} ms** — the "
             f"{len(r['small'])} smallest meshes (at most {r['small_max_faces']} faces), "
             f"`{' '.join(r['small_options'])}`: run_batch() on a started 1-worker cluster, "
             f"{min(r['batch_seconds']):.2f} s, against the same program commands run one after the other, "
             f"{min(r['direct_seconds']):.2f} s (best of 3 each); it holds Dask's round trip, the SHA-256 of the "
             "input, the record, the temporary folder and its rename.", ""]
    text = Path(path).read_text() if Path(path).exists() else ""
    start = text.find(SECTION)
    if start >= 0:
        end = text.find("\n## ", start + len(SECTION))
        text = text[:start] + "\n".join(lines) + ("\n" + text[end + 1:] if end >= 0 else "")
    else:
        text = text.rstrip("\n") + "\n\n" + "\n".join(lines)
    tmp = Path(path).with_suffix(".tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


if __name__ == "__main__":
    main()
