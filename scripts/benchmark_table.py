#!/usr/bin/env python3
"""Writes benchmark/RESULTS.md from the JSON files of trivial_connections_benchmark (Google Benchmark).

    python3 scripts/benchmark_table.py --out benchmark/RESULTS.md RESULT.json [RESULT.json ...]
    python3 scripts/benchmark_table.py --section placement --out benchmark/RESULTS.md placement-*.json
    python3 scripts/benchmark_table.py --section python --out benchmark/RESULTS.md python-binding.json
    python3 scripts/benchmark_table.py --section editor --out benchmark/RESULTS.md editor-latency.json

Standard library only. A benchmark is named BACKEND/MESH (BACKEND/program/MESH: the main program as a whole
process); with repetitions, every counter is the median of
the repetitions. When a mesh of a backend appears in several files, the newest file wins. One table per
backend (times, ratios to the reference, memory), then the log-log slopes of every phase against the number
of faces (least squares of log t over the meshes), and a header with the machine and the dates.
BACKEND/placement/MESH (trivial_connections_placement_benchmark) makes the section "Automatic placement";
with --section placement, only that section of --out is written (replaced in place, or inserted before the
scaling slopes), the rest of the file kept as it is. A JSON file of benchmark/python/binding_overhead.py (key
"python_binding") makes the section "The Python binding" (--section python: that section only); one with the key
"editor_latency" (benchmark/editor/latency.mjs, gathered by run_benchmarks.sh --editor) the section "The field
editor" (--section editor).
"""

import argparse
import datetime
import json
import math
import os
import platform
import statistics
import sys

BACKENDS = {
    "ldlt": "Eigen::SimplicialLDLT (header-only default)",
    "cholmod": "CHOLMOD supernodal (Eigen CholmodSupport, -DTRIVIAL_CONNECTIONS_WITH_CHOLMOD=ON)",
    "auto": "Automatic_solver_traits (SimplicialLDLT or CHOLMOD by predicted cost: what the program uses)",
}
FLOOR_NAMES = ["SimplicialLDLT+AMD", "SimplicialLDLT+METIS", "CHOLMOD"]

# (counter, column title) of the build phases, in the order they run
BUILD_PHASES = [
    ("t_mesh_setup", "mesh set-up"),
    ("t_geometry", "geometry"),
    ("t_trees", "trees"),
    ("t_assembly", "assembly"),
    ("t_factorization", "factor."),
    ("t_loop_metric", "loop metric"),
]

# phases whose scaling is fitted: (counter, name)
SLOPE_PHASES = [("t_reference", "reference (Laplacian analysis + factorization)")] + \
    [(c, "build: " + t) for c, t in BUILD_PHASES] + [
    ("t_build", "build (total, measured directly)"),
    ("t_solve", "solve (first singularity set)"),
    ("t_resolve", "re-solve (second set)"),
    ("t_field", "field"),
    ("peak_bytes", "peak memory"),
]

# the genus-0 scaling series: bunny00 and its Loop subdivisions
SERIES_PREFIX = "bunny00"


def load(paths):
    """{backend: {mesh: {"counters": {...}, "date": str, "context": {...}, "error": str|None}}}"""
    results = {}
    contexts = []
    for path in paths:
        with open(path) as f:
            try:
                data = json.load(f)
            except json.JSONDecodeError as e:
                print(f"benchmark_table: skipping {path}: {e}", file=sys.stderr)
                continue
        ctx = data.get("context", {})
        date = ctx.get("date", "")
        runs = {}
        for b in data.get("benchmarks", []):
            if b.get("run_type", "iteration") != "iteration":
                continue
            name = b.get("run_name", b["name"]).split("/iterations")[0].split("/manual_time")[0]
            if "/" not in name:
                continue
            runs.setdefault(name, []).append(b)
        if any(not n.split("/", 1)[1].startswith(PLACEMENT_PREFIX) for n in runs if "/" in n):
            contexts.append((path, ctx))
        for name, reps in runs.items():
            backend, mesh = name.split("/", 1)
            errors = [r.get("error_message", "error") for r in reps if r.get("error_occurred")]
            good = [r for r in reps if not r.get("error_occurred")]
            counters = {}
            if good:
                keys = set().union(*(r.keys() for r in good))
                for k in keys:
                    vals = [r[k] for r in good if isinstance(r.get(k), (int, float)) and not isinstance(r.get(k), bool)]
                    if len(vals) == len(good):
                        counters[k] = statistics.median(vals)
            entry = {"counters": counters, "date": date, "context": ctx, "repetitions": len(good),
                     "error": errors[0] if errors and not good else None}
            old = results.setdefault(backend, {}).get(mesh)
            if old is None or old["date"] <= date:
                results[backend][mesh] = entry
    return results, contexts


def fmt_time(t):
    if t is None or (isinstance(t, float) and math.isnan(t)):
        return "–"
    if t <= 0:
        return "–"
    if t < 1e-3:
        return f"{t * 1e6:.0f} µs"
    if t < 1:
        return f"{t * 1e3:.3g} ms"
    return f"{t:.3g} s"


def with_integers(c, key):
    """a solve time, with the part spent choosing the loop integers in parentheses when there is one"""
    total, integers = c.get(key), c.get(key + "_integers", 0)
    return fmt_time(total) + (f" ({fmt_time(integers)})" if integers and integers >= 1e-4 else "")


CHOLMOD_ORDERINGS = {0: "natural", 1: "given", 2: "AMD", 3: "METIS", 4: "NESDIS", 5: "COLAMD", 6: "postordered"}


def ordering(c):
    """the ordering CHOLMOD's analysis chose for the reference, if reported"""
    o = c.get("ref_cholmod_ordering")
    return "" if o is None else f" ({CHOLMOD_ORDERINGS.get(int(o), int(o))})"


def fmt_num(x, digits=3):
    if x is None or x < 0:
        return "–"
    if x >= 1000:
        return f"{x:,.0f}"
    return f"{x:.{digits}g}"


def fmt_faces(n):
    n = int(round(n))
    if n >= 1_000_000:
        return f"{n / 1e6:.2f}M"
    if n >= 10_000:
        return f"{n / 1e3:.0f}k"
    return f"{n / 1e3:.1f}k"


def slope(points):
    """least-squares slope of log y against log x, with the number of points"""
    pts = [(math.log(x), math.log(y)) for x, y in points if x > 0 and y and y > 0]
    if len(pts) < 2:
        return None, len(pts)
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if sxx == 0:
        return None, len(pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx, len(pts)


def machine():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    ram = "unknown"
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemTotal:"):
                    ram = f"{int(line.split()[1]) / 1024 / 1024:.1f} GiB"
                    break
    except OSError:
        pass
    blas = "unknown"
    for candidate in ("/usr/lib/x86_64-linux-gnu/libblas.so.3", "/usr/lib/aarch64-linux-gnu/libblas.so.3"):
        if os.path.exists(candidate):
            blas = os.path.realpath(candidate)
            break
    return {"nproc": os.cpu_count(), "cpu": cpu, "ram": ram, "kernel": platform.release(), "blas": blas}


def backend_order(b):
    return (list(BACKENDS).index(b) if b in BACKENDS else len(BACKENDS), b)


def mesh_order(item):
    mesh, entry = item
    return (entry["counters"].get("faces", 0), mesh)


PROGRAM_PREFIX = "program/"


CONTROLS_PREFIX = "controls/"


PLACEMENT_PREFIX = "placement/"
PLACEMENT_TITLE = "### Automatic placement"


def pipelines(meshes):
    """the per-mesh pipeline entries of one backend (without the program's, the design controls' and the
    placement's)"""
    return {m: e for m, e in meshes.items() if not m.startswith(PROGRAM_PREFIX) and not m.startswith(CONTROLS_PREFIX)
            and not m.startswith(PLACEMENT_PREFIX)}


def fmt_ratio(x, target):
    """a ratio to the reference, marked when it misses its target"""
    if x is None or x <= 0:
        return "–"
    return fmt_num(x) + ("" if x <= target else " ✗")


def placement_table(results, lines, command):
    """the section "Automatic placement" (BACKEND/placement/MESH), with its own measurement line"""
    rows = [(b, m[len(PLACEMENT_PREFIX):], e) for b in sorted(results, key=backend_order)
            for m, e in results[b].items() if m.startswith(PLACEMENT_PREFIX)]
    if not rows:
        return
    rows.sort(key=lambda r: (backend_order(r[0]), r[2]["counters"].get("faces", 0), r[1]))
    ctxs = [e["context"] for _, _, e in rows]
    dates = sorted({c.get("date", "")[:10] for c in ctxs if c.get("date")})
    commits = sorted({c.get("commit") + (f" (binary built {c['built']})" if c.get("built") else "")
                      for c in ctxs if c.get("commit")})
    m = machine()
    lines.append(PLACEMENT_TITLE)
    lines.append("")
    lines.append(f"Measured {', '.join(dates) if dates else 'on an unknown date'} on {m['nproc']} cores ({m['cpu']})"
                 + (f", commit {', '.join(commits)}" if commits else "")
                 + f", by `{command}` (`benchmark/Trivial_connections/benchmark_placement.cpp`); "
                 "`+modified`: include/ differed from that commit.")
    lines.append("")
    lines.append("Per mesh, in one run, n = 4: the solver is built (`build`, with the backend); `place_singularities` "
                 "places the singularities of the smoothest 4-direction field (`placement`, with the number of "
                 "eigensolver (LOBPCG) iterations, `Placement_report::iterations`); the trivial connection is solved with them "
                 "(`solve`); `principal_curvature_guide` + `place_singularities` with `alignment_guide` give the "
                 "curvature-aligned placement (`aligned`, guide included, its time in parentheses); then, for n = 1, "
                 "2 and 4, the refinement as users run it (second table below). Then the **reference** of the tables "
                 "above is timed: "
                 "analysis + factorization of the same mesh's vertex Laplacian with the same backend. "
                 "The placement factors its complex face pencil A + σB (one unknown per face, about twice the "
                 "vertices) with Eigen's `SimplicialLDLT` whatever the backend; `pencil factor.` and `pencil solve` "
                 "time that factorization and one solve with it (the median of 3) apart (the library's internal classes, as "
                 "`place_singularities` calls them), and `split` divides the placement into that factorization, "
                 "the eigensolver's solves (iterations × one solve) and the rest (assembly of the pencil, "
                 "normalisations, reading the singularities off the field). Sing.: singularities placed (smoothest, "
                 "aligned). Medians over the repetitions (`reps`).")
    lines.append("")
    lines.append("Issue targets (reported, not asserted): end-to-end = (build + placement + solve) / reference ≤ 3 "
                 "on 50k–1.2M faces; refinement to a local minimum / placement ≤ 1 (issue 38) on every mesh, for "
                 "n = 1, 2, 4; ✗ marks a ratio above its target.")
    lines.append("")
    ok = [(b, mesh, e["counters"]) for b, mesh, e in rows if not e["error"]]
    in_range = [r for r in ok if 50_000 <= r[2].get("faces", 0) <= 1_300_000]
    refined = [(c.get(f"r_refine_over_place_n{n}"), c.get(f"local_minimum_n{n}"))
               for _, _, c in ok for n in REFINED_ORDERS if c.get(f"t_refine_n{n}") is not None]
    if in_range or refined:
        targets = []
        if in_range:
            ends = [c.get("r_end_to_end", 0) for _, _, c in in_range]
            met_end = sum(1 for x in ends if 0 < x <= 3)
            targets.append(f"end-to-end ≤ 3 met on {met_end} of {len(in_range)} runs (mesh × backend) "
                           f"of 50k–1.2M faces (ratios {fmt_num(min(ends))}–{fmt_num(max(ends))})")
        if refined:
            ratios = [r for r, _ in refined if r is not None and r >= 0]
            met = sum(1 for r in ratios if r <= 1)
            minima = sum(1 for _, lm in refined if lm)
            targets.append(f"refinement / placement ≤ 1 met on {met} of {len(refined)} runs (mesh × backend × n)"
                           + (f" (ratios {fmt_num(min(ratios))}–{fmt_num(max(ratios))})" if ratios else "")
                           + f", a local minimum reached on {minima} of {len(refined)}")
        lines.append("**Targets**: " + "; ".join(targets) + ".")
        lines.append("")
    if ok:
        factor = [c.get("r_pencil_factorization", 0) for _, _, c in ok]
        share = [c.get("t_pencil_factorization", 0) / c["t_place"] for _, _, c in ok if c.get("t_place", 0) > 0]
        solves = [c.get("eigensolver_iterations", 0) * c.get("t_pencil_solve", 0) / c["t_place"]
                  for _, _, c in ok if c.get("t_place", 0) > 0]
        iterations = [c.get("eigensolver_iterations", 0) for _, _, c in ok]
        capped = sorted({mesh for _, mesh, c in ok if c.get("eigensolver_iterations", 0) >= 100})
        aligned = [c.get("r_place_aligned", 0) for _, _, c in ok]
        lines.append(f"**Where the time goes**: the factorization of the complex face pencil alone is "
                     f"{fmt_num(min(factor))}–{fmt_num(max(factor))} × the reference ({100 * min(share):.0f}–"
                     f"{100 * max(share):.0f} % of the placement); the eigensolver's solves take "
                     f"{100 * min(solves):.0f}–{100 * max(solves):.0f} % ({min(iterations):.0f}–{max(iterations):.0f} "
                     "iterations" + (f"; 100 is the eigensolver's cap, reached on {', '.join(capped)}" if capped else "")
                     + f"). The aligned placement (guide, one factorization, one solve) is "
                     f"{fmt_num(min(aligned))}–{fmt_num(max(aligned))} × the reference. The split is approximate: "
                     "its parts are timed apart, on a machine shared with other jobs while measuring.")
        lines.append("")
    head = ["mesh", "backend", "faces", "genus", "reference", "build", "placement (iter.)", "solve",
            "aligned (guide)", "sing. (aligned)", "pencil factor.", "pencil solve",
            "split: factor. / solves / rest", "end-to-end / ref", "placement / ref", "aligned / ref",
            "aligned end-to-end / ref", "pencil factor. / ref", "peak B/face", "reps"]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---", "---"] + ["---:"] * (len(head) - 2)) + "|")
    for b, mesh, e in rows:
        c = e["counters"]
        if e["error"]:
            lines.append(f"| {mesh} | {b} | " + " | ".join(["–"] * (len(head) - 3)) + f" | error: {e['error']} |")
            continue
        place = c.get("t_place", 0)
        split = "–"
        if place > 0:
            factor = c.get("t_pencil_factorization", 0) / place
            solves = c.get("eigensolver_iterations", 0) * c.get("t_pencil_solve", 0) / place
            split = f"{100 * factor:.0f} / {100 * solves:.0f} / {100 * (1 - factor - solves):.0f} %"
        lines.append("| " + " | ".join([
            mesh, b, fmt_faces(c.get("faces", 0)), f"{c.get('genus', 0):.0f}", fmt_time(c.get("t_reference")),
            fmt_time(c.get("t_build")), f"{fmt_time(place)} ({c.get('eigensolver_iterations', 0):.0f})",
            fmt_time(c.get("t_solve")),
            f"{fmt_time(c.get('t_guide', 0) + c.get('t_place_aligned', 0))} ({fmt_time(c.get('t_guide'))})",
            f"{c.get('singularities', 0):.0f} ({c.get('singularities_aligned', 0):.0f})",
            fmt_time(c.get("t_pencil_factorization")), fmt_time(c.get("t_pencil_solve")), split,
            fmt_ratio(c.get("r_end_to_end"), 3), fmt_num(c.get("r_place")), fmt_num(c.get("r_place_aligned")),
            fmt_num(c.get("r_end_to_end_aligned")), fmt_num(c.get("r_pencil_factorization")),
            fmt_num(c.get("peak_bytes_per_face"), 4),
            str(e["repetitions"])]) + " |")
    lines.append("")
    refinement_table(rows, lines)


REFINED_ORDERS = (1, 2, 4)
REFINEMENT_STOPS = {0: "local minimum", 1: "budget of trials spent", 2: "predicted moves rejected"}


def fmt_energy(x):
    return "–" if x is None else f"{x:.5g}"


def refinement_table(rows, lines):
    """per mesh, backend and n: place_singularities, then refine_singularities from it to a local minimum"""
    if not any(e["counters"].get(f"t_refine_n{n}") is not None for _, _, e in rows for n in REFINED_ORDERS):
        return
    lines.append("**Refinement to a local minimum** (issue 38), per mesh and n = 1, 2, 4, on the same prefactored "
                 "solver: `place_singularities(solver, out, symmetry_order(n))` (`placement`; for n = 4 the placement "
                 "of the table above), then `refine_singularities(solver, placed, x, cancel_pairs(true, "
                 "symmetry_order(n)))` from that placement, with no budget, as users run it (`refinement`, its "
                 "first solve of the placed set included). Singularities and energy (`energy + guidance_energy` of "
                 "the solve, `Refinement_report::energy_before`/`energy_after`): placed → refined. Rounds: rounds of "
                 "moves accepted together (trial solves); moves: singularities moved (of which cancellations of a "
                 "unit of 1/n of a pair). Local minimum: whether it stopped because no single move or cancellation "
                 "lowers the energy (otherwise why it stopped, `Refinement_stop`). Target of issue 38 (reported, not "
                 "asserted): refinement / placement ≤ 1; ✗ marks a miss.")
    lines.append("")
    head = ["mesh", "backend", "faces", "genus", "n", "placement", "refinement", "refinement / placement",
            "sing. placed → refined", "energy placed → refined", "rounds (trials)", "moves (cancel.)",
            "local minimum", "refinement / ref", "reps"]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---", "---"] + ["---:"] * (len(head) - 3) + ["---:"]) + "|")
    for b, mesh, e in rows:
        c = e["counters"]
        if e["error"]:
            continue
        for n in REFINED_ORDERS:
            g = lambda k: c.get(f"{k}_n{n}")
            if g("t_refine") is None:
                continue
            local = g("local_minimum")
            stop = g("stop")
            minimum = "yes" if local else ("no" + (f" ({REFINEMENT_STOPS.get(int(stop), int(stop))})"
                                                   if stop is not None else ""))
            lines.append("| " + " | ".join([
                mesh, b, fmt_faces(c.get("faces", 0)), f"{c.get('genus', 0):.0f}", str(n),
                fmt_time(g("t_place")), fmt_time(g("t_refine")), fmt_ratio(g("r_refine_over_place"), 1),
                f"{g('singularities_before') or 0:.0f} → {g('singularities_after') or 0:.0f}",
                f"{fmt_energy(g('energy_before'))} → {fmt_energy(g('energy_after'))}",
                f"{g('rounds') or 0:.0f} ({g('trials') or 0:.0f})",
                f"{g('moves') or 0:.0f} ({g('cancellations') or 0:.0f})",
                minimum, fmt_num(g("r_refine")), str(e["repetitions"])]) + " |")
    lines.append("")


PYTHON_TITLE = "### The Python binding"


def python_table(bindings, lines, command):
    """the section "The Python binding" from the newest JSON file of benchmark/python/binding_overhead.py"""
    if not bindings:
        return
    data = max(bindings, key=lambda d: d.get("date", ""))
    lines.append(PYTHON_TITLE)
    lines.append("")
    lines.append(f"Measured {data.get('date', '')[:10]}"
                 + (f", commit {data['commit']}" if data.get("commit") else "")
                 + f", backend `{data.get('backend', 'auto')}`, by `{command}` (`benchmark/python/binding_overhead.py`, "
                 "everything in one Python process; medians over the repetitions). Build: `Solver(V, F)` timed in "
                 "Python against what a C++ program holding the same arrays does, `triangle_soup_to_mesh()` into a "
                 "`Surface_mesh` then the solver's constructor, both timed in C++ by "
                 "`trivial_connections._reference_build`; the two alternate and each starts with the freed heap given "
                 "back to the system. **arrays** = Python / (soup to mesh + constructor), the target (≤ 1: from arrays "
                 "no dearer than from a Surface_mesh made of them); **mesh** = Python / constructor alone, for a "
                 "program that holds a Surface_mesh already: the arrays carry no adjacency, and finding it (the soup's "
                 "validation) costs more than reading it out of a halfedge structure, which the constructor does. "
                 "The module builds its solver from the soup's validated connectivity rather than from the "
                 "Surface_mesh it also makes, and makes that mesh on a second thread at the lowest priority while the "
                 "constructor runs: on a mesh whose constructor keeps both cores busy (cheese, genus 133, mostly the "
                 "loop metric) it finds no idle time, and the two paths are even (0.99–1.06 over the runs of "
                 "2026-12-03). Solve: `Solver.solve()` timed in Python against the C++ `solve()` + "
                 "`compute_field()` inside it (target ≤ 1.05 at 75k faces).")
    lines.append("")
    lines.append("| mesh | faces | Solver(V, F) | C++: soup to mesh | C++: constructor | arrays | mesh "
                 "| solve, Python | C++ solve + field | solve ratio | reps |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in data["python_binding"]:
        cpp_build = r["soup_to_mesh"] + r["constructor"]
        lines.append(f"| {r['mesh']} | {fmt_faces(r['faces'])} | {fmt_time(r['python_build'])} "
                     f"| {fmt_time(r['soup_to_mesh'])} | {fmt_time(r['constructor'])} "
                     f"| {r['python_build'] / cpp_build:.2f} | {r['python_build'] / r['constructor']:.2f} "
                     f"| {fmt_time(r['python_solve'])} | {fmt_time(r['cpp_solve'])} "
                     f"| {r['python_solve'] / r['cpp_solve']:.3f} | {r['repetitions']} |")
    lines.append("")


def load_side_results(paths):
    """the contents of the JSON files of benchmark/python/binding_overhead.py and of the editor's latency among
    `paths`, and the other paths"""
    bindings, editors, others = [], [], []
    for path in paths:
        try:
            with open(path) as f:
                data = json.load(f)
        except (OSError, json.JSONDecodeError):
            others.append(path)  # load() reports it
            continue
        if isinstance(data, dict) and "python_binding" in data:
            bindings.append(data)
        elif isinstance(data, dict) and "editor_latency" in data:
            editors.append(data)
        else:
            others.append(path)
    return bindings, editors, others


EDITOR_TITLE = "### The field editor"


def editor_table(editors, lines, command):
    """the section "The field editor" from the newest JSON file of the editor's latency runs"""
    if not editors:
        return
    data = max(editors, key=lambda d: d.get("date", ""))
    runs = data["editor_latency"]
    lines.append(EDITOR_TITLE)
    lines.append("")
    gl = sorted({r.get("gl", "?") for r in runs})
    browser = sorted({r.get("browser", "?") for r in runs})
    lines.append(f"Measured {data.get('date', '')[:10]}" + (f", commit {data['commit']}" if data.get("commit") else "")
                 + f", by `{command}` (`benchmark/editor/latency.mjs`): the editor in headless Chromium "
                 f"{', '.join(browser)}, GL {', '.join(gl)}, 1200 x 900 pixels, n = 4. Each run drags one singularity "
                 "to another vertex 100 times with the mouse; an edit is timed from the pointer's release to the frame "
                 "read back: the server's solve on the prefactored solver, the transfer (binary, one float32 angle per "
                 "face) and the draw. **server**: request to response, of which **C++** is the library's solve and "
                 "field; **draw**: after the response, until a pixel of the page's field layer is read back. The page "
                 "draws the field in screen space, in a 2D canvas over the WebGL one: a glyph (the n directions) in "
                 "every cell of 16 pixels whose centre is on the mesh, for the face under it, so an edit redraws a few "
                 "hundred to a few thousand glyphs whatever the zoom and the mesh, and the WebGL canvas (the shaded "
                 "mesh, and a buffer of face numbers read back for the glyphs' faces) only when the camera moves. "
                 "**glyphs**: their number at that view; **field shown**: the share of the blocks of 24 x 24 pixels "
                 "wholly on the mesh that hold the glyphs' ink. Zoom 1 shows the whole mesh; zoom 6 brings the camera "
                 "six times closer. `fandisk_large_split` is CGAL's `fandisk_large.off` with every triangle split in "
                 "four at its edge midpoints (`benchmark/editor/split_faces.py`: CGAL's data set has no mesh of 100k "
                 "faces). Target (issue 22, issue 39): median ≤ 50 ms, 95th percentile ≤ 100 ms at 100k faces; the "
                 "page opens in under 3 s after the server has factored. This machine has no GPU: SwiftShader draws "
                 "on the same two cores as the server.")
    lines.append("")
    lines.append("| mesh | faces | zoom | glyphs | field shown | median | 95th percentile | server (median) "
                 "| C++ solve + field | draw (median) | page opens | edits |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    ms = lambda x: f"{x:.0f} ms" if x >= 10 else f"{x:.1f} ms"
    for r in runs:
        st = r["stats"]
        lines.append(f"| {os.path.basename(r['mesh'])} | {fmt_faces(r['faces'])} | {r['zoom']:g} | "
                     f"{r.get('glyphs', '?')} | "
                     + (f"{100 * r['coverage']:.0f} % " if "coverage" in r else "? ")  # runs before the screen-space glyphs
                     + f"| {ms(st['total']['median'])} | {ms(st['total']['p95'])} "
                     f"| {ms(st['server']['median'])} | {ms(st['solve']['median'])} | {ms(st['draw']['median'])} "
                     f"| {r['opened']:.2f} s | {r['edits']} |")
    lines.append("")


def replace_section(path, title, section):
    """replaces the section `title` of the file (up to the next ### heading) by the lines `section`, or inserts it
    before the scaling slopes (else before the integer choice, else at the end)"""
    with open(path) as f:
        old = f.read().split("\n")
    while old and not old[-1].strip():
        old.pop()
    heading = [i for i, line in enumerate(old) if line.startswith("### ")]
    if title in old:
        start = old.index(title)
        end = next((i for i in heading if i > start), len(old))
    else:
        start = next((i for i in heading if old[i].startswith("### Scaling")),
                     next((i for i in heading if old[i].startswith("### Integer choice")), len(old)))
        end = start
    body = list(section)
    while body and not body[-1].strip():
        body.pop()
    if end < len(old):
        body.append("")
    elif start > 0 and old[start - 1].strip():
        body.insert(0, "")
    new = old[:start] + body + old[end:]
    with open(path, "w") as f:
        f.write("\n".join(new) + "\n")


def controls_table(results, lines):
    rows = [(b, m[len(CONTROLS_PREFIX):], e) for b in sorted(results, key=backend_order)
            for m, e in results[b].items() if m.startswith(CONTROLS_PREFIX)]
    if not rows:
        return
    rows.sort(key=lambda r: (backend_order(r[0]), r[2]["counters"].get("faces", 0)))
    lines.append("### Design controls: constrained and guided faces")
    lines.append("")
    lines.append("A solver with 20 constrained and 10 guided faces (n = 4), one solve, a re-solve with new directions "
                 "on the same faces, `set_constraints()` with 5 constrained faces dropped and 10 added (links kept "
                 "in the factor, links dropped from the dense block, new links bordered: one forward substitution "
                 "each), and a solve after it; against the same reference factorization as above. Expected: "
                 "re-solve and set_constraints far below the reference.")
    lines.append("")
    head = ["mesh", "backend", "faces", "reference", "build", "solve", "re-solve", "set_constraints",
            "solve after", "links (bordered, new)", "build / ref", "re-solve / ref", "set_constraints / ref"]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---", "---"] + ["---:"] * (len(head) - 2)) + "|")
    for b, mesh, e in rows:
        c = e["counters"]
        if e["error"]:
            lines.append(f"| {mesh} | {b} | " + " | ".join(["–"] * (len(head) - 3)) + f" | error: {e['error']} |")
            continue
        lines.append("| " + " | ".join([
            mesh, b, fmt_faces(c.get("faces", 0)), fmt_time(c.get("t_reference")), fmt_time(c.get("t_build")),
            fmt_time(c.get("t_solve")), fmt_time(c.get("t_resolve")), fmt_time(c.get("t_set_constraints")),
            fmt_time(c.get("t_solve_after_set")),
            f"{int(c.get('links_after_set', 0))} ({int(c.get('links_outside_the_factor', 0))}, "
            f"{int(c.get('new_forward_substitutions', 0))})",
            fmt_num(c.get("r_build")), fmt_num(c.get("r_resolve")), fmt_num(c.get("r_set_constraints"))]) + " |")
    lines.append("")


def program_table(results, lines):
    rows = [(b, m[len(PROGRAM_PREFIX):], e) for b in sorted(results, key=backend_order)
            for m, e in results[b].items() if m.startswith(PROGRAM_PREFIX)]
    if not rows:
        return
    lines.append("### The main program as a whole process")
    lines.append("")
    lines.append("`trivial_connections MESH.off --singularities S --n 1 --connection C --field F` (read, solve, field, "
                 "both files written), timed as a child process, against reading the same OFF file with CGAL "
                 "(`read_polygon_mesh` into a `Surface_mesh`) plus one analysis + factorization of the mesh's "
                 "Laplacian with the program's backend (the choice by predicted cost whenever CHOLMOD is installed). "
                 "Laplacian: building it from the mesh read (cotan weights, then the sparse matrix). "
                 "Targets: ratio ≤ 2; program / (read + Laplacian + floor) ≤ 1.0 (issue 20; the floor as in the "
                 "section above; without the Laplacian in the next column). The program's phases are its own "
                 "`--progress` times (10 ms resolution) over the floor.")
    lines.append("")
    head = ["mesh", "backend", "faces", "program", "program peak", "CGAL read", "reference factorization",
            "program / (read + reference)", "Laplacian", "floor", "program / (read + Laplacian + floor)",
            "program / (read + floor)", "program phases / floor"]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---", "---"] + ["---:"] * (len(head) - 2)) + "|")
    for b, mesh, e in rows:
        c = e["counters"]
        if e["error"]:
            lines.append(f"| {mesh} | {b} | " + " | ".join(["–"] * (len(head) - 3)) + f" | error: {e['error']} |")
            continue
        peak = c.get("program_peak_bytes")
        lines.append("| " + " | ".join([mesh, b, fmt_faces(c.get("faces", 0)), fmt_time(c.get("t_program")),
                                         f"{peak / 2**30:.2f} GiB" if peak and peak > 0 else "–",
                                         fmt_time(c.get("t_read")), fmt_time(c.get("t_reference")),
                                         fmt_num(c.get("r_program")), fmt_time(c.get("t_laplacian")), floor_cell(c),
                                         fmt_num(c.get("r_program_floor")),
                                         fmt_num(c.get("r_program_floor_without_laplacian")),
                                         program_phases(c)]) + " |")
    lines.append("")


def program_phases(c):
    """the program's --progress phases over the floor, in the order they run (10 ms resolution)"""
    order = ["reading_mesh", "mesh_setup", "geometry", "trees", "assembly", "factorization", "loop_metric",
             "solve", "field", "writing_files"]
    parts = [(k[len("r_program_"):-len("_floor")], v) for k, v in c.items()
             if k.startswith("r_program_") and k.endswith("_floor") and k != "r_program_floor"]
    parts.sort(key=lambda p: (order.index(p[0]) if p[0] in order else len(order), p[0]))
    return ", ".join(f"{name.replace('_', ' ')} {fmt_num(v)}" for name, v in parts) or "–"


def floor_cell(c):
    """the floor's time and which factorization it was"""
    if c.get("t_floor") is None:
        return "–"
    b = int(c.get("floor_backend", -1))
    return fmt_time(c.get("t_floor")) + (f" ({FLOOR_NAMES[b]})" if 0 <= b < len(FLOOR_NAMES) else "")


FLOOR_TITLE = "### Against the fastest factorization of the machine"


def floor_table(results, lines, contexts=(), command=""):
    """every backend against the fastest factorization of the machine (issue 20)"""
    rows = [(b, mesh, e) for b in sorted(results, key=backend_order)
            for mesh, e in sorted(pipelines(results[b]).items(), key=mesh_order)
            if not e["error"] and e["counters"].get("t_floor")]
    if not rows:
        return
    lines.append(FLOOR_TITLE)
    lines.append("")
    if command:
        m = machine()
        dates = sorted({ctx.get("date", "")[:10] for _, ctx in contexts if ctx.get("date")})
        commits = sorted({ctx.get("commit") for _, ctx in contexts if ctx.get("commit")})
        lines.append(f"Measured {', '.join(dates) if dates else 'on an unknown date'} on {m['nproc']} cores "
                     f"({m['cpu']}, BLAS `{m['blas']}`)" + (f", commit {', '.join(commits)}" if commits else "")
                     + f", by `{command}`.")
        lines.append("")
    lines.append("The **floor**: per mesh, the fastest of every sparse Cholesky of the same Laplacian the build has, "
                 "each with its best ordering, timed in the same run as the reference (analysis, ordering included, "
                 "+ factorization): SimplicialLDLT with AMD, SimplicialLDLT with METIS (libmetis-dev), supernodal "
                 "CHOLMOD with its own ordering choice (on the BLAS above). Target of issue 20 (reported, not "
                 "asserted): end to end of the library ≤ 1.2 × the floor at every size ≥ 50k faces; ✗ marks a miss. "
                 "A ratio below 1 means the floor's orderings are not the best ones: the solver's factorization "
                 "(Eigen's AMD order, given to CHOLMOD) can beat CHOLMOD's own choice.")
    lines.append("")
    big = [(b, c["counters"]) for b, _, c in rows if c["counters"].get("faces", 0) >= 5e4]
    for b in sorted({b for b, _ in big}, key=backend_order):
        r = [c.get("r_end_to_end_floor", 0) for bb, c in big if bb == b]
        met = sum(1 for x in r if x <= 1.2)
        lines.append(f"- **{b}**: end to end ≤ 1.2 × floor on {met} of {len(r)} meshes of ≥ 50k faces "
                     f"(ratios {fmt_num(min(r))}–{fmt_num(max(r))}).")
    lines.append("")
    head = ["mesh", "backend", "faces", "floor", "own reference", "build", "end to end", "build / floor",
            "end-to-end / floor"]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---", "---"] + ["---:"] * (len(head) - 2)) + "|")
    for b, mesh, e in rows:
        c = e["counters"]
        end = c.get("r_end_to_end_floor")
        mark = " ✗" if end is not None and c.get("faces", 0) >= 5e4 and end > 1.2 else ""
        lines.append("| " + " | ".join([mesh, b, fmt_faces(c.get("faces", 0)), floor_cell(c),
                                         fmt_time(c.get("t_reference")), fmt_time(c.get("t_build")),
                                         fmt_time(c.get("t_build", 0) + c.get("t_solve", 0) + c.get("t_field", 0)),
                                         fmt_num(c.get("r_build_floor")), fmt_num(end) + mark]) + " |")
    lines.append("")
    programs = [(b, mesh, e) for b in sorted(results, key=backend_order) for mesh, e in sorted(results[b].items())
                if mesh.startswith(PROGRAM_PREFIX) and not e["error"] and e["counters"].get("t_floor")]
    if programs:
        lines.append("The main program as a whole process (as in its section; target of issue 20: program / (CGAL "
                     "read + Laplacian + floor) ≤ 1.0 from 50k to 4.8M faces, and 4.8M faces within 30 s), and its "
                     "own `--progress` phases over the floor:")
        lines.append("")
        head = ["mesh", "backend", "faces", "program", "CGAL read", "Laplacian", "floor",
                "program / (read + Laplacian + floor)", "program / (read + floor)", "program phases / floor"]
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "|".join(["---", "---"] + ["---:"] * (len(head) - 3) + ["---"]) + "|")
        for b, mesh, e in sorted(programs, key=lambda r: r[2]["counters"].get("faces", 0)):
            c = e["counters"]
            r = c.get("r_program_floor")
            mark = " ✗" if r is not None and r > 1.0 else ""
            over_30s = " ✗" if c.get("faces", 0) > 4e6 and c.get("t_program", 0) > 30 else ""
            lines.append("| " + " | ".join([mesh[len(PROGRAM_PREFIX):], b, fmt_faces(c.get("faces", 0)),
                                             fmt_time(c.get("t_program")) + over_30s, fmt_time(c.get("t_read")),
                                             fmt_time(c.get("t_laplacian")), floor_cell(c), fmt_num(r) + mark,
                                             fmt_num(c.get("r_program_floor_without_laplacian")),
                                             program_phases(c)]) + " |")
        lines.append("")


def backend_table(backend, meshes, lines):
    lines.append(f"### {backend}: {BACKENDS.get(backend, backend)}")
    lines.append("")
    head = ["mesh", "faces", "genus", "bnd loops", "sing.", "floor", "reference"] + [t for _, t in BUILD_PHASES] + \
        ["build", "solve", "re-solve", "field", "end-to-end / floor", "re-solve / floor", "end-to-end / ref",
         "peak B/face", "ref peak B/face", "ref factor B/face", "ref GFlop", "faults/face", "floor faults/face",
         "reps"]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---"] + ["---:"] * (len(head) - 1)) + "|")
    for mesh, e in sorted(pipelines(meshes).items(), key=mesh_order):
        c = e["counters"]
        if e["error"]:
            lines.append(f"| {mesh} | " + " | ".join(["–"] * (len(head) - 2)) + f" | error: {e['error']} |")
            continue
        row = [mesh, fmt_faces(c.get("faces", 0)), f"{c.get('genus', 0):.0f}", f"{c.get('boundary_loops', 0):.0f}",
               f"{c.get('singularities', 0):.0f}", floor_cell(c), fmt_time(c.get("t_reference")) + ordering(c)]
        row += [fmt_time(c.get(k)) for k, _ in BUILD_PHASES]
        floor = c.get("t_floor")
        row += [fmt_time(c.get("t_build")), with_integers(c, "t_solve"), with_integers(c, "t_resolve"),
                fmt_time(c.get("t_field")), fmt_num(c.get("r_end_to_end_floor")),
                fmt_num(c["t_resolve"] / floor) if floor and c.get("t_resolve") is not None else "–",
                fmt_num(c.get("r_end_to_end")),
                fmt_num(c.get("peak_bytes_per_face"), 4), fmt_num(c.get("ref_peak_bytes_per_face"), 4),
                fmt_num(c.get("ref_factor_bytes_per_face"), 4), fmt_num(c.get("ref_factor_gflops"), 3),
                fmt_num(c.get("page_faults_per_face"), 3), fmt_num(c.get("floor_page_faults_per_face"), 3),
                str(e["repetitions"])]
        lines.append("| " + " | ".join(row) + " |")
    lines.append("")


def slope_table(results, lines):
    backends = [b for b in sorted(results, key=backend_order) if results[b]]
    head = ["phase"]
    for b in backends:
        head += [f"{b}: all meshes", f"{b}: {SERIES_PREFIX} series"]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---"] + ["---:"] * (len(head) - 1)) + "|")
    for key, title in SLOPE_PHASES:
        row = [title]
        any_value = False
        for b in backends:
            ok = [e for e in pipelines(results[b]).values() if not e["error"]]
            for subset in (ok, [e for m, e in results[b].items() if m.startswith(SERIES_PREFIX) and not e["error"]]):
                s, n = slope([(e["counters"].get("faces", 0), e["counters"].get(key)) for e in subset])
                if s is None:
                    row.append("–")
                else:
                    faces = [e["counters"]["faces"] for e in subset if e["counters"].get(key, 0) > 0]
                    row.append(f"{s:.2f} ({n} meshes, {fmt_faces(min(faces))}–{fmt_faces(max(faces))})")
                    any_value = True
        if any_value or key.startswith("t_"):
            lines.append("| " + " | ".join(row) + " |")
    lines.append("")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("json", nargs="+", help="Google Benchmark JSON outputs")
    ap.add_argument("--out", default="benchmark/RESULTS.md")
    ap.add_argument("--command", default="bash scripts/run_benchmarks.sh", help="how the numbers were made")
    ap.add_argument("--section", choices=["placement", "floor", "python", "editor"],
                    help="write only this section of --out (replaced in place, the rest of the file kept)")
    args = ap.parse_args()

    bindings, editors, benchmark_files = load_side_results([p for p in args.json if os.path.exists(p)])
    sections = {"editor": (editor_table, editors, EDITOR_TITLE, "editor latency"),
                "python": (python_table, bindings, PYTHON_TITLE, "binding_overhead.py")}
    if args.section in sections:
        table, data, title, what = sections[args.section]
        section = []
        table(data, section, f"{args.command} --{args.section}")
        if not section:
            sys.exit(f"benchmark_table: no {what} results in " + " ".join(args.json))
        if not os.path.exists(args.out):
            sys.exit(f"benchmark_table: {args.out} missing (run the suite first)")
        replace_section(args.out, title, section)
        print(f"benchmark_table: wrote the section {title[4:]!r} of {args.out}")
        return
    results, contexts = load(benchmark_files)
    if not any(results.values()):
        sys.exit("benchmark_table: no benchmark results in " + " ".join(args.json))
    if args.section:
        # one section rewritten in place, the rest of the file kept
        section = []
        if args.section == "floor":
            title = FLOOR_TITLE
            floor_table(results, section, contexts, args.command + " --floor")
        else:
            title = PLACEMENT_TITLE
            placement_table(results, section, args.command + " --placement")
        if not section:
            sys.exit(f"benchmark_table: no {args.section} results in " + " ".join(args.json))
        if not os.path.exists(args.out):
            sys.exit(f"benchmark_table: {args.out} missing (run the suite first)")
        replace_section(args.out, title, section)
        print(f"benchmark_table: wrote the section {title[4:]!r} of {args.out}")
        return
    m = machine()
    dates = sorted({ctx.get("date", "")[:10] for _, ctx in contexts if ctx.get("date")})
    commits = sorted({ctx.get("commit") + (f" (binary built {ctx['built']})" if ctx.get("built") else "")
                      for _, ctx in contexts if ctx.get("commit")})
    lines = []
    lines.append("# Benchmark results")
    lines.append("")
    lines.append(f"Written by `scripts/benchmark_table.py` from the JSON of `{args.command}` "
                 "(see `benchmark/Trivial_connections/benchmark_trivial_connections.cpp` for what is measured).")
    lines.append("")
    lines.append(f"- **Machine**: {m['nproc']} cores, {m['cpu']}, {m['ram']} RAM, Linux {m['kernel']}; "
                 f"BLAS used by CHOLMOD: `{m['blas']}`. The machine was shared with other jobs while measuring.")
    lines.append(f"- **Measured**: {', '.join(dates) if dates else 'unknown date'}"
                 + (f", commit {', '.join(commits)}" if commits else "")
                 + f"; table written {datetime.date.today().isoformat()}.")
    lines.append("- **Per mesh, in one run**: the solver is built (phases from the `progress` callback, the total "
                 "measured directly), solved for one singularity set (Poincaré–Hopf on every closed component), "
                 "re-solved on the same factorization for another set, and the field is extracted; then the "
                 "**reference** is timed: analysis + numeric factorization of the same mesh's vertex Laplacian "
                 "(edge weights 1/w_e of the solver, one vertex pinned per component) with the same sparse backend, "
                 "called as a user would (`SimplicialLDLT` with its AMD ordering; CHOLMOD with its default "
                 "ordering choice, shown in parentheses when reported). Solve and re-solve show in parentheses the part spent choosing the loop "
                 "integers (when ≥ 0.1 ms). "
                 "Every timed section, the solver's and each reference's, starts with the freed heap given back to "
                 "the system (`malloc_trim`), so that each pays for the new memory it touches (on a virtual machine "
                 "a first touch costs about 11 µs per 4 KiB page; runs before 2026-12-03 left the reference the "
                 "warm memory of its untimed assembly). "
                 "Timings are medians over the repetitions (`reps`).")
    lines.append("- **The floor** (issue 20): per mesh, the fastest factorization of the same Laplacian that the build "
                 "has, each backend with its best ordering (SimplicialLDLT with AMD or METIS, supernodal CHOLMOD with its "
                 "own choice), timed in the same run; the backend that won is named in parentheses. **Ratios**: "
                 "end-to-end / floor = (build + solve + field) / floor; re-solve / floor = re-solve / floor; "
                 "end-to-end / ref = (build + solve + field) / the reference of the table's own backend.")
    lines.append("- **Memory**: peak B/face = (VmHWM − resident size just before the build) / faces, over build, two "
                 "solves and the field (the peak is reset through `/proc/self/clear_refs` before each mesh); ref peak "
                 "B/face = the same for the reference (matrix + factorization); ref factor B/face = nnz(L) × 12 / faces "
                 "(8-byte value + 4-byte index per nonzero of the reference factor; for CHOLMOD its `lnz`); ref GFlop = "
                 "the work of the reference factorization, the sum over the columns of L of nnz(column)² (diagonal "
                 "included, as CHOLMOD counts), in 10⁹. Faults/face: minor page faults (first touches of 4 KiB pages, "
                 "or 2 MiB ones) over build, solves and field, and over the floor's analysis + factorization, per "
                 "face (runs from 2026-12-03 on).")
    lines.append("- A phase shown as – was not reported (phase times come from the solver's progress callback). "
                 "Build type Release (-O3); Google Benchmark's \"Library was built as DEBUG\" warning is about "
                 "Debian's libbenchmark itself, not the code measured.")
    lines.append("- Meshes: CGAL's data set; `NAME_loopK` is `NAME.off` after K steps of Loop subdivision "
                 "(`CGAL::Subdivision_method_3`, made by the benchmark and cached outside the repository).")
    lines.append("")
    for backend in sorted(results, key=backend_order):
        if pipelines(results[backend]):
            backend_table(backend, results[backend], lines)
    floor_table(results, lines)
    program_table(results, lines)
    controls_table(results, lines)
    placement_table(results, lines, args.command + " --placement")
    python_table(bindings, lines, args.command + " --python")
    editor_table(editors, lines, args.command + " --editor")
    lines.append("### Scaling: log–log slopes")
    lines.append("")
    lines.append("Least-squares slope of log(time) (or log(peak memory)) against log(faces), over all meshes of "
                 "the backend and over the genus-0 series `bunny00`, `bunny00_loop1`, ... alone "
                 "(1 = linear; genus and shape differ between the meshes of the first column, and the loop metric "
                 "depends on the genus rather than on the size).")
    lines.append("")
    slope_table(results, lines)
    with open(args.out, "w") as f:
        f.write("\n".join(lines))
    print(f"benchmark_table: wrote {args.out}")


if __name__ == "__main__":
    main()
