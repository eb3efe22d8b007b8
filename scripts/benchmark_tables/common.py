"""Shared by the tables of benchmark_table.py: backend and phase names, number formats, orders, the machine."""

import math
import os
import platform


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


def table_head(lines, head):
    """the heading and alignment rows of a table whose first two columns (mesh, backend) are text"""
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---", "---"] + ["---:"] * (len(head) - 2)) + "|")


def error_row(mesh, backend, head, error):
    """the row of a mesh whose run failed: a dash in each column, its error in the last"""
    return f"| {mesh} | {backend} | " + " | ".join(["–"] * (len(head) - 3)) + f" | error: {error} |"
