"""The whole of RESULTS.md: the header (machine, dates, what is measured), then every table in its order."""

import datetime

from .common import backend_order, machine, pipelines
from .editor import editor_table
from .pipeline import backend_table, floor_table, slope_table
from .placement import placement_table
from .program import controls_table, program_table
from .python_binding import python_table


def results_lines(results, contexts, bindings, editors, command):
    """the lines of the whole file; `command` is how the numbers were made"""
    m = machine()
    dates = sorted({ctx.get("date", "")[:10] for _, ctx in contexts if ctx.get("date")})
    commits = sorted({ctx.get("commit") + (f" (binary built {ctx['built']})" if ctx.get("built") else "")
                      for _, ctx in contexts if ctx.get("commit")})
    lines = []
    lines.append("# Benchmark results")
    lines.append("")
    lines.append(f"Written by `scripts/benchmark_table.py` from the JSON of `{command}` "
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
    placement_table(results, lines, command + " --placement")
    python_table(bindings, lines, command + " --python")
    editor_table(editors, lines, command + " --editor")
    lines.append("### Scaling: log–log slopes")
    lines.append("")
    lines.append("Least-squares slope of log(time) (or log(peak memory)) against log(faces), over all meshes of "
                 "the backend and over the genus-0 series `bunny00`, `bunny00_loop1`, ... alone "
                 "(1 = linear; genus and shape differ between the meshes of the first column, and the loop metric "
                 "depends on the genus rather than on the size).")
    lines.append("")
    slope_table(results, lines)
    return lines
