"""The whole of RESULTS.md: the header (machine, versions, dates, the run's steps and times, which sections it wrote),
then every table made from the JSON files in its order (scripts/benchmark_tables/sections.py merges them into the
existing file)."""

import datetime
import os

from .common import BACKENDS, backend_order, machine, pipelines
from .editor import editor_table
from .pipeline import backend_table, floor_table, slope_table
from .placement import placement_table
from .program import controls_table, program_table
from .python_binding import python_table
from .sections import PROSE, has_date_line
from .versions import versions


def results_lines(results, contexts, bindings, editors, command, root=None):
    """the lines of the whole file (header and the sections made from the JSON); `command` is how the numbers
    were made"""
    return header_lines(contexts, command, root) + [""] + section_lines(results, bindings, editors, command)


def fmt_seconds(t):
    t = int(round(t))
    if t < 60:
        return f"{t} s"
    if t < 3600:
        return f"{t // 60} min {t % 60:02d} s"
    return f"{t // 3600} h {t // 60 % 60:02d} min"


def section_name(title):
    """a section's heading without its #s; a backend's table by the backend's name"""
    name = title.lstrip("#").strip()
    backend = name.split(":", 1)[0]
    return f"the {backend} table" if name == f"{backend}: {BACKENDS.get(backend)}" else name


def earlier_runs(old_header):
    """the previous header's bullets on when its tables were measured, as one sentence"""
    parts = []
    for line in old_header:
        for label in ("- **Measured**:", "- **Runs in this file**:"):
            if line.startswith(label):
                parts.append(line[len(label):].strip())
        if line.startswith("- **Earlier runs**"):
            parts.append(line.split("): ", 1)[1] if "): " in line else line[len("- **Earlier runs**"):].strip())
    return " — ".join(parts)


def header_lines(contexts, command, root=None, run=None, status=None, earlier=""):
    """the header of the file: machine, versions, dates; with `run` (scripts/regenerate_results.sh's record: its
    command, start, total and steps) the time of each step; with `status` ([(title, lines, 'new' | 'kept')] and
    `run`'s reasons) which sections this run wrote and which it kept; `earlier`: the previous header's account of
    the runs of the sections kept without a date line of their own"""
    root = root or os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    m = machine()
    dates = sorted({ctx.get("date", "")[:10] for _, ctx in contexts if ctx.get("date")})
    commits = sorted({ctx.get("commit") + (f" (binary built {ctx['built']})" if ctx.get("built") else "")
                      for _, ctx in contexts if ctx.get("commit")})
    now = datetime.datetime.now(datetime.timezone.utc)
    lines = []
    lines.append("# Benchmark results")
    lines.append("")
    if run:
        what = ("no measurement: the tables that the JSON files of earlier runs make, rewritten"
                if run.get("mode") == "tables-only" else
                "every measurement of this file, one step after the other, then `scripts/benchmark_table.py`")
        lines.append(f"Written by `{run['command']}` ({what}), started {run['start']} UTC, "
                     f"**{fmt_seconds(run['total'])}** in all; each section says what it measures "
                     "(`benchmark/Trivial_connections/benchmark_trivial_connections.cpp` for the tables of the suite).")
    else:
        lines.append(f"Written by `scripts/benchmark_table.py` from the JSON of `{command}` "
                     "(see `benchmark/Trivial_connections/benchmark_trivial_connections.cpp` for what is measured).")
    lines.append("")
    lines.append(f"- **Machine**: {m['nproc']} cores, {m['cpu']}, {m['ram']} RAM, Linux {m['kernel']}; "
                 f"BLAS used by CHOLMOD: `{m['blas']}`. The machine was shared with other jobs while measuring.")
    lines.append("- **Versions** (read from the system when this file was written, "
                 f"{now.strftime('%Y-%m-%d %H:%M')} UTC): "
                 + "; ".join(f"{name} {version}" for name, version in versions(root)) + ".")
    if dates or commits:
        lines.append(f"- **Measured** (the suite's JSON files): {', '.join(dates) if dates else 'unknown date'}"
                     + (f", commit {', '.join(commits)}" if commits else "")
                     + f"; table written {now.date().isoformat()}.")
    if run:
        steps = [s for s in run["steps"] if s["status"] != "skipped"]
        lines.append("- **Steps of this run** (wall time): "
                     + "; ".join(f"{s['name']} {fmt_seconds(s['seconds'])}"
                                 + ("" if s["status"] == "done" else f" ({s['status']})") for s in steps)
                     + "." + (" Not run: " + ", ".join(f"{s['name']} ({s['note'] or 'skipped'})"
                                                       for s in run["steps"] if s["status"] == "skipped") + "."
                              if any(s["status"] == "skipped" for s in run["steps"]) else ""))
    if status:
        reasons = (run or {}).get("kept", {})
        new = [section_name(t) for t, _, how in status if how == "new"]
        kept = [(t, lines_) for t, lines_, how in status if how == "kept"]
        lines.append("- **Sections**: " + (f"written in this run: {', '.join(new)}" if new else "none written")
                     + ("; kept as they were (each with its own date line, or see the next line): "
                        + "; ".join(f"{section_name(t)} ({reasons.get(t) or 'no new results for it'})"
                                    for t, _ in kept) if kept else "; none kept from earlier runs") + ".")
        undated = [t for t, lines_ in kept if t not in PROSE and not has_date_line(lines_)]
        if undated and earlier:
            lines.append("- **Earlier runs** (the previous header's words, for the kept sections without a date line "
                         f"of their own: {', '.join(section_name(t) for t in undated)}): {earlier}")
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
    return lines


def section_lines(results, bindings, editors, command):
    """the sections made from the JSON files, in their order"""
    lines = []
    for backend in sorted(results, key=backend_order):
        if pipelines(results[backend]):
            backend_table(backend, results[backend], lines)
    floor_table(results, lines)
    program_table(results, lines)
    controls_table(results, lines)
    placement_table(results, lines, command + " --placement")
    python_table(bindings, lines, command + " --python")
    editor_table(editors, lines, command + " --editor")
    if not any(pipelines(meshes) for meshes in results.values()):
        return lines  # no run of the suite among the JSON files: its slopes stay as they are
    lines.append("### Scaling: log–log slopes")
    lines.append("")
    lines.append("Least-squares slope of log(time) (or log(peak memory)) against log(faces), over all meshes of "
                 "the backend and over the genus-0 series `bunny00`, `bunny00_loop1`, ... alone "
                 "(1 = linear; genus and shape differ between the meshes of the first column, and the loop metric "
                 "depends on the genus rather than on the size).")
    lines.append("")
    slope_table(results, lines)
    return lines
